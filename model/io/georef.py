"""Georeferenced rasters: GeoTIFF and image + world file, their transform and CRS (docs/gdal.md, ADR 0016).

MR Modeler works in **grid coordinates**: pixel (x, y) is centred on the point (x, y), y up (DESIGN §1). A
raster of H rows whose GDAL affine transform is ``T`` (``X = a·col + b·row + c``, ``Y = d·col + e·row + f``,
with (col, row) = (0, 0) the top-left corner of the top-left pixel) is read with its bottom-left pixel at
(0, 0), so grid point (u, v) is the raster position (col, row) = (u + ½, H − ½ − v) and the world point

    (X, Y) = T · (u + ½, H − ½ − v).

In GDAL's words: the grid coordinates of an unreferenced image with origin (x0, y0) *are* world coordinates
under ``from_origin(x0 − ½, y0 + H − ½, 1, 1)``. :class:`GeoRef` holds ``T``, the raster's size and its CRS,
and maps geometries both ways (:meth:`GeoRef.to_world`, :meth:`GeoRef.to_grid`); an affine map carries
every exactness statement over (D and R commute with it as long as it is the raster's own grid).

Formats:

``.tif`` / ``.tiff``
    GeoTIFF through rasterio (the ``geo`` extra: ``pip install 'mr-modeler[geo]'``). Band 1 is read;
    non-zero samples (or those brighter than ``threshold``) are in the set, ``nodata`` samples never are.
    Written as one uint8 band (0/1) covering the georeference's whole frame, with its transform and CRS.
``.png`` / ``.pgm`` / ``.pbm`` + world file
    A world file beside the image (``name.pgw``, ``name.pngw``, ``name.wld``, …: six lines A D B E C F, where
    C, F is the *centre* of the top-left pixel) gives the transform, and ``name.prj`` (WKT) the CRS. No
    rasterio needed.
"""

from __future__ import annotations

import json
import logging
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeAlias

import numpy as np

from mrm.errors import DEFAULT_PIXEL_LIMIT, FileFormatError, ParameterError, SizeLimitError
from mrm.reps.pixels import PixelSet

log = logging.getLogger(__name__)

PathLike = str | os.PathLike[str]

#: Extensions of GeoTIFF files.
GEOTIFF_EXTENSIONS = (".tif", ".tiff")
#: Image extensions a world file may accompany, and the world file extensions tried for each (in order).
WORLD_FILE_EXTENSIONS = {
    ".png": (".pgw", ".pngw", ".wld"),
    ".pgm": (".pgmw", ".wld"),
    ".pbm": (".pbmw", ".wld"),
    ".tif": (".tfw", ".tifw", ".wld"),
    ".tiff": (".tfw", ".tiffw", ".wld"),
}
#: A geometry covering fewer pixels than this gets a warning (wrong units? a polygon in degrees?).
FEW_PIXELS = 5

#: (a, b, c, d, e, f) of GDAL's / rasterio's ``Affine``.
Transform: TypeAlias = tuple[float, float, float, float, float, float]


def _rasterio() -> Any:
    try:
        import rasterio
    except ImportError:  # pragma: no cover - depends on the install
        raise FileFormatError(
            "GeoTIFF needs the geo extra: pip install 'mr-modeler[geo]' (it installs rasterio)"
        ) from None
    return rasterio


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
    """

    transform: Transform
    width: int
    height: int
    crs: str | None = None

    def __post_init__(self) -> None:
        a, b, _c, d, e, _f = self.transform
        if not all(math.isfinite(v) for v in self.transform) or a * e - b * d == 0:
            raise FileFormatError(f"the raster's transform {self.transform} is not invertible")
        if self.width < 1 or self.height < 1:
            raise FileFormatError(f"a raster of {self.width}×{self.height} pixels holds nothing")

    # ------------------------------------------------------------------ maps
    def grid_to_world(self) -> list[float]:
        """The map (u, v) ↦ (X, Y) as shapely's ``affine_transform`` matrix [a, b, d, e, xoff, yoff]."""
        a, b, c, d, e, f = self.transform
        h = self.height
        # (X, Y) = T · (u + ½, H − ½ − v)
        return [a, -b, d, -e, a * 0.5 + b * (h - 0.5) + c, d * 0.5 + e * (h - 0.5) + f]

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

    def to_grid(self, geom: Any) -> Any:
        """A geometry in world coordinates, mapped to grid coordinates."""
        from shapely.affinity import affine_transform

        return affine_transform(geom, self.world_to_grid())

    @property
    def frame(self) -> tuple[int, int, int, int]:
        """The box of the raster's pixels in grid coordinates: (0, 0, width − 1, height − 1)."""
        return (0, 0, self.width - 1, self.height - 1)

    @property
    def pixel_area(self) -> float:
        """The area of one pixel in world units."""
        a, b, _c, d, e, _f = self.transform
        return abs(a * e - b * d)

    def as_dict(self) -> dict[str, Any]:
        """JSON form: ``transform``, ``width``, ``height``, ``crs``."""
        return {
            "transform": list(self.transform),
            "width": self.width,
            "height": self.height,
            "crs": self.crs,
        }

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


