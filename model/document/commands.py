"""The undoable edits of a document's objects as wholes.

Add, remove, reorder, rename, restyle, replace a source, add an operation's results, merge, split, change the
settings. Every edit of a :class:`~mrm.document.Document` is a command pushed on its history
(``doc.push(cmd)``); the edits of an object's content — its vertices, its pixels — are
:mod:`mrm.document.edits`. They keep as little as
possible: object-level edits keep the object before and after (immutable values, so this is a swap of
references that shares everything unchanged).

A command computes its result on its first :meth:`do` from the document as it is then (e.g. the pixels a dab
actually flips) and replays exactly that afterwards. Each ``do`` validates before it mutates, so a refused
edit (a vertex drag that would make the polygon cross itself) raises :class:`InvalidGeometryError` and
leaves the document untouched.

Editing an object's Euclidean shape makes the Euclidean representation its source; painting makes the discrete
one its source (docs/design.md §7). A hand-edited object is no longer what its operation produced, so these
edits clear its provenance (undo brings it back).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

from mrm.core.errors import NotApplicableError, ParameterError
from mrm.core.grids import GridSet, LabelGrid, LabelMap, PixelSet, joint_box
from mrm.core.limits import check_name, check_pixel_extent
from mrm.core.models import Model
from mrm.document.document import Document
from mrm.document.history import COMMAND_OVERHEAD, Command
from mrm.document.objects import (
    PALETTE,
    DocObject,
    Geometry,
    Settings,
    Source,
    Style,
    is_polyhedron,
    validate_geometry,
)
from mrm.geometry.polyhedra import Polyhedron
from mrm.ops.georef import common_grid
from mrm.ops.provenance import Provenance


def source_nbytes(source: Source) -> int:
    """Approximate memory of a source value."""
    if isinstance(source, GridSet):
        return int(source.mask.nbytes) + 64
    if isinstance(source, LabelGrid):
        return int(source.labels.nbytes) + 64
    if is_polyhedron(source):
        return int(source.vertices.nbytes + source.triangles.nbytes) + 64
    import shapely

    return int(shapely.get_num_coordinates(source)) * 16 + 64


def same_source(a: Source, b: Source) -> bool:
    """True when two sources are identical bit for bit (unlike ``==``, this tells 0.0 from -0.0)."""
    if a is b:
        return True
    if isinstance(a, GridSet | LabelGrid) or isinstance(b, GridSet | LabelGrid) or is_polyhedron(a):
        return type(a) is type(b) and a == b
    import shapely

    return bool(shapely.to_wkb(a) == shapely.to_wkb(b))


def check_union_box(boxes: Sequence[tuple[int, int, int, int] | None], what: str) -> None:
    """Refuse, before any array is allocated, a result whose box would exceed the per-object limits.

    Two small objects 2³² pixels apart have a union whose mask would take gigabytes; the box alone says so.
    """
    box = joint_box(boxes)
    if box is None:
        return
    x0, y0, x1, y1 = box
    check_pixel_extent((x0, y0), (y1 - y0 + 1, x1 - x0 + 1), what)


def refuse_label_map(obj: DocObject, what: str) -> None:
    """Refuse a pixel or polygon edit on a label map or a 3D object, saying what to do instead (ADR 0033)."""
    if obj.dimension == 3:
        raise NotApplicableError(
            f"{obj.name!r} is a 3D object: {what} apply to pixel and polygon objects (docs/design.md §11)"
        )
    if isinstance(obj.source, LabelMap):
        raise NotApplicableError(
            f"{obj.name!r} is a label map: {what} apply to pixel and polygon objects; Edit ▸ Split into "
            "Objects makes one pixel object per label"
        )


def object_pixels(doc: Document, obj: DocObject) -> PixelSet:
    """The discrete representation of ``obj`` under the document's model (its source, or D(source))."""
    refuse_label_map(obj, "pixel edits, merges and operations")
    if isinstance(obj.source, PixelSet):
        return obj.source
    ps = doc.cache.entry_under(obj.source, doc.settings).get("discrete")
    assert isinstance(ps, PixelSet)
    return ps


def object_polygons(doc: Document, obj: DocObject) -> Geometry:
    """The Euclidean representation of ``obj`` (its source, or R(source))."""
    refuse_label_map(obj, "vertex edits")
    if not isinstance(obj.source, PixelSet):
        return obj.source
    return validate_geometry(doc.cache.entry_under(obj.source, doc.settings).get("euclidean"))


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


class SwapObject(Command):
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
            and isinstance(other, SwapObject)
            and other.obj_id == self.obj_id
            and self.drag_id is not None
            and other.drag_id == self.drag_id
            and self._same_target(other)
        ):
            self.after = other.after
            return True
        return False

    def _same_target(self, other: SwapObject) -> bool:
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


class RenameObject(SwapObject):
    """Give an object a new name."""

    def __init__(self, obj_id: int, name: str) -> None:
        super().__init__(obj_id)
        if not isinstance(name, str):
            raise ParameterError("a name must be text")
        self.name = check_name(name)
        self.label = "Rename"

    def _build(self, doc: Document, obj: DocObject) -> DocObject:
        return obj.with_(name=self.name)


class RestyleObject(SwapObject):
    """Give an object a new style."""

    def __init__(self, obj_id: int, style: Style) -> None:
        super().__init__(obj_id)
        if not isinstance(style, Style):
            raise ParameterError("style must be a Style")
        self.style = style
        self.label = "Change style"

    def _build(self, doc: Document, obj: DocObject) -> DocObject:
        return obj.with_(style=self.style)


class SetSource(SwapObject):
    """Replace an object's source: a new geometry (replace geometry) or a new pixel set.

    Parameters
    ----------
    obj_id : int
        The object.
    source : PixelSet or VoxelSet or Polygon or MultiPolygon or Polyhedron
        The new source; a geometry must be valid (:func:`~mrm.document.validate_geometry`); a voxel set (the
        3D views' paint, erase, delete component, fill cavity) replaces a voxel object's, a polyhedron (Edit ▸
        Transform 3D Object) a polyhedron object's.
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
        if not isinstance(source, GridSet | Polyhedron):  # both are valid by construction
            source = validate_geometry(source)
        self.source = source
        self.label = label
        self.drag_id = drag_id

    def _build(self, doc: Document, obj: DocObject) -> DocObject:
        return obj.with_(source=self.source, provenance=None)


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
        parts = [object_pixels(doc, o) for o in objs]
        check_union_box([p.bbox for p in parts], "the merged object")  # before allocating it
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

    @classmethod
    def compact_limit(cls, doc: Document, triangles: int) -> ChangeSettings:
        """The command setting the compact limit of the voxel objects' R (:attr:`Settings.compact_limit`)."""
        cmd = cls(dataclasses.replace(doc.settings, compact_limit=triangles))
        cmd.label = f"Compact R up to {cmd.settings.compact_limit:,} triangles"
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
