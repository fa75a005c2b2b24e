"""The concrete undoable edits of a document.

Every edit of a :class:`~mrm.document.Document` is one of these commands pushed on its history
(``doc.push(cmd)``). They keep as little as possible:

* object-level edits (rename, restyle, replace geometry, vertex edits, change of source) keep the object
  before and after — immutable values, so this is a swap of references and shares everything unchanged;
* pixel edits (paint, erase, fill hole, delete component) keep a :class:`PixelDelta`: the bounding box of the
  pixels that flipped and their packed mask. Applying it is an XOR, so the same delta serves undo and redo,
  and a 1,000-dab brush stroke on a 2048² object costs kilobytes, not 1,000 copies.

A command computes its result on its first :meth:`do` from the document as it is then (e.g. the pixels a dab
actually flips) and replays exactly that afterwards. Each ``do`` validates before it mutates, so a refused
edit (a vertex drag that would make the polygon cross itself) raises :class:`InvalidGeometryError` and
leaves the document untouched.

Editing an object's Euclidean shape makes the Euclidean representation its source; painting makes the
discrete one its source (docs/design.md §7). A hand-edited object is no longer what its operation produced,
so these
edits clear its provenance (undo brings it back).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import InvalidGeometryError, NotApplicableError, ParameterError
from mrm.core.grids import LabelMap, PixelSet
from mrm.core.limits import check_name, check_pixel_extent
from mrm.core.models import Model
from mrm.document.document import Document
from mrm.document.history import COMMAND_OVERHEAD, Command
from mrm.document.objects import PALETTE, DocObject, Geometry, Settings, Source, Style, validate_geometry
from mrm.geometry.topology.labeling import label
from mrm.ops.georef import common_grid
from mrm.ops.provenance import Provenance
from mrm.reps.region import fill_chains, region_of

#: A vertex of a Euclidean source: (polygon index in a MultiPolygon (0 for a Polygon), ring (0 = exterior,
#: k = k-th hole), vertex index in the ring, the closing point not counted).
VertexRef = tuple[int, int, int]


def source_nbytes(source: Source) -> int:
    """Approximate memory of a source value."""
    if isinstance(source, PixelSet):
        return int(source.mask.nbytes) + 64
    if isinstance(source, LabelMap):
        return int(source.labels.nbytes) + 64
    import shapely

    return int(shapely.get_num_coordinates(source)) * 16 + 64


def same_source(a: Source, b: Source) -> bool:
    """True when two sources are identical bit for bit (unlike ``==``, this tells 0.0 from -0.0)."""
    if a is b:
        return True
    if isinstance(a, PixelSet | LabelMap) or isinstance(b, PixelSet | LabelMap):
        return type(a) is type(b) and a == b
    import shapely

    return bool(shapely.to_wkb(a) == shapely.to_wkb(b))


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


def _check_union_box(boxes: Sequence[tuple[int, int, int, int] | None], what: str) -> None:
    """Refuse, before any array is allocated, a result whose box would exceed the per-object limits.

    Two small objects 2³² pixels apart have a union whose mask would take gigabytes; the box alone says so.
    """
    real = [b for b in boxes if b is not None]
    if not real:
        return
    x0, y0 = min(b[0] for b in real), min(b[1] for b in real)
    x1, y1 = max(b[2] for b in real), max(b[3] for b in real)
    check_pixel_extent((x0, y0), (y1 - y0 + 1, x1 - x0 + 1), what)


def _not_a_label_map(obj: DocObject, what: str) -> None:
    """Refuse a pixel or polygon edit on a label map, saying what to do instead (ADR 0033)."""
    if isinstance(obj.source, LabelMap):
        raise NotApplicableError(
            f"{obj.name!r} is a label map: {what} apply to pixel and polygon objects; Edit ▸ Split into "
            "Objects makes one pixel object per label"
        )


def discrete_of(doc: Document, obj: DocObject) -> PixelSet:
    """The discrete representation of ``obj`` under the document's model (its source, or D(source))."""
    _not_a_label_map(obj, "pixel edits, merges and operations")
    if isinstance(obj.source, PixelSet):
        return obj.source
    ps = doc.cache.entry(obj.source, doc.model).get("discrete")
    assert isinstance(ps, PixelSet)
    return ps