# ---------------------------------------------------------------------------------------------- CRS
def _crs_text(crs: Any) -> str | None:
    """``EPSG:n`` when the CRS has a code, else its WKT (None for no CRS)."""
    if crs is None:
        return None
    epsg = crs.to_epsg()
    return f"EPSG:{epsg}" if epsg is not None else str(crs.to_wkt())


def geojson_crs_member(crs: str | None) -> dict[str, Any] | None:
    """The (pre-RFC 7946) ``crs`` member GDAL and QGIS read, e.g. ``urn:ogc:def:crs:EPSG::32633``.

    None for no CRS, or a CRS without an EPSG code (GDAL would then assume EPSG:4326; see docs/gdal.md).
    """
    if crs is None or not crs.upper().startswith("EPSG:"):
        return None
    return {"type": "name", "properties": {"name": f"urn:ogc:def:crs:EPSG::{crs.split(':', 1)[1]}"}}


def read_geojson_crs(path: PathLike) -> str | None:
    """The CRS a GeoJSON file names in its ``crs`` member (``EPSG:n``), or None."""
    try:
        with open(path, "rb") as fh:
            doc = json.loads(fh.read(1 << 27))
    except (ValueError, RecursionError):
        return None  # the vector reader reports a malformed file
    crs = doc.get("crs") if isinstance(doc, dict) else None
    name = crs.get("properties", {}).get("name") if isinstance(crs, dict) else None
    if not isinstance(name, str):
        return None
    code = name.rsplit(":", 1)[-1]
    if "EPSG" in name.upper() and code.isdigit():
        return f"EPSG:{code}"
    return name


def same_crs(a: str | None, b: str | None) -> bool:
    """Whether two CRS texts name the same system (EPSG codes compared; WKT through rasterio if present)."""
    if a is None or b is None or a == b:
        return a == b
    try:
        rasterio = _rasterio()
        return bool(rasterio.crs.CRS.from_user_input(a) == rasterio.crs.CRS.from_user_input(b))
    except Exception:  # unparsable CRS text: only equal texts are the same
        return False


# ---------------------------------------------------------------------------------------------- world files
def world_file_of(path: PathLike) -> Path | None:
    """The world file beside ``path`` (``name.pgw`` for ``name.png``, …), or None."""
    p = Path(path)
    for ext in WORLD_FILE_EXTENSIONS.get(p.suffix.lower(), ()):
        for candidate in (p.with_suffix(ext), p.with_suffix(ext.upper())):
            if candidate.is_file():
                return candidate
    return None


def parse_world_file(text: str, name: str) -> tuple[float, float, float, float, float, float]:
    """Parse a world file into GDAL's (a, b, c, d, e, f); it holds A D B E C F, C/F at a pixel's centre."""
    try:
        vals = [float(v) for v in text.split()]
    except ValueError:
        raise FileFormatError(f"{name}: a world file holds six numbers") from None
    if len(vals) != 6 or not all(math.isfinite(v) for v in vals):
        raise FileFormatError(f"{name}: a world file holds six finite numbers, found {len(vals)}")
    a, d, b, e, c, f = vals
    # C, F: the centre of the top-left pixel; GDAL's c, f: its top-left corner.
    return (a, b, c - 0.5 * a - 0.5 * b, d, e, f - 0.5 * d - 0.5 * e)


