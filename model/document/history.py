"""One undo history for the whole document: commands, macros, merging, a clean marker and limits.

A :class:`Command` knows how to apply itself to a document (:meth:`Command.do`) and how to revert that
(:meth:`Command.undo`); :class:`History` keeps the applied commands in order. The design follows Qt's
``QUndoStack`` (so the GUI can wrap it in actions one to one) with three additions the document needs:

* **macros** — a brush stroke or a drag is pushed as many small commands that form *one* undo step;
* **limits** in steps and in bytes (:meth:`Command.byte_size`): painting on a large object must not let the
  history grow without bound, so the oldest steps are dropped first;
* **listeners** — the GUI's undo/redo actions and the window's "modified" mark subscribe to state changes.

Derived representations never enter the history: commands hold only source data (immutable values, or the
compact deltas of :mod:`mrm.document.commands`), so undo is a swap of references or an XOR of a small mask.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from mrm.document.document import Document

#: Bytes charged for a command's own bookkeeping (object header, references), on top of its payload.
COMMAND_OVERHEAD = 128


class Command:
    """An undoable edit of a :class:`~mrm.document.Document`.

    Subclasses implement :meth:`do` and :meth:`undo`; both must leave the document exactly as it was before
    the other one ran (bit for bit), and :meth:`do` must either succeed completely or raise before changing
    anything, because a failed command is never pushed.

    Attributes
    ----------
    label : str
        Text shown in the Edit menu ("Undo Rename", ...).
    """

    label: str = "Edit"

    def do(self, doc: Document) -> None:
        """Apply the edit (first time and every redo)."""
        raise NotImplementedError

    def undo(self, doc: Document) -> None:
        """Revert the edit."""
        raise NotImplementedError

    def merge_with(self, other: Command) -> bool:
        """Absorb ``other``, which has just been applied after this command, into this one.

        Return True when merged: ``other`` is then dropped and undoing this command must revert both.
        The default never merges.
        """
        return False

    def is_obsolete(self) -> bool:
        """True when the command has no net effect (e.g. a drag that came back to where it started)."""
        return False

    def byte_size(self) -> int:
        """Approximate memory held by the command, for the history's byte limit."""
        return COMMAND_OVERHEAD


class Macro(Command):
    """Several commands applied and reverted as one step (a brush stroke, a drag, an import).

    Parameters
    ----------
    label : str
        Text of the undo step.
    """

    def __init__(self, label: str) -> None:
        self.label = label
        self.children: list[Command] = []

    def do(self, doc: Document) -> None:
        """Apply the children in order."""
        for c in self.children:
            c.do(doc)

    def undo(self, doc: Document) -> None:
        """Revert the children in reverse order."""
        for c in reversed(self.children):
            c.undo(doc)

    def is_obsolete(self) -> bool:
        """True when no child had an effect."""
        return all(c.is_obsolete() for c in self.children)

    def byte_size(self) -> int:
        """The children's sizes plus the macro's own bookkeeping."""
        return COMMAND_OVERHEAD + sum(c.byte_size() for c in self.children)


