"""The values a document holds: objects, their styles and settings, and the checks every source passes.

An object (:class:`DocObject`) is an immutable value: an id, a name, a :class:`Style`, an optional
:class:`~mrm.ops.provenance.Provenance`, an optional georeference, and its **source** — a Euclidean geometry
(shapely Polygon / MultiPolygon, always valid), a discrete :class:`~mrm.core.grids.PixelSet` or a label map.
Every check of a source against the limits of :mod:`mrm.core.limits` happens when the value is made.
"""

from __future__ import annotations

import re
import sys
import threading
import weakref
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Literal, TypeAlias, TypeGuard

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from mrm.core import limits
from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.georef import GeoRef
from mrm.core.grids import GridSet, LabelGrid, LabelMap, LabelVolume, PixelSet, VoxelSet
from mrm.core.limits import COORDINATE_LIMIT
from mrm.core.models import DEFAULT_MODEL, Model
from mrm.ops.provenance import Provenance

if TYPE_CHECKING:
    from mrm.geometry.polyhedra import Polyhedron

#: A Euclidean source: a valid shapely Polygon or MultiPolygon (possibly empty).
Geometry: TypeAlias = Polygon | MultiPolygon
#: What an object's source can be: pixels, polygons, or a label map (ADR 0033); voxels or a label volume in 3D
#: (docs/design.md §11).
Source: TypeAlias = "PixelSet | Polygon | MultiPolygon | LabelMap | VoxelSet | LabelVolume | Polyhedron"
SourceKind = Literal["euclidean", "discrete", "labels"]


def is_polyhedron(value: object) -> TypeGuard[Polyhedron]:
    """True for a :class:`~mrm.geometry.polyhedra.Polyhedron`, without importing its module.

    The polyhedra's module loads a dozen compiled kernels; a document of plane objects (the desktop's first
    paint) must not pay for them. No value can be a polyhedron before that module is loaded.
    """
    module = sys.modules.get("mrm.geometry.polyhedra.polyhedron")
    return module is not None and isinstance(value, module.Polyhedron)


_COLOR_RE = re.compile(r"^#[0-9a-fA-F]{6}([0-9a-fA-F]{2})?$")

#: Fill colours given to new objects in turn (a colour-blind-safe palette).
PALETTE = ("#4c72b0", "#dd8452", "#55a868", "#c44e52", "#8172b3", "#937860", "#da8bc3", "#8c8c8c")


# ---------------------------------------------------------------------------------------------- geometry
_VALIDATED: weakref.WeakValueDictionary[int, Any] = weakref.WeakValueDictionary()
_VALIDATED_LOCK = threading.Lock()


def validate_geometry(geom: object) -> Geometry:
    """Return ``geom`` if it can be a Euclidean source, else raise :class:`InvalidGeometryError`.

    A Euclidean source is a 2-D shapely Polygon or MultiPolygon, valid in the OGC sense (docs/design.md §6),
    with finite coordinates of magnitude at most :data:`COORDINATE_LIMIT`. An empty geometry of any type
    becomes the empty Polygon. Coordinates are never altered.
    """
    if not isinstance(geom, shapely.Geometry):
        raise InvalidGeometryError(f"expected a polygon, got {type(geom).__name__}")
    with _VALIDATED_LOCK:
        if _VALIDATED.get(id(geom)) is geom:
            return geom
    if geom.is_empty:
        return Polygon()
    if not isinstance(geom, Polygon | MultiPolygon):
        raise InvalidGeometryError(f"an object's Euclidean shape must be a polygon, got a {geom.geom_type}")
    if shapely.has_z(geom):
        raise InvalidGeometryError("the polygon has 3-D coordinates; only plane (x, y) coordinates are used")
    coords = shapely.get_coordinates(geom)
    if not np.isfinite(coords).all():
        raise InvalidGeometryError("the polygon has NaN or infinite coordinates")
    if coords.size and float(np.abs(coords).max()) > COORDINATE_LIMIT:
        raise InvalidGeometryError(
            f"the polygon has a coordinate of magnitude {float(np.abs(coords).max()):.3g}, "
            f"beyond the limit of {COORDINATE_LIMIT:.0f}"
        )
    if not shapely.is_valid(geom):
        raise InvalidGeometryError(f"invalid polygon: {shapely.is_valid_reason(geom)}")
    with _VALIDATED_LOCK:
        _VALIDATED[id(geom)] = geom
    return geom