def euclidean_of(doc: Document, obj: DocObject) -> Geometry:
    """The Euclidean representation of ``obj`` (its source, or R(source))."""
    _not_a_label_map(obj, "vertex edits")
    if not isinstance(obj.source, PixelSet):
        return obj.source
    return validate_geometry(doc.cache.entry(obj.source, doc.model).get("euclidean"))


# ---------------------------------------------------------------------------------------------- object list
class AddObject(Command):
    """Insert a new object (made with :meth:`Document.make_object`) at ``index`` (default: on top)."""

    def __init__(self, obj: DocObject, index: int | None = None, *, select: bool = False) -> None:
        self.obj = obj
        self.index = index
        self.select = select
        self.selection_before: tuple[int, ...] = ()
        self.label = f"Add {obj.name}"

    def do(self, doc: Document) -> None:
        """Insert the object."""
        doc.check_capacity(add=[self.obj])
        self.selection_before = doc.selection
        doc.insert_object(self.obj, self.index)
        if self.select:
            doc.set_selection([self.obj.id])

    def undo(self, doc: Document) -> None:
        """Remove it again (and restore the selection)."""
        doc.remove_object(self.obj.id)
        doc.set_selection(self.selection_before)

    def byte_size(self) -> int:
        """The object's source (it lives only here once undone)."""
        return COMMAND_OVERHEAD + source_nbytes(self.obj.source)


class RemoveObjects(Command):
    """Remove objects (undo puts each back at its place)."""

    def __init__(self, ids: Sequence[int]) -> None:
        self.ids = list(dict.fromkeys(ids))
        if not self.ids:
            raise ParameterError("nothing to remove")
        self.removed: list[tuple[int, DocObject]] = []
        self.selection_before: tuple[int, ...] = ()
        self.label = "Remove object" if len(self.ids) == 1 else f"Remove {len(self.ids)} objects"

    def do(self, doc: Document) -> None:
        """Remove the objects, remembering their positions."""
        for i in self.ids:
            doc.get(i)  # all exist, or nothing happens
        self.selection_before = doc.selection
        removed = []
        for i in self.ids:
            obj, idx = doc.remove_object(i)
            removed.append((idx, obj))
        self.removed = removed

    def undo(self, doc: Document) -> None:
        """Re-insert them in reverse order of removal, so every index is right; restore the selection."""
        for idx, obj in reversed(self.removed):
            doc.insert_object(obj, idx)
        doc.set_selection(self.selection_before)

    def byte_size(self) -> int:
        """The removed objects' sources."""
        return COMMAND_OVERHEAD + sum(source_nbytes(o.source) for _, o in self.removed)


class ReorderObjects(Command):
    """Put the objects in a new order (a permutation of the current ids)."""

    def __init__(self, order: Sequence[int], label: str = "Reorder objects") -> None:
        self.order = [int(i) for i in order]
        self.before: list[int] = []
        self.label = label

    @classmethod
    def move(cls, doc: Document, obj_id: int, index: int) -> ReorderObjects:
        """The command moving one object to position ``index`` (clamped to the list)."""
        ids = [i for i in doc.ids if i != obj_id]
        doc.get(obj_id)
        ids.insert(max(0, min(index, len(ids))), obj_id)
        return cls(ids, label="Move object")

    def do(self, doc: Document) -> None:
        """Apply the new order."""
        if sorted(self.order) != sorted(doc.ids):
            raise ParameterError("the new order must list every object exactly once")
        self.before = list(doc.ids)
        doc.set_order(self.order)

    def undo(self, doc: Document) -> None:
        """Restore the previous order."""
        doc.set_order(self.before)

    def is_obsolete(self) -> bool:
        """True when the order did not change."""
        return self.before == self.order