def world_file_text(transform: Transform) -> str:
    """The six lines of a world file (A D B E C F) for GDAL's transform, written with ``repr``."""
    a, b, c, d, e, f = transform
    return (
        "\n".join(repr(float(v)) for v in (a, d, b, e, c + 0.5 * a + 0.5 * b, f + 0.5 * d + 0.5 * e)) + "\n"
    )


def _image_size(path: PathLike) -> tuple[int, int]:
    from PIL import Image

    with Image.open(path) as im:  # the header only
        return int(im.size[0]), int(im.size[1])


def read_georef(path: PathLike) -> GeoRef | None:
    """The georeference of a raster: a GeoTIFF's own, or an image's world file (+ ``.prj``); else None."""
    p = Path(path)
    if p.suffix.lower() in GEOTIFF_EXTENSIONS:
        rasterio = _rasterio()
        try:
            with rasterio.open(p) as ds:
                t = ds.transform
                if ds.transform.is_identity and world_file_of(p) is None:
                    return None  # a plain TIFF without georeference
                return GeoRef((t.a, t.b, t.c, t.d, t.e, t.f), ds.width, ds.height, _crs_text(ds.crs))
        except rasterio.errors.RasterioIOError as e:
            raise FileFormatError(f"{p.name}: not a readable GeoTIFF ({e})") from None
    wf = world_file_of(p)
    if wf is None:
        return None
    transform = parse_world_file(wf.read_text(encoding="ascii", errors="replace"), wf.name)
    width, height = _image_size(p)
    prj = p.with_suffix(".prj")
    crs = prj.read_text(encoding="utf-8", errors="replace").strip() if prj.is_file() else None
    if crs:
        try:
            crs = _crs_text(_rasterio().crs.CRS.from_wkt(crs))
        except Exception:  # no rasterio, or a WKT it cannot parse: keep the text as it is
            log.debug("kept the .prj text of %s as it is", p.name)
    return GeoRef(transform, width, height, crs or None)


def write_world_file(path: PathLike, georef: GeoRef) -> Path:
    """Write the world file (and ``.prj`` for a CRS) beside the image ``path``; returns the world file."""
    from mrm.io.atomic import atomic_write_text

    p = Path(path)
    wf = p.with_suffix(WORLD_FILE_EXTENSIONS.get(p.suffix.lower(), (".wld",))[0])
    atomic_write_text(wf, world_file_text(georef.transform))
    if georef.crs is not None:
        text = georef.crs
        try:
            text = _rasterio().crs.CRS.from_user_input(georef.crs).to_wkt()
        except Exception:  # no rasterio: EPSG codes are written as they are
            log.debug("wrote the CRS of %s as text", p.name)
        atomic_write_text(p.with_suffix(".prj"), text + "\n")
    return wf


# ---------------------------------------------------------------------------------------------- GeoTIFF
def read_raster(
    path: PathLike,
    *,
    threshold: float | None = None,
    limit: int = DEFAULT_PIXEL_LIMIT,
) -> tuple[PixelSet, GeoRef | None]:
    """Read band 1 of a GeoTIFF as a pixel set (bottom-left pixel at (0, 0)) and its georeference.

    Parameters
    ----------
    path : str or path-like
    threshold : float, optional
        Samples greater than it are in the set; by default every non-zero sample is.
    limit : int
        Rasters with more pixels are refused from their header.

    Returns
    -------
    pixels : PixelSet
    georef : GeoRef or None
        None for a TIFF without georeference.
    """
    from mrm.io.threshold import binarize

    rasterio = _rasterio()
    name = Path(path).name
    try:
        with rasterio.open(path) as ds:
            if ds.width * ds.height > limit:
                raise SizeLimitError(ds.width * ds.height, limit, f"{name}: the raster")
            band = ds.read(1)
            nodata = ds.nodata
    except rasterio.errors.RasterioIOError as e:
        raise FileFormatError(f"{name}: not a readable GeoTIFF ({e})") from None
    valid = np.ones(band.shape, dtype=bool) if nodata is None else band != nodata
    if band.dtype.kind == "f":
        valid &= np.isfinite(band)
        rows = (band > (0.0 if threshold is None else threshold)) & valid
    elif threshold is None:
        rows = (band != 0) & valid
    else:
        grey = np.where(valid, band, 0).astype(np.int64)
        rows = binarize(np.clip(grey, 0, None), threshold) & valid
    return PixelSet(rows[::-1], (0, 0)), read_georef(path)


