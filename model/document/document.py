"""The shared model: an ordered list of objects, each with one source representation (docs/design.md §7).

An object (:class:`~mrm.document.objects.DocObject`) is an immutable value with one **source** representation
— a Euclidean geometry, a discrete :class:`~mrm.core.grids.PixelSet` or a label map. The other representations
are *derived* from the source under the document's discretization model and cached by
:mod:`mrm.document.derive`:

* Euclidean source E: discrete = D(E), Euclidean = E;
* discrete source A: discrete = A, Euclidean = R(A);

so D(Euclidean) = discrete holds for every object at every moment (D(R(A)) = A is R's contract).

The :class:`Document` is changed only through the commands of :mod:`mrm.document.commands`, pushed on its
single :class:`~mrm.document.history.History`. Views subscribe to coarse, batched :class:`Changes` and never
mutate the model themselves. Nothing here imports Qt.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

from mrm.core import limits
from mrm.core.georef import GeoRef
from mrm.document.derive import DerivationCache, Derived
from mrm.document.history import Command, History
from mrm.document.objects import DocObject, Settings, Source, Style
from mrm.ops.georef import result_georef
from mrm.ops.provenance import Provenance


# ---------------------------------------------------------------------------------------------- events
@dataclass(frozen=True)
class Changes:
    """What changed in one batch of edits; delivered to every subscriber once per batch.

    Attributes
    ----------
    revision : int
        The document revision after the batch.
    inserted, removed : tuple of int
        Ids of objects that appeared / disappeared (net over the batch).
    changed : Mapping[int, frozenset[str]]
        For objects present before and after: which aspects changed, among 'source', 'name', 'style',
        'provenance', 'georef' and 'derived' (the derived representations changed although the source did
        not, e.g. after a change of the discretization model).
    reordered : bool
        The order of the objects present before and after changed.
    selection, settings, reset : bool
        The selection changed / the settings changed / the whole document was replaced (views rebuild).
    """

    revision: int
    inserted: tuple[int, ...] = ()
    removed: tuple[int, ...] = ()
    changed: Mapping[int, frozenset[str]] = field(default_factory=dict)
    reordered: bool = False
    selection: bool = False
    settings: bool = False
    reset: bool = False


class _Pending:
    def __init__(self, order: list[int], selection: tuple[int, ...], settings: Settings) -> None:
        self.order = order
        self.selection = selection
        self.settings = settings
        self.changed: dict[int, set[str]] = {}
        self.reset = False
        self.touched = False


# ---------------------------------------------------------------------------------------------- document
class Document:
    """An ordered collection of objects with settings, a selection, one history and change events.

    Parameters
    ----------
    settings : Settings, optional
        Initial settings (default model 'standard').
    max_undo_steps, max_undo_bytes : int
        Limits of the history.

    Notes
    -----
    Views read the document and push commands (``doc.push(cmd)``); they never call the low-level mutation
    methods, which exist for the commands. Every mutation bumps :attr:`revision`; a mutation that changes an
    object's derived representations also bumps that object's :meth:`object_revision`, which the derivation
    service compares to drop stale results.
    """

    def __init__(
        self,
        settings: Settings | None = None,
        *,
        max_undo_steps: int = 1000,
        max_undo_bytes: int = 512 * 2**20,
    ) -> None:
        self._objects: list[DocObject] = []
        self._by_id: dict[int, DocObject] = {}
        self._settings = settings or Settings()
        self._selection: tuple[int, ...] = ()
        self._revision = 0
        self._obj_rev: dict[int, int] = {}
        self._next_id = 1
        # new_id may be called from a worker (objects read off the GUI thread, e.g. a paste): no two callers
        # may get the same id.
        self._id_lock = threading.Lock()
        # Running totals of the per-file limits (mrm.core.limits): pixels of the discrete sources' boxes and
        # the bytes of the project file, kept by the low-level mutations.
        self._mask_pixels = 0
        self._file_bytes = 0
        self._subscribers: list[Callable[[Changes], None]] = []
        self._batch_depth = 0
        self._pending: _Pending | None = None
        self.cache = DerivationCache()
        self.history = History(self, max_steps=max_undo_steps, max_bytes=max_undo_bytes)
        #: The project file this document was loaded from / last saved to (None for a new document).
        self.path: Path | None = None

    # ------------------------------------------------------------------ reading
    @property
    def objects(self) -> tuple[DocObject, ...]:
        """The objects in order (first = bottom of the drawing order)."""
        return tuple(self._objects)

    @property
    def plane_objects(self) -> tuple[DocObject, ...]:
        """The 2D objects in order (pixels, polygons, label maps): what the plane views draw and pick.

        Voxel sets and label volumes (docs/design.md §11) are kept, saved and listed like any object; the
        plane views leave them out.
        """
        return tuple(o for o in self._objects if o.dimension == 2)

    @property
    def ids(self) -> tuple[int, ...]:
        """The object ids in order."""
        return tuple(o.id for o in self._objects)

    def __len__(self) -> int:
        return len(self._objects)

    def __iter__(self) -> Iterator[DocObject]:
        return iter(tuple(self._objects))

    def __contains__(self, obj_id: object) -> bool:
        return obj_id in self._by_id

    def get(self, obj_id: int) -> DocObject:
        """Return the object with id ``obj_id`` (KeyError if absent)."""
        try:
            return self._by_id[obj_id]
        except KeyError:
            raise KeyError(f"no object with id {obj_id}") from None

    def index_of(self, obj_id: int) -> int:
        """Position of the object in the order."""
        for i, o in enumerate(self._objects):
            if o.id == obj_id:
                return i
        raise KeyError(f"no object with id {obj_id}")

    def find(self, name: str) -> list[DocObject]:
        """The objects called ``name``, in order."""
        return [o for o in self._objects if o.name == name]

    @property
    def settings(self) -> Settings:
        """The document settings."""
        return self._settings

    @property
    def model(self) -> str:
        """The discretization model in force."""
        return self._settings.model

    @property
    def selection(self) -> tuple[int, ...]:
        """Ids of the selected objects, in selection order."""
        return self._selection

    @property
    def revision(self) -> int:
        """Counter bumped by every mutation."""
        return self._revision

    def object_revision(self, obj_id: int) -> int:
        """Counter bumped whenever the derived representations of ``obj_id`` change (-1 if absent)."""
        return self._obj_rev.get(obj_id, -1) if obj_id in self._by_id else -1

    @property
    def is_modified(self) -> bool:
        """True when the document differs from its last saved (or loaded) state."""
        return not self.history.is_clean

    def derived(self, obj_id: int) -> Derived:
        """The representations of object ``obj_id`` under the current model, computed lazily and cached.

        ``doc.derived(i).get('euclidean')`` computes in the calling thread; the GUI computes slow ones on its
        task runner (:mod:`mrm.views.scene`).
        """
        return self.cache.entry_under(self.get(obj_id).source, self._settings)

    # ------------------------------------------------------------------ events
    def subscribe(self, callback: Callable[[Changes], None]) -> Callable[[], None]:
        """Call ``callback(changes)`` after every batch of edits; returns a function that unsubscribes."""
        self._subscribers.append(callback)

        def unsubscribe() -> None:
            if callback in self._subscribers:
                self._subscribers.remove(callback)

        return unsubscribe

    @contextmanager
    def batch(self) -> Iterator[None]:
        """Group mutations so that subscribers get one :class:`Changes` at the end (batches nest)."""
        if self._batch_depth == 0:
            self._pending = _Pending(list(self.ids), self._selection, self._settings)
        self._batch_depth += 1
        try:
            yield
        finally:
            self._batch_depth -= 1
            if self._batch_depth == 0:
                pending, self._pending = self._pending, None
                if pending is not None and pending.touched:
                    self._emit(pending)

    def _touch(self) -> _Pending:
        assert self._pending is not None, "mutations run inside batch()"
        self._pending.touched = True
        self._revision += 1
        return self._pending

    def _emit(self, p: _Pending) -> None:
        now = self.ids
        before = set(p.order)
        after = set(now)
        inserted = tuple(i for i in now if i not in before)
        removed = tuple(i for i in p.order if i not in after)
        changed = {i: frozenset(w) for i, w in p.changed.items() if i in before and i in after and w}
        reordered = [i for i in p.order if i in after] != [i for i in now if i in before]
        changes = Changes(
            revision=self._revision,
            inserted=inserted,
            removed=removed,
            changed=changed,
            reordered=reordered,
            selection=p.selection != self._selection,
            settings=p.settings != self._settings,
            reset=p.reset,
        )
        self.cache.retain((o.source, *self._settings.derivation_key(o.source)) for o in self._objects)
        errors: list[BaseException] = []
        for cb in list(self._subscribers):
            try:
                cb(changes)
            except Exception as e:  # one faulty view must not starve the others of the event
                errors.append(e)
        if errors:
            raise errors[0]

    # ------------------------------------------------------------------ editing (through the history)
    def push(self, cmd: Command) -> None:
        """Apply ``cmd`` and record it in the history (shortcut for ``doc.history.push``)."""
        self.history.push(cmd)

    def undo(self) -> None:
        """Undo the last step."""
        self.history.undo()

    def redo(self) -> None:
        """Redo the next step."""
        self.history.redo()

    def set_selection(self, ids: Iterable[int]) -> None:
        """Select the given objects (unknown ids are ignored). Selection is not an undoable edit."""
        sel = tuple(dict.fromkeys(i for i in ids if i in self._by_id))
        if sel == self._selection:
            return
        with self.batch():
            self._touch()
            self._selection = sel

    def new_id(self) -> int:
        """Reserve a fresh object id (ids are never reused, so undo can bring any object back)."""
        with self._id_lock:
            i = self._next_id
            self._next_id += 1
            return i

    def make_object(
        self,
        source: Source,
        name: str | None = None,
        *,
        style: Style | None = None,
        provenance: Provenance | None = None,
        georef: GeoRef | Literal["inputs"] | None = "inputs",
    ) -> DocObject:
        """Build a new object with a fresh id (not yet inserted: push an ``AddObject`` with it).

        ``georef`` defaults to what the provenance's inputs give (:func:`mrm.io.georef.result_georef`: the
        inputs' grid, scaled for DSS_α; None without provenance or for inputs on different grids), so every
        operation result keeps its inputs' place on the Earth without each caller passing it.
        """
        i = self.new_id()
        if georef == "inputs":
            georef = None
            if provenance is not None and provenance.inputs:
                ins = [self._by_id[k].georef if k in self._by_id else None for k in provenance.inputs]
                georef = result_georef(provenance.operation, provenance.params, ins)
        return DocObject(
            id=i,
            name=name if name is not None else f"Object {i}",
            source=source,
            style=style if style is not None else Style.for_index(i - 1),
            provenance=provenance,
            georef=georef,
        )

    # ------------------------------------------------------------------ limits
    def check_capacity(self, add: Iterable[DocObject] = (), remove: Iterable[int] = ()) -> None:
        """Refuse an edit that would take the document beyond the per-file limits (:mod:`mrm.core.limits`).

        Commands call this before they change anything, with the objects they will insert (or the new
        versions of objects they replace) and the ids they will remove or replace; the project file of the
        result is then guaranteed to save and reopen.

        Raises
        ------
        SizeLimitError, LimitError
            Too many pixels in the discrete sources together, or a project file too large.
        """
        pixels, nbytes = self._mask_pixels, self._file_bytes
        for i in dict.fromkeys(remove):
            o = self._by_id.get(i)
            if o is not None:
                pixels -= o.mask_pixels
                nbytes -= o.file_bytes
        for o in add:
            pixels += o.mask_pixels
            nbytes += o.file_bytes
        if pixels > self._mask_pixels or nbytes > self._file_bytes:
            limits.check_document_totals(pixels, nbytes)

    def _count(self, obj: DocObject, sign: int) -> None:
        self._mask_pixels += sign * obj.mask_pixels
        self._file_bytes += sign * obj.file_bytes

    # ------------------------------------------------------------------ low-level mutations (commands only)
    def insert_object(self, obj: DocObject, index: int | None = None) -> None:
        """Insert ``obj`` at ``index`` (default: on top). For commands; views push commands."""
        if obj.id in self._by_id:
            raise ValueError(f"an object with id {obj.id} already exists")
        with self.batch():
            p = self._touch()
            n = len(self._objects)
            idx = n if index is None else max(0, min(int(index), n))
            self._objects.insert(idx, obj)
            self._by_id[obj.id] = obj
            self._count(obj, +1)
            self._obj_rev[obj.id] = self._obj_rev.get(obj.id, 0) + 1
            with self._id_lock:
                self._next_id = max(self._next_id, obj.id + 1)
            if obj.id in p.order:  # removed and re-inserted in one batch: it may differ in every aspect
                aspects = ("source", "name", "style", "provenance", "georef")
                p.changed.setdefault(obj.id, set()).update(aspects)

    def remove_object(self, obj_id: int) -> tuple[DocObject, int]:
        """Remove an object; returns it and the position it had. For commands."""
        idx = self.index_of(obj_id)
        with self.batch():
            self._touch()
            obj = self._objects.pop(idx)
            del self._by_id[obj_id]
            self._count(obj, -1)
            self._obj_rev[obj_id] = self._obj_rev.get(obj_id, 0) + 1
            if obj_id in self._selection:
                self._selection = tuple(i for i in self._selection if i != obj_id)
        return obj, idx

    def replace_object(self, obj: DocObject) -> DocObject:
        """Replace the object with the same id by ``obj``; returns the old one. For commands."""
        old = self.get(obj.id)
        idx = self.index_of(obj.id)
        with self.batch():
            p = self._touch()
            self._objects[idx] = obj
            self._by_id[obj.id] = obj
            self._count(old, -1)
            self._count(obj, +1)
            what = p.changed.setdefault(obj.id, set())
            if old.source is not obj.source:
                what.add("source")
                self._obj_rev[obj.id] = self._obj_rev.get(obj.id, 0) + 1
            for name in ("name", "style", "provenance", "georef"):
                if getattr(old, name) != getattr(obj, name):
                    what.add(name)
        return old

    def set_order(self, ids: Sequence[int]) -> None:
        """Reorder the objects; ``ids`` must be a permutation of :attr:`ids`. For commands."""
        if sorted(ids) != sorted(self._by_id):
            raise ValueError("the new order must list every object exactly once")
        with self.batch():
            self._touch()
            self._objects = [self._by_id[i] for i in ids]

    def set_settings(self, settings: Settings) -> None:
        """Change the settings, re-deriving the objects whose derivations depend on what changed.

        Every object for a new model, the voxel objects for a new compact limit. For commands.
        """
        with self.batch():
            p = self._touch()
            for o in self._objects:
                if settings.derivation_key(o.source) != self._settings.derivation_key(o.source):
                    p.changed.setdefault(o.id, set()).add("derived")
                    self._obj_rev[o.id] = self._obj_rev.get(o.id, 0) + 1
            self._settings = settings

    def reset(
        self,
        objects: Iterable[DocObject],
        settings: Settings | None = None,
        selection: Iterable[int] = (),
        *,
        clean: bool = True,
    ) -> None:
        """Replace the whole content (open/revert/new), clearing the history; subscribers get ``reset``."""
        objs = list(objects)
        ids = [o.id for o in objs]
        if len(set(ids)) != len(ids):
            raise ValueError("object ids must be unique")
        with self.batch():
            p = self._touch()
            p.reset = True
            for o in self._objects:
                self._obj_rev[o.id] = self._obj_rev.get(o.id, 0) + 1
            self._objects = objs
            self._by_id = {o.id: o for o in objs}
            self._mask_pixels = sum(o.mask_pixels for o in objs)
            self._file_bytes = sum(o.file_bytes for o in objs)
            for o in objs:
                self._obj_rev[o.id] = self._obj_rev.get(o.id, 0) + 1
            self._settings = settings or Settings()
            self._selection = tuple(dict.fromkeys(i for i in selection if i in self._by_id))
            with self._id_lock:
                self._next_id = max([self._next_id, *[i + 1 for i in ids]])
            self.history.clear(clean=clean)