class _Swap(Command):
    """Replace one object by a new version of itself; undo swaps the old one back."""

    drag_id: object | None = None

    def __init__(self, obj_id: int) -> None:
        self.obj_id = obj_id
        self.before: DocObject | None = None
        self.after: DocObject | None = None

    def _build(self, doc: Document, obj: DocObject) -> DocObject:
        raise NotImplementedError

    def do(self, doc: Document) -> None:
        """Swap in the new version (computed on the first call)."""
        obj = doc.get(self.obj_id)
        if self.after is None:
            self.after = self._build(doc, obj)
            self.before = obj
        doc.check_capacity(add=[self.after], remove=[self.obj_id])
        doc.replace_object(self.after)

    def undo(self, doc: Document) -> None:
        """Swap the old version back."""
        assert self.before is not None
        doc.replace_object(self.before)

    def merge_with(self, other: Command) -> bool:
        """Merge the steps of one drag: same class, object and non-None ``drag_id``."""
        if (
            type(other) is type(self)
            and isinstance(other, _Swap)
            and other.obj_id == self.obj_id
            and self.drag_id is not None
            and other.drag_id == self.drag_id
            and self._same_target(other)
        ):
            self.after = other.after
            return True
        return False

    def _same_target(self, other: _Swap) -> bool:
        return True

    def is_obsolete(self) -> bool:
        """True when nothing changed (e.g. a drag back to the start), bit for bit."""
        b, a = self.before, self.after
        if b is None or a is None:
            return False
        same_rest = (b.name, b.style, b.provenance) == (a.name, a.style, a.provenance)
        return same_rest and same_source(b.source, a.source)

    def byte_size(self) -> int:
        """The sources kept (only counted when the edit replaced the source)."""
        n = COMMAND_OVERHEAD
        if self.before is not None and self.after is not None and self.before.source is not self.after.source:
            n += source_nbytes(self.before.source) + source_nbytes(self.after.source)
        return n


class RenameObject(_Swap):
    """Give an object a new name."""

    def __init__(self, obj_id: int, name: str) -> None:
        super().__init__(obj_id)
        if not isinstance(name, str):
            raise ParameterError("a name must be text")
        self.name = check_name(name)
        self.label = "Rename"

    def _build(self, doc: Document, obj: DocObject) -> DocObject:
        return obj.with_(name=self.name)


class RestyleObject(_Swap):
    """Give an object a new style."""

    def __init__(self, obj_id: int, style: Style) -> None:
        super().__init__(obj_id)
        if not isinstance(style, Style):
            raise ParameterError("style must be a Style")
        self.style = style
        self.label = "Change style"

    def _build(self, doc: Document, obj: DocObject) -> DocObject:
        return obj.with_(style=self.style)


class SetSource(_Swap):
    """Replace an object's source: a new geometry (replace geometry) or a new pixel set.

    Parameters
    ----------
    obj_id : int
        The object.
    source : PixelSet or Polygon or MultiPolygon
        The new source; a geometry must be valid (:func:`~mrm.document.validate_geometry`).
    label : str
        Text of the undo step.
    drag_id : object, optional
        Consecutive commands with the same non-None ``drag_id`` merge into one step (a whole-object drag
        that pushes a command per mouse move).
    """

    def __init__(
        self, obj_id: int, source: Source, label: str = "Replace geometry", drag_id: object = None
    ) -> None:
        super().__init__(obj_id)
        if not isinstance(source, PixelSet):
            source = validate_geometry(source)
        self.source = source
        self.label = label
        self.drag_id = drag_id

    def _build(self, doc: Document, obj: DocObject) -> DocObject:
        return obj.with_(source=self.source, provenance=None)


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


class _VertexEdit(_Swap):
    vertex: VertexRef

    def _edit(self, polys: list[list[npt.NDArray[np.float64]]]) -> None:
        raise NotImplementedError

    def _build(self, doc: Document, obj: DocObject) -> DocObject:
        multi, polys = _rings(euclidean_of(doc, obj))
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

    def _same_target(self, other: _Swap) -> bool:
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
        base = discrete_of(doc, obj)
        if self.delta is None:
            self.delta = PixelDelta(self._flipped(doc, base))
            self.euclidean_before = obj if not isinstance(obj.source, PixelSet) else None
            self.provenance_before = obj.provenance
        if self.delta.is_empty():
            return
        _check_union_box([base.bbox, self.delta.box()], "the edited object")  # before allocating it
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
    outer
    crack chain (the region representation) gives the set with every hole filled; its difference with the set
    is the union of the holes, and since distinct holes are distinct 8-components of the complement, the
    8-component of that difference holding ``at`` is exactly the hole holding ``at``.

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