def _source_cost(source: Source) -> tuple[int, int]:
    """(pixels of the mask box, bytes in a file) of a source; refuses one beyond the per-object limits."""
    if isinstance(source, GridSet):
        limits.check_pixel_extent(source.origin, source.shape, f"the {source.unit} object")
        n = int(source.mask.size)
        return n, limits.source_file_bytes("discrete", pixels=n)
    if isinstance(source, LabelGrid):
        flat = source.set_type.ndim == 2
        label_limit = limits.MAX_LABEL_PIXELS if flat else limits.MAX_LABEL_VOXELS
        limits.check_pixel_extent(source.origin, source.shape, f"the {source.what}", limit=label_limit)
        n = int(source.labels.size)
        return limits.LABEL_WEIGHT * n, limits.source_file_bytes("labels", pixels=n)
    if is_polyhedron(source):
        # validated, and its triangles bounded, when it was made; here its share of a file: 3 floats a
        # vertex, 3 integers a triangle
        n = source.n_vertices
        limits.check_vertices(n, "the polyhedron object")
        return 0, limits.source_file_bytes("euclidean", coordinates=2 * n + source.n_triangles, rings=0)
    n = int(shapely.get_num_coordinates(source))
    limits.check_vertices(n, "the polygon object")
    parts = shapely.get_parts(source)
    rings = int(parts.size + shapely.get_num_interior_rings(parts).sum()) if parts.size else 0
    return 0, limits.source_file_bytes("euclidean", coordinates=n, rings=rings)


def source_kind(source: Source) -> SourceKind:
    """'discrete' for a pixel or voxel set, 'euclidean' for a geometry, 'labels' for a label map or volume."""
    if isinstance(source, GridSet):
        return "discrete"
    return "labels" if isinstance(source, LabelGrid) else "euclidean"


def source_dimension(source: Source) -> int:
    """2 for pixels, label maps and polygons; 3 for voxels, label volumes and polyhedra."""
    if isinstance(source, GridSet):
        return source.ndim
    if isinstance(source, LabelGrid):
        return source.set_type.ndim
    return 3 if is_polyhedron(source) else 2


def validate_source(source: object) -> Source:
    """Return ``source`` checked: a pixel set, a label map, or a geometry :func:`validate_geometry` takes."""
    if isinstance(source, PixelSet | LabelMap | VoxelSet | LabelVolume) or is_polyhedron(source):
        return source
    return validate_geometry(source)


# ---------------------------------------------------------------------------------------------- values
def _check_color(value: object, what: str) -> str:
    if not isinstance(value, str) or not _COLOR_RE.match(value):
        raise ParameterError(f"{what} must be a colour '#rrggbb' or '#rrggbbaa', got {value!r}")
    return value.lower()


@dataclass(frozen=True)
class Style:
    """How an object is drawn in every view.

    Parameters
    ----------
    fill : str
        Fill colour, ``'#rrggbb'`` or ``'#rrggbbaa'``.
    stroke : str
        Outline colour, same form.
    opacity : float
        Fill opacity in [0, 1].
    stroke_width : float
        Outline width in screen pixels, ≥ 0.
    visible : bool
        Whether the object is drawn at all.
    """

    fill: str = PALETTE[0]
    stroke: str = "#1f2a44"
    opacity: float = 0.6
    stroke_width: float = 1.5
    visible: bool = True

    def __post_init__(self) -> None:
        object.__setattr__(self, "fill", _check_color(self.fill, "fill"))
        object.__setattr__(self, "stroke", _check_color(self.stroke, "stroke"))
        for name, hi in (("opacity", 1.0), ("stroke_width", 100.0)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int | float) or not (0.0 <= float(v) <= hi):
                raise ParameterError(f"{name} must be a number in [0, {hi:g}], got {v!r}")
            object.__setattr__(self, name, float(v) + 0.0)  # + 0.0 turns -0.0 into 0.0
        if not isinstance(self.visible, bool):
            raise ParameterError(f"visible must be true or false, got {self.visible!r}")

    @classmethod
    def for_index(cls, i: int) -> Style:
        """A default style whose fill colour cycles through :data:`PALETTE`."""
        return cls(fill=PALETTE[i % len(PALETTE)])


