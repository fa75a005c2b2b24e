"""Where a raster lies on the Earth: its affine transform, its size and its CRS (docs/gdal.md, ADR 0021).

MR Modeler works in **grid coordinates**: pixel (x, y) is centred on the point (x, y), y up (docs/design.md
§1). A raster of H rows whose GDAL affine transform is ``T`` (``X = a·col + b·row + c``, ``Y = d·col + e·row +
f``, with (col, row) = (0, 0) the top-left corner of the top-left pixel) is read with its bottom-left pixel at
(0, 0), so grid point (u, v) is the raster position (col, row) = (u + ½, H − ½ − v). A :class:`GeoRef` is a
value an object carries (ADR 0021); reading and writing georeferenced files is :mod:`mrm.io.georef`'s.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, TypeAlias

import numpy as np
import numpy.typing as npt

from mrm.core.errors import FileFormatError, ParameterError
from mrm.core.grids import PixelSet
from mrm.core.limits import check_crs_text, check_transform

__all__ = ["GeoRef", "Transform", "grid_origin", "unit_grid"]

#: (a, b, c, d, e, f) of GDAL's / rasterio's ``Affine``.
Transform: TypeAlias = tuple[float, float, float, float, float, float]


@dataclass(frozen=True)
class GeoRef:
    """Where a raster lies on the Earth: its affine transform, its size and its CRS.

    Attributes
    ----------
    transform : tuple of 6 float
        GDAL's affine (a, b, c, d, e, f): world X = a·col + b·row + c, Y = d·col + e·row + f.
    width, height : int
        The raster's size in pixels.
    crs : str or None
        The coordinate reference system as ``EPSG:n`` when it has a code, else WKT; None when unknown.
    origin : (int, int)
        The grid coordinates of the raster's bottom-left pixel: (0, 0) for a raster as it is read, (x0, y0)
        for a unit grid read back in place (:func:`grid_origin`), anything for an object's grid after an edit
        (:meth:`covering`, :meth:`scaled`).
    """

    transform: Transform
    width: int
    height: int
    crs: str | None = None
    origin: tuple[int, int] = (0, 0)

    def __post_init__(self) -> None:
        if len(self.transform) != 6 or not all(
            isinstance(v, int | float) and not isinstance(v, bool) for v in self.transform
        ):
            raise FileFormatError(f"a raster's transform is six numbers, got {self.transform!r}")
        object.__setattr__(self, "transform", tuple(float(v) for v in self.transform))
        a, b, _c, d, e, _f = self.transform
        if not all(math.isfinite(v) for v in self.transform) or a * e - b * d == 0:
            raise FileFormatError(f"the raster's transform {self.transform} is not invertible")
        # One set of limits for import, operations and the project loader (ADR 0047): what imports reopens.
        check_transform(self.transform, tuple(self.grid_to_world()))  # an overflow (inf) is refused there
        for v in (self.width, self.height, *self.origin):
            if isinstance(v, bool) or not isinstance(v, int | np.integer):
                raise FileFormatError(f"a raster's size and origin are integers, got {v!r}")
        if self.width < 1 or self.height < 1:
            raise FileFormatError(f"a raster of {self.width}×{self.height} pixels holds nothing")
        if len(self.origin) != 2:
            raise FileFormatError(f"a raster's origin is (x0, y0), got {self.origin!r}")
        object.__setattr__(self, "origin", (int(self.origin[0]), int(self.origin[1])))
        if self.crs is not None and not isinstance(self.crs, str):
            raise FileFormatError(f"a CRS is given as text (EPSG:n or WKT), got {type(self.crs).__name__}")
        if self.crs is not None:
            check_crs_text(self.crs)

    # ------------------------------------------------------------------ maps
    def grid_to_world(self) -> list[float]:
        """The map (u, v) ↦ (X, Y) as shapely's ``affine_transform`` matrix [a, b, d, e, xoff, yoff]."""
        a, b, c, d, e, f = self.transform
        h = self.height
        x0, y0 = self.origin
        # (X, Y) = T · (u − x0 + ½, H − ½ − (v − y0))
        cu, rv = 0.5 - x0, h - 0.5 + y0
        return [a, -b, d, -e, a * cu + b * rv + c, d * cu + e * rv + f]

    def world_to_grid(self) -> list[float]:
        """The inverse map (X, Y) ↦ (u, v), as shapely's ``affine_transform`` matrix."""
        a, b, d, e, xo, yo = self.grid_to_world()
        det = a * e - b * d
        ia, ib, id_, ie = e / det, -b / det, -d / det, a / det
        return [ia, ib, id_, ie, -(ia * xo + ib * yo), -(id_ * xo + ie * yo)]

    def to_world(self, geom: Any) -> Any:
        """A geometry in grid coordinates, mapped to the raster's world coordinates."""
        from shapely.affinity import affine_transform

        return affine_transform(geom, self.grid_to_world())

    def raster_to_world(self, geom: Any) -> Any:
        """A geometry in grid coordinates, mapped to world coordinates in GDAL's order of operations.

        Each point goes to the raster position (col, row) = (u − x0 + ½, H − ½ − (v − y0)), exact for the
        half-integer corners of pixels, then to ``X = c + a·col + b·row``, ``Y = f + d·col + e·row`` in the
        order GDAL's polygonize computes them, so a pixel corner lands on the very float that
        ``rasterio.features.shapes`` / ``gdal_polygonize`` give it. :meth:`to_world` composes the two maps
        first (one rounding less for points off the corners, another float for the corners).
        """
        import shapely

        a, b, c, d, e, f = self.transform
        x0, y0 = self.origin
        h = self.height

        def place(xy: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
            col = xy[:, 0] - x0 + 0.5
            row = (h - 0.5 + y0) - xy[:, 1]
            out: npt.NDArray[np.float64] = np.column_stack((c + col * a + row * b, f + col * d + row * e))
            return out

        return shapely.transform(geom, place)

    def to_grid(self, geom: Any) -> Any:
        """A geometry in world coordinates, mapped to grid coordinates."""
        from shapely.affinity import affine_transform

        return affine_transform(geom, self.world_to_grid())

    @property
    def frame(self) -> tuple[int, int, int, int]:
        """The box of the raster's pixels in grid coordinates: (x0, y0, x0 + width − 1, y0 + height − 1)."""
        x0, y0 = self.origin
        return (x0, y0, x0 + self.width - 1, y0 + self.height - 1)

    def as_dict(self) -> dict[str, Any]:
        """JSON form: ``transform``, ``width``, ``height``, ``crs``, ``origin`` (what project files store)."""
        return {
            "transform": list(self.transform),
            "width": self.width,
            "height": self.height,
            "crs": self.crs,
            "origin": list(self.origin),
        }

    # ------------------------------------------------------------------ other frames of the same map
    def covering(self, box: tuple[int, int, int, int] | None) -> GeoRef:
        """The same grid-to-world map on a frame grown to hold ``box`` (grid pixels xmin, ymin, xmax, ymax).

        An object edited or rotated on its raster's grid may leave the raster's frame; exporting it on this
        frame keeps every pixel, and GDAL still reads each pixel where the map puts it. The frame only grows
        by whole pixels, so the new corner is the old one moved by whole pixel steps (exact for the usual
        power-of-two or integer pixel sizes). Returns ``self`` when the frame already holds ``box``.
        """
        fx0, fy0, fx1, fy1 = self.frame
        if box is None or (box[0] >= fx0 and box[1] >= fy0 and box[2] <= fx1 and box[3] <= fy1):
            return self
        nx0, ny0 = min(fx0, box[0]), min(fy0, box[1])
        nx1, ny1 = max(fx1, box[2]), max(fy1, box[3])
        a, b, c, d, e, f = self.transform
        dcol, drow = nx0 - fx0, fy1 - ny1  # the new top-left pixel, in the old raster's (col, row)
        return GeoRef(
            (a, b, c + a * dcol + b * drow, d, e, f + d * dcol + e * drow),
            nx1 - nx0 + 1,
            ny1 - ny0 + 1,
            self.crs,
            (nx0, ny0),
        )

    def scaled(self, ratio: Fraction, offset: tuple[Fraction, Fraction]) -> GeoRef:
        """The georeference of a result made on this grid by the scaling ``u′ = ratio·u + offset`` (ADR 0021).

        DSS_α scales by α about its centre C (``offset = (1 − α)·C``): the result's grid point u′ stands for
        the world point of u, so the new map is ``grid_to_world ∘ (u′ ↦ (u′ − offset)/ratio)``: pixels α times
        smaller, the world outline where the input's was. The map is rounded to float64 once (exact for α a
        power of two); the frame is the pixels whose centres lie in the scaled frame.
        """
        q = Fraction(ratio)
        if q <= 0:
            raise ParameterError(f"a scaling factor is positive, got {q}")
        tx, ty = Fraction(offset[0]), Fraction(offset[1])
        A, B, D, E, XO, YO = self.grid_to_world()
        fi = float(1 / q)
        kx, ky = float(-tx / q), float(-ty / q)  # u = u′/ratio − offset/ratio
        m = [A * fi, B * fi, D * fi, E * fi, XO + A * kx + B * ky, YO + D * kx + E * ky]
        fx0, fy0, fx1, fy1 = self.frame

        def span(lo: int, hi: int, t: Fraction) -> tuple[int, int]:
            a0 = math.ceil(q * (Fraction(lo) - Fraction(1, 2)) + t)
            a1 = math.floor(q * (Fraction(hi) + Fraction(1, 2)) + t)
            return a0, max(a0, a1)

        (nx0, nx1), (ny0, ny1) = span(fx0, fx1, tx), span(fy0, fy1, ty)
        return GeoRef.from_grid_map(m, (nx0, ny0, nx1, ny1), self.crs)

    @classmethod
    def from_grid_map(cls, m: Sequence[float], frame: tuple[int, int, int, int], crs: str | None) -> GeoRef:
        """The georeference with grid-to-world map ``m`` (shapely's [a, b, d, e, xoff, yoff]) on ``frame``."""
        A, B, D, E, XO, YO = (float(v) for v in m)
        x0, y0, x1, y1 = frame
        h = y1 - y0 + 1
        # u = col + x0 − ½, v = H − ½ − row + y0
        cu, rv = x0 - 0.5, h - 0.5 + y0
        return cls((A, -B, A * cu + B * rv + XO, D, -E, D * cu + E * rv + YO), x1 - x0 + 1, h, crs, (x0, y0))

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_resolution(
        cls,
        resolution: float,
        extent: tuple[float, float, float, float],
        crs: str | None = None,
    ) -> GeoRef:
        """A north-up grid of square pixels of ``resolution`` world units covering ``extent``.

        Parameters
        ----------
        resolution : float
            The side of a pixel, > 0.
        extent : (xmin, ymin, xmax, ymax)
            The world box to cover; the grid starts at (xmin, ymax) and has ⌈width / resolution⌉ columns.
        """
        if not (math.isfinite(resolution) and resolution > 0):
            raise ParameterError(f"--resolution must be a positive number, got {resolution}")
        xmin, ymin, xmax, ymax = extent
        if not all(math.isfinite(v) for v in extent) or xmax <= xmin or ymax <= ymin:
            raise ParameterError(f"the extent {extent} is empty or not finite")
        w = max(1, math.ceil((xmax - xmin) / resolution - 1e-9))
        h = max(1, math.ceil((ymax - ymin) / resolution - 1e-9))
        return cls((resolution, 0.0, xmin, 0.0, -resolution, ymax), w, h, crs)


def unit_grid(ps: PixelSet) -> GeoRef:
    """The georeference under which grid coordinates are world coordinates.

    GDAL's ``from_origin(x0 − ½, y0 + H − ½, 1, 1)`` over the set's bounding box (one pixel at (0, 0) for the
    empty set).
    """
    (x0, y0), (h, w) = ps.origin, ps.shape
    h, w = max(h, 1), max(w, 1)
    return GeoRef((1.0, 0.0, x0 - 0.5, 0.0, -1.0, y0 + h - 0.5), w, h)


def grid_origin(georef: GeoRef | None) -> tuple[int, int]:
    """The origin a raster's bottom-left pixel gets.

    (x0, y0) for a unit grid written by :func:`unit_grid`, so that such files read back in place; (0, 0) for
    any other georeference.
    """
    if georef is None:
        return (0, 0)
    a, b, c, d, e, f = georef.transform
    x0, y0 = c + 0.5, f + 0.5 - georef.height
    if (a, b, d, e) == (1.0, 0.0, 0.0, -1.0) and x0.is_integer() and y0.is_integer():
        return int(x0), int(y0)
    return (0, 0)
