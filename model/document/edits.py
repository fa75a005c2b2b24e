"""The undoable edits of an object's content: a Euclidean source's vertices, a discrete one's pixels.

* vertex edits (move, insert, delete) keep the object before and after, as every object-level edit does
  (:mod:`mrm.document.commands`): a swap of immutable values;
* pixel edits (paint, erase, fill hole, delete component) keep a :class:`PixelDelta`: the bounding box of the
  pixels that flipped and their packed mask. Applying it is an XOR, so the same delta serves undo and redo,
  and a 1,000-dab brush stroke on a 2048² object costs kilobytes, not 1,000 copies.

A command computes its result on its first ``do`` from the document as it is then (e.g. the pixels a dab
actually flips) and replays exactly that afterwards. Each ``do`` validates before it mutates, so a refused
edit (a vertex drag that would make the polygon cross itself) raises :class:`InvalidGeometryError` and
leaves the document untouched. Editing an object's Euclidean shape makes the Euclidean representation its
source; painting makes the discrete one its source (docs/design.md §7); either clears the provenance of what
an operation produced (undo brings it back).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.grids import PixelSet
from mrm.document.commands import SwapObject, check_union_box, object_pixels, object_polygons, source_nbytes
from mrm.document.document import Document
from mrm.document.history import COMMAND_OVERHEAD, Command
from mrm.document.objects import DocObject, Geometry, validate_geometry
from mrm.geometry.topology.labeling import label
from mrm.reps.region import fill_chains, region_of

#: A vertex of a Euclidean source: (polygon index in a MultiPolygon (0 for a Polygon), ring (0 = exterior,
#: k = k-th hole), vertex index in the ring, the closing point not counted).
VertexRef = tuple[int, int, int]


# ---------------------------------------------------------------------------------------------- pixel deltas
class PixelDelta:
    """The pixels an edit flips: a box and a packed mask. ``delta.apply(A)`` = A XOR delta.

    Parameters
    ----------
    flipped : PixelSet
        The pixels that change state (in A and leaving, or not in A and entering).
    """

    __slots__ = ("_bits", "count", "origin", "shape")

    def __init__(self, flipped: PixelSet) -> None:
        self.origin = flipped.origin
        self.shape = flipped.shape
        self.count = flipped.count
        self._bits = np.packbits(flipped.mask, axis=None)

    def is_empty(self) -> bool:
        """True when no pixel flips."""
        return self.count == 0

    def mask(self) -> npt.NDArray[np.bool_]:
        """The flipped pixels as a boolean mask over the box (row = y − y0)."""
        h, w = self.shape
        return np.unpackbits(self._bits, count=h * w).reshape(h, w).astype(bool)

    def pixels(self) -> PixelSet:
        """The flipped pixels."""
        return PixelSet(self.mask(), self.origin)

    def apply(self, ps: PixelSet) -> PixelSet:
        """Return ``ps`` with the delta's pixels flipped (its own inverse)."""
        if self.count == 0:
            return ps
        h, w = self.shape
        x0, y0 = self.origin
        b = ps.bbox
        if b is None:
            return self.pixels()
        box = (min(b[0], x0), min(b[1], y0), max(b[2], x0 + w - 1), max(b[3], y0 + h - 1))
        arr = ps.to_array(box)
        sub = arr[y0 - box[1] : y0 - box[1] + h, x0 - box[0] : x0 - box[0] + w]
        np.logical_xor(sub, self.mask(), out=sub)
        return PixelSet(arr, (box[0], box[1]))

    def nbytes(self) -> int:
        """Memory held."""
        return int(self._bits.nbytes) + 64

    def box(self) -> tuple[int, int, int, int] | None:
        """The box (xmin, ymin, xmax, ymax) of the flipped pixels' array, None when nothing flips."""
        if self.count == 0:
            return None
        (x0, y0), (h, w) = self.origin, self.shape
        return (x0, y0, x0 + w - 1, y0 + h - 1)


# ---------------------------------------------------------------------------------------------- vertices
def _rings(geom: Geometry) -> tuple[bool, list[list[npt.NDArray[np.float64]]]]:
    """(is_multi, polygons as lists of rings, each an (n, 2) array without the closing point)."""
    polys = list(geom.geoms) if isinstance(geom, MultiPolygon) else ([] if geom.is_empty else [geom])
    out = []
    for p in polys:
        rings = [np.asarray(p.exterior.coords, dtype=np.float64)[:-1, :2]]
        rings += [np.asarray(r.coords, dtype=np.float64)[:-1, :2] for r in p.interiors]
        out.append(rings)
    return isinstance(geom, MultiPolygon), out


