"""Binds the document's single history to the Undo and Redo actions and the window's modified mark."""

from __future__ import annotations

from collections.abc import Callable

from PySide6 import QtCore, QtGui

from mrm.document import Document


class UndoAdapter(QtCore.QObject):
    """Keeps the actions' enabled state and text ("Undo Paint") in step with the document's history.

    Signals
    -------
    cleanChanged(bool)
        The document became clean (saved state) or modified.
    """

    cleanChanged = QtCore.Signal(bool)

    def __init__(
        self,
        doc: Document,
        undo: QtGui.QAction,
        redo: QtGui.QAction,
        parent: QtCore.QObject | None = None,
        *,
        before: Callable[[], bool] | None = None,
    ) -> None:
        super().__init__(parent)
        self.doc = doc
        self.undo_action = undo
        self.redo_action = redo
        #: Called before undo/redo; returning True means "handled" (a tool cancelled its gesture instead).
        self.before = before
        self._clean: bool | None = None
        undo.triggered.connect(self.undo)
        redo.triggered.connect(self.redo)
        self._unsubscribe = doc.history.subscribe(self.update)
        self.update()

    def close(self) -> None:
        self._unsubscribe()

    def undo(self) -> None:
        if self.before is not None and self.before():
            return
        if self.doc.history.can_undo():
            self.doc.undo()

    def redo(self) -> None:
        if self.before is not None and self.before():
            return
        if self.doc.history.can_redo():
            self.doc.redo()

    def update(self) -> None:
        h = self.doc.history
        self.undo_action.setEnabled(h.can_undo())
        self.redo_action.setEnabled(h.can_redo())
        u, r = h.undo_label(), h.redo_label()
        self.undo_action.setText(f"&Undo {u}" if u else "&Undo")
        self.redo_action.setText(f"&Redo {r}" if r else "&Redo")
        # The toolbar keeps its short label; the tooltip says what would be undone or redone.
        self.undo_action.setIconText("Undo")
        self.redo_action.setIconText("Redo")
        self.undo_action.setToolTip(f"Undo {u}" if u else "Nothing to undo")
        self.redo_action.setToolTip(f"Redo {r}" if r else "Nothing to redo")
        self.undo_action.setStatusTip(f"Undo {u}" if u else "Nothing to undo")
        self.redo_action.setStatusTip(f"Redo {r}" if r else "Nothing to redo")
        clean = h.is_clean
        if clean != self._clean:
            self._clean = clean
            self.cleanChanged.emit(clean)