def write_raster(ps: PixelSet, path: PathLike, georef: GeoRef) -> None:
    """Write the pixels of ``georef``'s frame as a one-band uint8 GeoTIFF (1 = in the set), atomically."""
    rasterio = _rasterio()
    from mrm.io.atomic import atomic_open

    image = ps.to_image(georef.frame).astype(np.uint8)
    profile = {
        "driver": "GTiff",
        "width": georef.width,
        "height": georef.height,
        "count": 1,
        "dtype": "uint8",
        "transform": rasterio.Affine(*georef.transform),
        "crs": georef.crs,
        "compress": "deflate",
        "nbits": 1,
    }
    with rasterio.io.MemoryFile() as mem:
        with mem.open(**profile) as ds:
            ds.write(image, 1)
        data = mem.read()
    with atomic_open(path, "wb") as fh:
        fh.write(data)


def few_pixels_warning(ps: PixelSet, geom: Any, what: str) -> str | None:
    """A warning when a geometry with area covers fewer than :data:`FEW_PIXELS` pixels, else None."""
    if len(ps) >= FEW_PIXELS or getattr(geom, "is_empty", True):
        return None
    return (
        f"{what} covers only {len(ps)} pixel{'s' if len(ps) != 1 else ''}: are its coordinates in other "
        "units than the pixel grid (degrees?)? Give --resolution (world units per pixel) or --like RASTER"
    )


def unit_grid(ps: PixelSet) -> GeoRef:
    """The georeference under which grid coordinates are world coordinates.

    GDAL's ``from_origin(x0 − ½, y0 + H − ½, 1, 1)`` over the set's bounding box (one pixel at (0, 0) for
    the empty set).
    """
    (x0, y0), (h, w) = ps.origin, ps.shape
    h, w = max(h, 1), max(w, 1)
    return GeoRef((1.0, 0.0, x0 - 0.5, 0.0, -1.0, y0 + h - 0.5), w, h)


def grid_origin(georef: GeoRef | None) -> tuple[int, int]:
    """The origin a raster's bottom-left pixel gets.

    (x0, y0) for a unit grid written by :func:`unit_grid`, so that such files read back in place; (0, 0)
    for any other georeference.
    """
    if georef is None:
        return (0, 0)
    a, b, c, d, e, f = georef.transform
    x0, y0 = c + 0.5, f + 0.5 - georef.height
    if (a, b, d, e) == (1.0, 0.0, 0.0, -1.0) and x0.is_integer() and y0.is_integer():
        return int(x0), int(y0)
    return (0, 0)


def read_pixels_tif(
    path: PathLike, *, threshold: float | None = None, limit: int = DEFAULT_PIXEL_LIMIT
) -> PixelSet:
    """:func:`mrm.io.pixel_files.read_pixels` for a GeoTIFF: band 1, placed by :func:`grid_origin`."""
    ps, georef = read_raster(path, threshold=threshold, limit=limit)
    dx, dy = grid_origin(georef)
    return ps.translate(dx, dy) if (dx, dy) != (0, 0) else ps


def write_pixels_tif(ps: PixelSet, path: PathLike) -> None:
    """:func:`mrm.io.pixel_files.write_pixels` for a GeoTIFF: the bounding box on its :func:`unit_grid`."""
    # The grid's pixel (0, 0) is the set's origin (x0, y0): unit_grid maps it to the world point (x0, y0).
    x0, y0 = ps.origin
    write_raster(ps.translate(-x0, -y0), path, unit_grid(ps))