def _close(r: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    return np.concatenate([r, r[:1]], axis=0)


def _build_geometry(multi: bool, polys: list[list[npt.NDArray[np.float64]]]) -> Geometry:
    for rings in polys:
        for r in rings:
            if len(r) < 3:
                raise InvalidGeometryError("a polygon ring needs at least 3 vertices")
    built = [Polygon(_close(rs[0]), [_close(h) for h in rs[1:]]) for rs in polys]
    geom: Geometry = MultiPolygon(built) if multi else built[0]
    return validate_geometry(geom)


def _locate(polys: list[list[npt.NDArray[np.float64]]], v: VertexRef, *, insert: bool = False) -> None:
    part, ring, index = v
    if not 0 <= part < len(polys):
        raise ParameterError(f"no polygon {part} (the shape has {len(polys)})")
    if not 0 <= ring < len(polys[part]):
        raise ParameterError(f"no ring {ring} in polygon {part}")
    n = len(polys[part][ring])
    if not (0 <= index <= n if insert else 0 <= index < n):
        raise ParameterError(f"no vertex {index} in ring {ring} of polygon {part}")


def _point(xy: Sequence[float]) -> npt.NDArray[np.float64]:
    p = np.asarray([float(xy[0]), float(xy[1])], dtype=np.float64)
    if not np.isfinite(p).all():
        raise InvalidGeometryError("a vertex needs finite coordinates")
    return p


class _VertexEdit(SwapObject):
    vertex: VertexRef

    def _edit(self, polys: list[list[npt.NDArray[np.float64]]]) -> None:
        raise NotImplementedError

    def _build(self, doc: Document, obj: DocObject) -> DocObject:
        multi, polys = _rings(object_polygons(doc, obj))
        self._edit(polys)
        return obj.with_(source=_build_geometry(multi, polys), provenance=None)


class MoveVertex(_VertexEdit):
    """Move one vertex of an object's Euclidean shape to ``xy``.

    Parameters
    ----------
    obj_id : int
        The object (a discrete-source object is edited through its Euclidean representation R(A), which
        becomes its source).
    vertex : VertexRef
        (polygon, ring, index).
    xy : pair of float
        The new position.
    drag_id : object, optional
        The moves of one drag share a ``drag_id`` and merge into one undo step; the view can push a command
        per mouse move for a live preview, or one on release.
    """

    def __init__(self, obj_id: int, vertex: VertexRef, xy: Sequence[float], drag_id: object = None) -> None:
        super().__init__(obj_id)
        self.vertex = (int(vertex[0]), int(vertex[1]), int(vertex[2]))
        self.xy = _point(xy)
        self.drag_id = drag_id
        self.label = "Move vertex"

    def _edit(self, polys: list[list[npt.NDArray[np.float64]]]) -> None:
        _locate(polys, self.vertex)
        part, ring, index = self.vertex
        polys[part][ring] = polys[part][ring].copy()
        polys[part][ring][index] = self.xy

    def _same_target(self, other: SwapObject) -> bool:
        return isinstance(other, MoveVertex) and other.vertex == self.vertex


class InsertVertex(_VertexEdit):
    """Insert a vertex at ``xy`` before position ``index`` of a ring (``index`` = ring length appends)."""

    def __init__(self, obj_id: int, vertex: VertexRef, xy: Sequence[float]) -> None:
        super().__init__(obj_id)
        self.vertex = (int(vertex[0]), int(vertex[1]), int(vertex[2]))
        self.xy = _point(xy)
        self.label = "Insert vertex"

    def _edit(self, polys: list[list[npt.NDArray[np.float64]]]) -> None:
        _locate(polys, self.vertex, insert=True)
        part, ring, index = self.vertex
        polys[part][ring] = np.insert(polys[part][ring], index, self.xy, axis=0)


class DeleteVertex(_VertexEdit):
    """Delete one vertex (refused when its ring would keep fewer than 3)."""

    def __init__(self, obj_id: int, vertex: VertexRef) -> None:
        super().__init__(obj_id)
        self.vertex = (int(vertex[0]), int(vertex[1]), int(vertex[2]))
        self.label = "Delete vertex"

    def _edit(self, polys: list[list[npt.NDArray[np.float64]]]) -> None:
        _locate(polys, self.vertex)
        part, ring, index = self.vertex
        polys[part][ring] = np.delete(polys[part][ring], index, axis=0)


# ---------------------------------------------------------------------------------------------- pixels
class _PixelEdit(Command):
    """Flip a set of pixels of an object's discrete representation, which becomes its source."""

    def __init__(self, obj_id: int) -> None:
        self.obj_id = obj_id
        self.delta: PixelDelta | None = None
        #: The object before the first edit if its source was Euclidean (undo restores that source).
        self.euclidean_before: DocObject | None = None
        self.provenance_before: Any = None

    def _flipped(self, doc: Document, base: PixelSet) -> PixelSet:
        raise NotImplementedError

    def do(self, doc: Document) -> None:
        """Apply the delta (computed on the first call from the pixels that actually change)."""
        obj = doc.get(self.obj_id)
        base = object_pixels(doc, obj)
        if self.delta is None:
            self.delta = PixelDelta(self._flipped(doc, base))
            self.euclidean_before = obj if not isinstance(obj.source, PixelSet) else None
            self.provenance_before = obj.provenance
        if self.delta.is_empty():
            return
        check_union_box([base.bbox, self.delta.box()], "the edited object")  # before allocating it
        after = obj.with_(source=self.delta.apply(base), provenance=None)  # checks the per-object limits
        doc.check_capacity(add=[after], remove=[self.obj_id])
        doc.replace_object(after)

    def undo(self, doc: Document) -> None:
        """Flip the pixels back (or restore the Euclidean source the object had)."""
        assert self.delta is not None
        if self.delta.is_empty():
            return
        obj = doc.get(self.obj_id)
        if self.euclidean_before is not None:
            doc.replace_object(self.euclidean_before)
            return
        assert isinstance(obj.source, PixelSet)
        doc.replace_object(obj.with_(source=self.delta.apply(obj.source), provenance=self.provenance_before))

    def is_obsolete(self) -> bool:
        """True when no pixel changed."""
        return self.delta is not None and self.delta.is_empty()

    def byte_size(self) -> int:
        """The packed delta (plus the small Euclidean source replaced, if any)."""
        n = COMMAND_OVERHEAD + (self.delta.nbytes() if self.delta is not None else 0)
        if self.euclidean_before is not None:
            n += source_nbytes(self.euclidean_before.source)
        return n


class PaintPixels(_PixelEdit):
    """Add (``value=True``) or erase (``value=False``) the pixels of a dab.

    A brush stroke is a macro of these (``with doc.history.macro("Brush"): ...``), so it is one undo step
    that stores only the pixels each dab flipped.
    """

    def __init__(self, obj_id: int, pixels: PixelSet, value: bool = True) -> None:
        super().__init__(obj_id)
        self._dab: PixelSet | None = pixels
        self.value = bool(value)
        self.label = "Paint" if value else "Erase"

    def _flipped(self, doc: Document, base: PixelSet) -> PixelSet:
        dab = self._dab
        assert dab is not None
        self._dab = None  # only the delta is kept
        box = dab.bbox
        if box is None:
            return PixelSet.empty()
        local = base.crop(box)  # keep the work proportional to the dab, not the object
        return dab - local if self.value else dab & local


def ErasePixels(obj_id: int, pixels: PixelSet) -> PaintPixels:
    """The command erasing ``pixels`` from an object (a :class:`PaintPixels` with ``value=False``)."""
    return PaintPixels(obj_id, pixels, value=False)


def component_pixels(ps: PixelSet, at: tuple[int, int]) -> PixelSet:
    """The 4-connected component of ``ps`` holding pixel ``at`` (from the region representation).

    Raises
    ------
    ParameterError
        When ``at`` is not a pixel of the set.
    """
    region = region_of(ps)
    comp = region.component_of(at[0], at[1])
    if comp is None:
        raise ParameterError(f"pixel ({at[0]}, {at[1]}) is not part of the object")
    return region.labels.pixel_set(comp.label)


def hole_pixels(ps: PixelSet, at: tuple[int, int] | None = None) -> PixelSet:
    """The pixels of the hole of ``ps`` holding pixel ``at`` — or of every hole when ``at`` is None.

    The holes are the bounded 8-components of the complement (docs/design.md §4). Filling each component's
    outer crack chain (the region representation) gives the set with every hole filled; its difference with
    the set is the union of the holes, and since distinct holes are distinct 8-components of the complement,
    the 8-component of that difference holding ``at`` is exactly the hole holding ``at``.

    Raises
    ------
    ParameterError
        When ``at`` is given and is not in a hole.
    """
    region = region_of(ps)
    if region.n_holes == 0:
        if at is None:
            return PixelSet.empty()
        raise ParameterError("the object has no hole")
    filled = PixelSet.empty()
    for comp in region.components:
        if comp.holes:
            filled = filled | fill_chains(comp.outer)
    holes = filled - ps
    if at is None:
        return holes
    x, y = int(at[0]), int(at[1])
    if (x, y) not in holes:
        raise ParameterError(f"pixel ({x}, {y}) is not in a hole of the object")
    labels, _ = label(holes.mask, connectivity=8)
    x0, y0 = holes.origin
    return PixelSet(labels == labels[y - y0, x - x0], holes.origin)


class FillHole(_PixelEdit):
    """Fill the hole containing pixel ``at`` (every hole when ``at`` is None) of an object.

    Holes are the bounded 8-components of the complement (docs/design.md §4); the region representation finds
    them.
    """

    def __init__(self, obj_id: int, at: tuple[int, int] | None = None) -> None:
        super().__init__(obj_id)
        self.at = None if at is None else (int(at[0]), int(at[1]))
        self.label = "Fill hole" if at is not None else "Fill holes"

    def _flipped(self, doc: Document, base: PixelSet) -> PixelSet:
        return hole_pixels(base, self.at)


class DeleteComponent(_PixelEdit):
    """Delete the 4-connected component containing pixel ``at``."""

    def __init__(self, obj_id: int, at: tuple[int, int]) -> None:
        super().__init__(obj_id)
        self.at = (int(at[0]), int(at[1]))
        self.label = "Delete component"

    def _flipped(self, doc: Document, base: PixelSet) -> PixelSet:
        return component_pixels(base, self.at)