# ------------------------------------------------------------------------------------------- several objects
class ApplyResults(Command):
    """Apply an operation's results: add new objects, replace some, remove others — one undo step.

    Parameters
    ----------
    label : str
        Text of the undo step (the operation's name).
    add : sequence of DocObject
        New objects (made with :meth:`Document.make_object`, with their provenance).
    replace : sequence of DocObject
        New versions of existing objects (same id).
    remove : sequence of int
        Ids of objects to remove.
    index : int, optional
        Where the new objects go (default: on top).
    select : bool
        Select the new objects afterwards.
    """

    def __init__(
        self,
        label: str,
        add: Sequence[DocObject] = (),
        replace: Sequence[DocObject] = (),
        remove: Sequence[int] = (),
        *,
        index: int | None = None,
        select: bool = True,
    ) -> None:
        self.label = label
        self.add = list(add)
        self.replace = list(replace)
        self.remove = list(dict.fromkeys(remove))
        self.index = index
        self.select = select
        self._replaced: list[DocObject] = []
        self._removed: list[tuple[int, DocObject]] = []
        self._selection_before: tuple[int, ...] = ()

    def do(self, doc: Document) -> None:
        """Remove, replace, then insert — after checking all of it, so a refused step changes nothing."""
        for i in self.remove:
            doc.get(i)
        replaced = [o.id for o in self.replace]
        for o in self.replace:
            doc.get(o.id)
        if len(set(replaced)) != len(replaced):
            raise ParameterError("an operation result replaces the same object twice")
        both = set(replaced) & set(self.remove)
        if both:
            raise ParameterError(f"an operation result both replaces and removes object {min(both)}")
        added = [o.id for o in self.add]
        if len(set(added)) != len(added):
            raise ParameterError("an operation result adds two objects with the same id")
        for o in self.add:
            if o.id in doc:
                raise ParameterError(f"an object with id {o.id} already exists")
        doc.check_capacity(add=[*self.replace, *self.add], remove=[*self.remove, *replaced])
        self._selection_before = doc.selection
        removed = []
        for i in self.remove:
            obj, idx = doc.remove_object(i)
            removed.append((idx, obj))
        self._removed = removed
        self._replaced = [doc.replace_object(o) for o in self.replace]
        at = self.index
        for k, o in enumerate(self.add):
            doc.insert_object(o, None if at is None else at + k)
        if self.select and self.add:
            doc.set_selection(o.id for o in self.add)

    def undo(self, doc: Document) -> None:
        """Remove the new objects, restore the replaced and removed ones and the selection."""
        for o in reversed(self.add):
            doc.remove_object(o.id)
        for o in reversed(self._replaced):
            doc.replace_object(o)
        for idx, obj in reversed(self._removed):
            doc.insert_object(obj, idx)
        doc.set_selection(self._selection_before)

    def byte_size(self) -> int:
        """Sources of every object involved."""
        objs = [*self.add, *self.replace, *self._replaced, *(o for _, o in self._removed)]
        return COMMAND_OVERHEAD + sum(source_nbytes(o.source) for o in objs)


class _Replacing(Command):
    """A command whose effect is an :class:`ApplyResults` built on its first run (objects in, objects out)."""

    label = ""
    _inner: ApplyResults | None = None

    def _build(self, doc: Document) -> ApplyResults:
        raise NotImplementedError

    def do(self, doc: Document) -> None:
        """Build the replacement (first call) and apply it."""
        if self._inner is None:
            self._inner = self._build(doc)
            self.label = self._inner.label
        self._inner.do(doc)

    def undo(self, doc: Document) -> None:
        """Bring back what was replaced."""
        assert self._inner is not None
        self._inner.undo(doc)

    def byte_size(self) -> int:
        """The new and removed sources."""
        return self._inner.byte_size() if self._inner is not None else COMMAND_OVERHEAD