class History:
    """The linear undo history of one document.

    Parameters
    ----------
    doc : Document
        The document the commands act on.
    max_steps : int
        At most this many undo steps are kept; the oldest are dropped first.
    max_bytes : int
        The steps kept hold at most this many bytes (:meth:`Command.byte_size`), except that the most recent
        step is always kept whatever its size.

    Notes
    -----
    ``index`` counts the applied steps: steps ``[0, index)`` can be undone, ``[index, count)`` redone.
    The clean marker records the index at which the document matched its file; it becomes unreachable
    (``clean_index is None``) when the steps leading to it are dropped, so the document stays "modified"
    until the next save.
    """

    def __init__(self, doc: Document, max_steps: int = 1000, max_bytes: int = 512 * 2**20) -> None:
        if max_steps < 1 or max_bytes < 0:
            raise ValueError("history limits must be positive")
        self._doc = doc
        self.max_steps = int(max_steps)
        self.max_bytes = int(max_bytes)
        self._steps: list[Command] = []
        self._index = 0
        self._clean: int | None = 0
        self._macros: list[Macro] = []
        self._listeners: list[Callable[[], None]] = []

    # ------------------------------------------------------------------ state
    @property
    def index(self) -> int:
        """Number of applied steps."""
        return self._index

    @property
    def count(self) -> int:
        """Number of steps kept (applied and undone)."""
        return len(self._steps)

    @property
    def clean_index(self) -> int | None:
        """The index at which the document is clean, or None if that state can no longer be reached."""
        return self._clean

    @property
    def is_clean(self) -> bool:
        """True when the document matches the state last marked clean (e.g. its saved file)."""
        return self._clean == self._index and not self._macros

    @property
    def in_macro(self) -> bool:
        """True while a macro is open."""
        return bool(self._macros)

    def can_undo(self) -> bool:
        """True when there is a step to undo and no macro is open."""
        return self._index > 0 and not self._macros

    def can_redo(self) -> bool:
        """True when there is a step to redo and no macro is open."""
        return self._index < len(self._steps) and not self._macros

    def undo_label(self) -> str:
        """Label of the step :meth:`undo` would revert ('' if none)."""
        return self._steps[self._index - 1].label if self._index > 0 else ""

    def redo_label(self) -> str:
        """Label of the step :meth:`redo` would apply ('' if none)."""
        return self._steps[self._index].label if self._index < len(self._steps) else ""

    def byte_size(self) -> int:
        """Memory held by the steps kept (applied, undone and an open macro)."""
        return sum(s.byte_size() for s in self._steps) + sum(m.byte_size() for m in self._macros)

    def steps(self) -> tuple[Command, ...]:
        """The steps kept, oldest first."""
        return tuple(self._steps)

    # ------------------------------------------------------------------ listeners
    def subscribe(self, callback: Callable[[], None]) -> Callable[[], None]:
        """Call ``callback()`` whenever index, count, clean state or labels may have changed.

        Returns a function that unsubscribes.
        """
        self._listeners.append(callback)

        def unsubscribe() -> None:
            if callback in self._listeners:
                self._listeners.remove(callback)

        return unsubscribe

    def _notify(self) -> None:
        for cb in list(self._listeners):
            cb()

    # ------------------------------------------------------------------ editing
    def push(self, cmd: Command) -> None:
        """Apply ``cmd`` and record it as a new step (or as part of the open macro).

        If ``cmd.do`` raises, nothing is recorded and the exception propagates (the command guarantees that
        the document is unchanged). A command that merges into the previous one (:meth:`Command.merge_with`)
        extends that step instead of adding one; merging never crosses the clean marker, so "modified" stays
        truthful.
        """
        with self._doc.batch():
            cmd.do(self._doc)
        if self._macros:
            children = self._macros[-1].children
            if children and children[-1].merge_with(cmd):
                if children[-1].is_obsolete():
                    children.pop()
            elif not cmd.is_obsolete():
                children.append(cmd)
            self._notify()
            return
        if cmd.is_obsolete():  # it changed nothing: keep the redo tail, add no step
            self._notify()
            return
        self._drop_redo_tail()
        top = self._steps[-1] if self._index > 0 else None
        if top is not None and self._index != self._clean and top.merge_with(cmd):
            if top.is_obsolete():
                self._steps.pop()
                self._index -= 1
        else:
            self._steps.append(cmd)
            self._index += 1
        self._enforce_limits()
        self._notify()

    def _drop_redo_tail(self) -> None:
        if self._index < len(self._steps):
            del self._steps[self._index :]
            if self._clean is not None and self._clean > self._index:
                self._clean = None

    def _enforce_limits(self) -> None:
        drop = max(0, len(self._steps) - self.max_steps)
        sizes = [s.byte_size() for s in self._steps]
        total = sum(sizes[drop:])
        while total > self.max_bytes and drop < len(self._steps) - 1:
            total -= sizes[drop]
            drop += 1
        if drop:
            del self._steps[:drop]
            self._index = max(0, self._index - drop)
            if self._clean is not None:
                self._clean = self._clean - drop if self._clean >= drop else None

    def begin_macro(self, label: str) -> None:
        """Open a macro: commands pushed until :meth:`end_macro` form one step. Nested macros flatten."""
        self._macros.append(Macro(label))
        self._notify()

    def end_macro(self) -> None:
        """Close the innermost macro; the outermost one becomes a step (an empty macro is dropped)."""
        if not self._macros:
            raise RuntimeError("end_macro() without begin_macro()")
        m = self._macros.pop()
        if self._macros:
            if m.children:
                self._macros[-1].children.append(m)
            self._notify()
            return
        if m.children:
            self._drop_redo_tail()
            self._steps.append(m)
            self._index += 1
            self._enforce_limits()
        self._notify()

    @contextmanager
    def macro(self, label: str) -> Iterator[None]:
        """Context manager around :meth:`begin_macro` / :meth:`end_macro`.

        If the body raises, the commands already pushed in the macro are reverted and nothing is recorded,
        so a failed multi-step edit leaves the document as it was.
        """
        self.begin_macro(label)
        try:
            yield
        except BaseException:
            m = self._macros.pop()
            with self._doc.batch():
                m.undo(self._doc)
            self._notify()
            raise
        self.end_macro()

    def undo(self) -> None:
        """Revert the last applied step (no-op when there is none)."""
        if self._macros:
            raise RuntimeError("cannot undo while a macro is open")
        if self._index == 0:
            return
        step = self._steps[self._index - 1]
        with self._doc.batch():
            step.undo(self._doc)
        self._index -= 1
        self._notify()

    def redo(self) -> None:
        """Re-apply the next undone step (no-op when there is none)."""
        if self._macros:
            raise RuntimeError("cannot redo while a macro is open")
        if self._index >= len(self._steps):
            return
        step = self._steps[self._index]
        with self._doc.batch():
            step.do(self._doc)
        self._index += 1
        self._notify()

    def set_clean(self) -> None:
        """Mark the current state as clean (called once the document has been written to its file)."""
        self._clean = self._index
        self._notify()

    def clear(self, *, clean: bool = True) -> None:
        """Forget every step (used after loading a file).

        Parameters
        ----------
        clean : bool
            Whether the current state is the clean one: True after opening a project, False after restoring
            an autosave (the recovered edits are not in any saved file yet).
        """
        if self._macros:
            raise RuntimeError("cannot clear the history while a macro is open")
        self._steps.clear()
        self._index = 0
        self._clean = 0 if clean else None
        self._notify()
