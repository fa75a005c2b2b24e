"""What the four views show: the document, live previews of edits in progress, derived representations.

The :class:`Scene` turns the document's plain-Python change events into Qt signals, keeps the *preview*
source of an object while a tool drags or paints it (the document itself changes only when the edit is
committed as one undo step), and hands out derived representations: at once when they are cached or cheap,
otherwise computed by the task runner off the GUI thread, the newest request winning.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from PySide6 import QtCore

from mrm.core.errors import MRMError
from mrm.document import Changes, DocObject, Document, Source, Style
from mrm.document.derive import SYNC_COST, Derived, Rep

if TYPE_CHECKING:
    from mrm.core.grids import PixelSet

#: The one look of every previewed result (a "ghost"): a neutral grey no object is given (not in the
#: palette of new objects), half transparent; the Euclidean view also draws its outline dashed. Ghosts are
#: drawn only in the discrete and Euclidean views, listed nowhere and never counted by Fit All.
GHOST_FILL = "#9a9a9a"
GHOST_STYLE = Style(fill=GHOST_FILL, opacity=0.5)


#: Pixel sets with boxes up to this many pixels are counted on the GUI thread when asked (a millisecond).
COUNT_SYNC = 4_000_000


def pixel_count(ps: PixelSet) -> int | None:
    """The number of pixels of ``ps`` for a label on the GUI thread; None while a worker has not counted it.

    Counting 10⁸ pixels takes tens of milliseconds: a big set is counted on the worker that makes its
    region (:func:`mrm.document.derive.region_from_pixels`), and kept by the set.
    """
    return ps.count if ps.mask.size <= COUNT_SYNC else ps.known_count


#: What each representation is called in the status bar's progress.
REP_WORDS = {
    "discrete": "pixels D(E)",
    "euclidean": "Euclidean shape R(A)",
    "region": "regions",
    "analytical": "digital straight segments",
}
#: The steps of a derivation, per kind of source: a Cancel takes effect between them.
DERIVATION_STEPS: dict[str, dict[str, tuple[Rep, ...]]] = {
    "discrete": {
        "discrete": ("discrete",),
        "euclidean": ("euclidean",),
        "region": ("region",),
        "analytical": ("region", "analytical"),
    },
    "euclidean": {
        "discrete": ("discrete",),
        "euclidean": ("euclidean",),
        "region": ("discrete", "region"),
        "analytical": ("discrete", "region", "analytical"),
    },
    # A label map (ADR 0033): its cells, its gauss subdivision; no analytical representation.
    "labels": {
        "discrete": ("discrete",),
        "euclidean": ("euclidean",),
        "region": ("region",),
        "analytical": ("analytical",),
    },
}
#: The text a view shows for a representation whose computation was cancelled.
CANCELLED = "not computed (cancelled)"


@dataclass(frozen=True)
class Phantom:
    """A result previewed but not yet in the document (an operation's live preview); ids are negative."""

    id: int
    name: str
    source: Source
    style: Style = field(default_factory=lambda: GHOST_STYLE)

    @property
    def kind(self) -> str:
        from mrm.core.grids import PixelSet

        return "discrete" if isinstance(self.source, PixelSet) else "euclidean"


#: Where the desktop raises the document's compact limit (the menu command of ``mrm.app.main_window``).
RAISE_COMPACT_LIMIT = "Edit ▸ Discretization Model ▸ Compact R Limit… raises it"


class Scene(QtCore.QObject):
    """The views' shared state.

    Signals
    -------
    documentChanged(Changes)
        After every batch of document edits.
    previewChanged(int)
        The preview source of an object was set or cleared.
    derivedReady(int)
        A representation of that object computed in the background is now available.
    segmentSelected(int, int, int)
        The analytical segment (object id, chain index, segment index) chosen in the table or a view; -1s
        when none.
    planeSegmentSelected(int, int)
        A 3D object's digital plane segment (object id, segment index) chosen in the table; -1s when none.
    """

    documentChanged = QtCore.Signal(object)
    previewChanged = QtCore.Signal(int)
    phantomsChanged = QtCore.Signal()
    derivedReady = QtCore.Signal(int)
    segmentSelected = QtCore.Signal(int, int, int)
    planeSegmentSelected = QtCore.Signal(int, int)

    def __init__(self, doc: Document, runner: Any, parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.runner = runner
        self._previews: dict[int, Derived] = {}
        self._errors: dict[tuple[int, str], str] = {}
        self.sync_cost = float(SYNC_COST)
        self.segment: tuple[int, int, int] = (-1, -1, -1)
        self.plane_segment: tuple[int, int] = (-1, -1)
        self._wanted: dict[str, Derived] = {}  # slot -> the entry being computed there
        self._phantoms: dict[int, tuple[Phantom, Derived]] = {}
        self._cancelled: dict[tuple[int, str], Derived] = {}  # (object, rep) -> the entry cancelled
        self._unsubscribe = doc.subscribe(self._on_changes)

    def close(self) -> None:
        self._unsubscribe()

    # ------------------------------------------------------------------ document
    def _on_changes(self, changes: Changes) -> None:
        if changes.reset:
            self._previews.clear()
        for i in changes.removed:
            self._previews.pop(i, None)
        self._errors = {k: v for k, v in self._errors.items() if self.has(k[0])}
        # A chosen segment belongs to the selected object as it is: gone with it, or with a change of it.
        if self._chosen_is_stale(self.segment[0], changes):
            self.select_segment(-1, -1, -1)
        if self._chosen_is_stale(self.plane_segment[0], changes):
            self.select_plane_segment(-1, -1)
        self.documentChanged.emit(changes)

    def _chosen_is_stale(self, obj_id: int, changes: Changes) -> bool:
        return obj_id != -1 and (
            obj_id not in self.doc
            or obj_id in changes.changed
            or (changes.selection and obj_id not in self.doc.selection)
        )

    def objects(self) -> tuple[DocObject | Phantom, ...]:
        """What the views draw, bottom first: the document's plane objects, then the previewed results."""
        return (*self.doc.plane_objects, *(p for p, _ in self._phantoms.values()))

    def has(self, obj_id: int) -> bool:
        return obj_id in self.doc or obj_id in self._phantoms

    # ------------------------------------------------------------------ phantoms (operation previews)
    def set_phantoms(self, items: list[tuple[str, Source]]) -> None:
        """Show ``(name, source)`` results as ghosts drawn above the document ([] clears)."""
        if not items and not self._phantoms:
            return
        self._phantoms = {}
        for k, (name, src) in enumerate(items):
            ph = Phantom(-(k + 1), name, src, GHOST_STYLE)
            self._phantoms[ph.id] = (ph, Derived.under(src, self.doc.settings))
        self.phantomsChanged.emit()

    def phantoms(self) -> list[Phantom]:
        return [p for p, _ in self._phantoms.values()]

    def selected(self) -> DocObject | None:
        """The first selected object, in either dimension (the inspector accounts for 3D results too)."""
        sel = self.doc.selection
        return self.doc.get(sel[0]) if sel and sel[0] in self.doc else None

    def primary(self) -> DocObject | None:
        """The selected object shown in detail (first of the selection), if the plane views show it."""
        sel = self.doc.selection
        obj = self.doc.get(sel[0]) if sel and sel[0] in self.doc else None
        return obj if obj is not None and obj.dimension == 2 else None

    # ------------------------------------------------------------------ previews
    def set_preview(self, obj_id: int, source: Source | None) -> None:
        """Show ``source`` in place of the object's source in every view (None: back to the document)."""
        if source is None:
            if self._previews.pop(obj_id, None) is None:
                return
        else:
            cur = self._previews.get(obj_id)
            if cur is not None and cur.source is source:
                return
            self._previews[obj_id] = Derived.under(source, self.doc.settings)
        self.previewChanged.emit(obj_id)

    def preview(self, obj_id: int) -> Derived | None:
        return self._previews.get(obj_id)

    def has_preview(self, obj_id: int) -> bool:
        return obj_id in self._previews

    def source(self, obj_id: int) -> Source:
        p = self._previews.get(obj_id)
        return p.source if p is not None else self.doc.get(obj_id).source

    def entry(self, obj_id: int) -> Derived:
        """The derived representations of what is shown for the object (its preview, else its source)."""
        if obj_id < 0:
            return self._phantoms[obj_id][1]
        p = self._previews.get(obj_id)
        return p if p is not None else self.doc.derived(obj_id)

    # ------------------------------------------------------------------ derived representations
    def get(self, obj_id: int, rep: Rep) -> Any | None:
        """Return representation ``rep`` of the object if available now; otherwise start computing it.

        When the computation ends, :attr:`derivedReady` is emitted for the object (if what it was computed
        for is still what is shown) and the next call returns the value. Returns None while computing or
        after an error (see :meth:`error`).
        """
        entry = self.entry(obj_id)
        value = entry.peek(rep)
        if value is not None:
            return value
        key = (obj_id, rep)
        if entry.is_ready(rep) or entry.estimated_cost(rep) < self.sync_cost:
            try:
                value = entry.get(rep)
            except (MRMError, ImportError) as e:
                self._errors[key] = _message(e)
                return None
            self._errors.pop(key, None)
            return value
        if self._cancelled.get(key) is entry:
            return None  # the user cancelled it: computed again only when asked (resume_derivations)
        slot = f"derive:{obj_id}:{rep}"
        if self.runner.is_busy(slot) and self._wanted.get(slot) is entry:
            return None  # already computing exactly this
        self._wanted[slot] = entry
        name = self._name(obj_id)

        def compute(progress: Any, e: Derived = entry) -> Any:
            # One step at a time, so that a Cancel stops between the steps (a kernel itself runs to its end).
            steps = DERIVATION_STEPS[e.kind][rep]
            for k, step in enumerate(steps):
                progress.update(
                    k / len(steps), f"{name}: computing the {REP_WORDS[step]} ({k + 1}/{len(steps)})"
                )
                e.get(step, progress)
            progress.update(1.0)
            return e.get(rep)

        def cancelled(e: Derived = entry) -> None:
            self._wanted.pop(slot, None)
            if self._still_shown(obj_id, e):
                self._cancelled[key] = e
                self.derivedReady.emit(obj_id)

        def done(_value: Any, e: Derived = entry) -> None:
            self._wanted.pop(slot, None)
            self._errors.pop(key, None)
            if self._still_shown(obj_id, e):
                self.derivedReady.emit(obj_id)

        def failed(exc: BaseException, e: Derived = entry) -> None:
            self._wanted.pop(slot, None)
            if not isinstance(exc, MRMError | ImportError):
                raise exc
            self._errors[key] = _message(exc)
            if self._still_shown(obj_id, e):
                self.derivedReady.emit(obj_id)

        self.runner.submit(
            slot,
            compute,
            on_result=done,
            on_error=failed,
            on_cancel=cancelled,
            label=f"{name}: computing the {REP_WORDS[rep]}",
            show_progress=True,
        )
        return None

    def _name(self, obj_id: int) -> str:
        if obj_id < 0:
            return "preview"
        return str(self.doc.get(obj_id).name) if obj_id in self.doc else "object"

    def cancel_derivations(self) -> bool:
        """Stop the derivations in progress (Cancel in the status bar); True if there were any.

        What is computed stays; what is not is shown as cancelled, until :meth:`resume_derivations`.
        """
        busy = [slot for slot in self._wanted if self.runner.is_busy(slot)]
        for slot in busy:
            self.runner.cancel(slot)
        return bool(busy)

    def is_cancelled(self, obj_id: int, rep: str) -> bool:
        """True when the user cancelled computing ``rep`` of what is shown for the object."""
        e = self._cancelled.get((obj_id, rep))
        return e is not None and self.has(obj_id) and self.entry(obj_id) is e

    def resume_derivations(self) -> None:
        """Compute again what was cancelled (the views ask for it at their next refresh)."""
        ids = {k[0] for k in self._cancelled}
        self._cancelled.clear()
        for i in ids:
            if self.has(i):
                self.derivedReady.emit(i)

    def _still_shown(self, obj_id: int, entry: Derived) -> bool:
        return self.has(obj_id) and self.entry(obj_id) is entry

    def error(self, obj_id: int, rep: str) -> str | None:
        """The message of the last failed (or cancelled) derivation of ``rep`` for the object, if any."""
        if self.is_cancelled(obj_id, rep):
            return CANCELLED
        return self._errors.get((obj_id, rep))

    def r_note(self, obj_id: int) -> str | None:
        """What the user is told about the object's R(A) (the safety net: exact, not compact), if anything.

        When the net is over the document's compact limit, the note ends with where the limit is raised.
        """
        if not self.has(obj_id):
            return None
        entry = self.entry(obj_id)
        note = entry.r_note
        return f"{note} ({RAISE_COMPACT_LIMIT})" if note is not None and entry.r_over_limit else note

    def is_computing(self) -> bool:
        return any(self.runner.is_busy(s) for s in self._wanted)

    # ------------------------------------------------------------------ analytical selection
    def select_segment(self, obj_id: int, chain: int, index: int) -> None:
        seg = (obj_id, chain, index)
        if seg != self.segment:
            self.segment = seg
            self.segmentSelected.emit(*seg)

    def select_plane_segment(self, obj_id: int, index: int) -> None:
        """Choose digital plane segment ``index`` of the 3D object ``obj_id`` (-1, -1: none)."""
        seg = (obj_id, index)
        if seg != self.plane_segment:
            self.plane_segment = seg
            self.planeSegmentSelected.emit(*seg)


def _message(e: BaseException) -> str:
    if isinstance(e, ImportError):
        # A part of the model not installed in this build: say what is missing, not a traceback.
        return f"not available ({e.name or e})"
    return str(e)