class MergeObjects(_Replacing):
    """Merge objects into one whose discrete source is the union of their discrete representations.

    The union is taken on pixels because D is union-stable (D(E ∪ F) = D(E) ∪ D(F)), so the merged object
    is exactly what the inputs showed, with no rounding from a Euclidean boolean operation. The inputs are
    removed; the merged object takes the place and style of the lowest one and records the merge in its
    provenance.
    """

    def __init__(self, ids: Sequence[int], name: str | None = None) -> None:
        self.ids = list(dict.fromkeys(ids))
        if len(self.ids) < 2:
            raise ParameterError("merging needs at least two objects")
        self.name = name
        self.label = f"Merge {len(self.ids)} objects"

    def _build(self, doc: Document) -> ApplyResults:
        objs = sorted((doc.get(i) for i in self.ids), key=lambda o: doc.index_of(o.id))
        parts = [discrete_of(doc, o) for o in objs]
        _check_union_box([p.bbox for p in parts], "the merged object")  # before allocating it
        union = PixelSet.empty()
        for part in parts:
            union = union | part
        merged = DocObject(
            id=doc.new_id(),
            name=self.name if self.name is not None else objs[0].name,
            source=union,
            style=objs[0].style,
            provenance=Provenance("merge", {}, tuple(o.id for o in objs)),
            georef=common_grid([o.georef for o in objs], "a merge"),  # one grid: kept (ADR 0021)
        )
        index = doc.index_of(objs[0].id)
        return ApplyResults(self.label, add=[merged], remove=[o.id for o in objs], index=index)


class SplitLabelMap(_Replacing):
    """Replace a label map object by one pixel object per label (named ``<name> label <v>``), in its place.

    What importing a label image "one object per label" gives, from a label map already in the document
    (ADR 0033). The objects keep the map's georeference; undo brings the map back.
    """

    def __init__(self, obj_id: int) -> None:
        self.obj_id = obj_id
        self.label = "Split label map"

    def _build(self, doc: Document) -> ApplyResults:
        obj = doc.get(self.obj_id)
        if not isinstance(obj.source, LabelMap):
            raise NotApplicableError(f"{obj.name!r} is not a label map: there is nothing to split")
        lm = obj.source
        parts = [
            DocObject(
                id=doc.new_id(),
                name=f"{obj.name} label {v}",
                source=lm.pixel_set(v),
                style=dataclasses.replace(obj.style, fill=PALETTE[k % len(PALETTE)]),
                georef=obj.georef,
            )
            for k, v in enumerate(lm.label_values())
        ]
        label = f"Split {obj.name} into {len(parts)} objects"
        return ApplyResults(label, add=parts, remove=[obj.id], index=doc.index_of(obj.id), select=True)


class ChangeSettings(Command):
    """Change the document settings; a new discretization model re-derives every object."""

    def __init__(self, settings: Settings) -> None:
        if not isinstance(settings, Settings):
            raise ParameterError("settings must be a Settings")
        self.settings = settings
        self.before: Settings | None = None
        self.label = "Change settings"

    @classmethod
    def model(cls, doc: Document, model: Model | str) -> ChangeSettings:
        """The command switching the discretization model (its name is read by :meth:`Model.parse`)."""
        chosen = Model.parse(model)
        cmd = cls(dataclasses.replace(doc.settings, model=chosen))
        cmd.label = f"Use the {chosen} model"
        return cmd

    def do(self, doc: Document) -> None:
        """Apply the new settings."""
        self.before = doc.settings
        doc.set_settings(self.settings)

    def undo(self, doc: Document) -> None:
        """Restore the previous settings."""
        assert self.before is not None
        doc.set_settings(self.before)

    def is_obsolete(self) -> bool:
        """True when nothing changed."""
        return self.before == self.settings