@dataclass(frozen=True, eq=True)
class DocObject:
    """One object of a document: an immutable value (edits make new objects).

    Parameters
    ----------
    id : int
        Unique within the document, never reused (an undo may bring a removed object back).
    name : str
        Shown in the object list; need not be unique.
    source : PixelSet or Polygon or MultiPolygon
        The source representation (docs/design.md §7).
    style : Style
        How it is drawn.
    provenance : Provenance or None
        The operation that produced it, if any.
    georef : GeoRef or None
        Where its grid lies on the Earth (the affine transform and CRS of the raster it came from, or of
        its inputs' grid: :func:`mrm.io.georef.result_georef`); None for a plain grid (ADR 0016, 0021).
    """

    id: int
    name: str
    source: Source
    style: Style = field(default_factory=Style)
    provenance: Provenance | None = None
    georef: GeoRef | None = None

    __hash__ = None  # type: ignore[assignment]  # a value with a dict inside; compare, don't hash

    def __post_init__(self) -> None:
        if isinstance(self.id, bool) or not isinstance(self.id, int) or not 1 <= self.id <= limits.MAX_ID:
            raise ParameterError(f"object ids are integers in [1, 2^53], got {self.id!r}")
        if not isinstance(self.name, str):
            raise ParameterError(f"an object name must be text, got {type(self.name).__name__}")
        limits.check_name(self.name)
        object.__setattr__(self, "source", validate_source(self.source))
        if not isinstance(self.style, Style):
            raise ParameterError("style must be a Style")
        if self.provenance is not None and not isinstance(self.provenance, Provenance):
            raise ParameterError("provenance must be a Provenance or None")
        if self.georef is not None:
            if not isinstance(self.georef, GeoRef):
                raise ParameterError("georef must be a GeoRef or None")
            if self.georef.crs is not None:
                limits.check_text(self.georef.crs, "the CRS")
        # The object's share of the per-file limits, checked by the document before it is inserted.
        pixels, source_bytes = _source_cost(self.source)
        prov_bytes = limits.json_bytes(self.provenance.to_json()) if self.provenance is not None else 4
        if self.georef is not None:  # counted with the provenance: both are small records beside the source
            prov_bytes += limits.json_bytes(self.georef.as_dict()) + 12
        object.__setattr__(self, "_mask_pixels", pixels)
        object.__setattr__(
            self,
            "_file_bytes",
            limits.object_file_bytes(limits.json_bytes(self.name), prov_bytes, source_bytes),
        )

    @property
    def mask_pixels(self) -> int:
        """Pixels of the bounding box of a grid source (0 for a Euclidean one), as files count them.

        A label map's or volume's points count :data:`~mrm.core.limits.LABEL_WEIGHT` times each.
        """
        return int(self.__dict__["_mask_pixels"])

    @property
    def file_bytes(self) -> int:
        """Upper bound of the bytes this object takes in a project file."""
        return int(self.__dict__["_file_bytes"])

    @property
    def dimension(self) -> int:
        """2 for a plane object, 3 for a voxel set or label volume (docs/design.md §11)."""
        return source_dimension(self.source)

    @property
    def kind(self) -> SourceKind:
        """'discrete', 'euclidean' or 'labels' (a label map, ADR 0033): which representation is the source."""
        return source_kind(self.source)

    def with_(self, **changes: Any) -> DocObject:
        """Return a copy with some fields replaced."""
        return replace(self, **changes)


@dataclass(frozen=True)
class Settings:
    """Document-wide settings saved in the project file.

    Parameters
    ----------
    model : Model
        The discretization model D (and its associated continuation R); text is read by :meth:`Model.parse`.
    compact_limit : int
        The most triangles of a voxel set's safety net that its R simplifies into a compact polyhedron
        (``compact_limit`` of :func:`~mrm.geometry.reconstruct.reconstruct_voxels_detailed`, ADR 0073);
        beyond it a non-convex set's R is the safety net. From 1 to ``limits.MAX_OBJECT_TRIANGLES``;
        default ``limits.MAX_COMPACT_R_TRIANGLES``.

    Raises
    ------
    ParameterError
        For an unknown model or a compact limit that is not a whole number in range.
    """

    model: Model = DEFAULT_MODEL
    compact_limit: int = limits.MAX_COMPACT_R_TRIANGLES

    def __post_init__(self) -> None:
        object.__setattr__(self, "model", Model.parse(self.model))
        object.__setattr__(self, "compact_limit", limits.check_compact_limit(self.compact_limit))

    def derivation_key(self, source: object) -> tuple[Model, int | None]:
        """What of these settings the derived representations of ``source`` depend on.

        The model for every source; the compact limit too for a voxel set, whose R it decides. Two sources
        whose keys are equal share their derivations, so a new limit re-derives the voxel objects only.
        """
        return self.model, (self.compact_limit if isinstance(source, VoxelSet) else None)
