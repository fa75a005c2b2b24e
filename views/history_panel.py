"""The History panel: the document's undo steps as a list, the current position marked; a click goes there.

It reads the model's history (:class:`mrm.document.history.History`: its steps, their labels, the current
index and the clean marker) and follows it live through the history's listener, which is called on every push,
undo, redo, merge and clear (a project opened or a new one started). Choosing a row undoes or redoes, one
history step at a time, until the document is at that row's state — so "modified", the clean marker and Redo
behave exactly as if the user had pressed Ctrl+Z or Ctrl+Shift+Z that many times.
"""

from __future__ import annotations

import logging
from collections.abc import Callable

from PySide6 import QtCore, QtGui, QtWidgets

from mrm.document import Document

log = logging.getLogger(__name__)
Qt = QtCore.Qt
_ROOT = QtCore.QModelIndex()

#: The first row: the state before any step kept in the history.
INITIAL_LABEL = "Open/New document"
#: Role of a row's relation to the current position: "done", "current" or "undone".
StateRole = Qt.ItemDataRole.UserRole + 1


class HistoryModel(QtCore.QAbstractListModel):
    """Row 0 is the document before any kept step; row k (k ≥ 1) the state after step k.

    The current row is the history's index; rows after it are undone steps (redo brings them back).
    """

    def __init__(self, doc: Document, parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self._labels: list[str] = []
        self._index = 0
        self._clean: int | None = 0
        self.reload()

    def reload(self) -> None:
        """Read the history again (labels, position, clean marker)."""
        h = self.doc.history
        self.beginResetModel()
        self._labels = [INITIAL_LABEL, *(s.label for s in h.steps())]
        self._index = h.index
        self._clean = h.clean_index
        self.endResetModel()

    @property
    def current_row(self) -> int:
        return self._index

    def rowCount(self, parent: QtCore.QModelIndex | QtCore.QPersistentModelIndex = _ROOT) -> int:
        return 0 if parent.isValid() else len(self._labels)

    def data(self, index: QtCore.QModelIndex | QtCore.QPersistentModelIndex, role: int = 0) -> object:
        if not index.isValid():
            return None
        row = index.row()
        state = "current" if row == self._index else ("undone" if row > self._index else "done")
        if role == Qt.ItemDataRole.DisplayRole:
            saved = "  (saved)" if row == self._clean else ""
            return f"{self._labels[row]}{saved}"
        if role == StateRole:
            return state
        if role == Qt.ItemDataRole.FontRole and state == "current":
            font = QtGui.QFont()
            font.setBold(True)
            return font
        if role == Qt.ItemDataRole.ForegroundRole and state == "undone":
            pal = QtWidgets.QApplication.palette()
            return pal.brush(QtGui.QPalette.ColorGroup.Disabled, QtGui.QPalette.ColorRole.Text)
        if role == Qt.ItemDataRole.ToolTipRole:
            if state == "current":
                return "The document is here"
            verb = "redo" if state == "undone" else "undo"
            return f"Click to {verb} up to here"
        return None


class HistoryPanel(QtWidgets.QWidget):
    """The list of history steps; choosing a row (click, arrows, Home/End) moves the document there.

    Parameters
    ----------
    doc : Document
        The window's document (kept for the window's life; a project switch clears its history).
    before : callable, optional
        Called before moving through the history (the window cancels a tool's gesture in progress).
    """

    def __init__(
        self,
        doc: Document,
        parent: QtWidgets.QWidget | None = None,
        *,
        before: Callable[[], object] | None = None,
    ) -> None:
        super().__init__(parent)
        self.setObjectName("historyPanel")
        self.doc = doc
        self.before = before
        self.model = HistoryModel(doc, self)
        self.view = QtWidgets.QListView(self)
        self.view.setObjectName("historyList")
        self.view.setModel(self.model)
        self.view.setUniformItemSizes(True)
        self.view.setEditTriggers(QtWidgets.QAbstractItemView.EditTrigger.NoEditTriggers)
        self.view.setSelectionMode(QtWidgets.QAbstractItemView.SelectionMode.SingleSelection)
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(self.view)
        self._updating = False
        self._moving = False
        self._unsubscribe = doc.history.subscribe(self.refresh)
        self.view.selectionModel().currentChanged.connect(self._chosen)
        self.refresh()

    def close_panel(self) -> None:
        """Stop following the history (the window is closing)."""
        self._unsubscribe()

    def refresh(self) -> None:
        """Show the history as it is now, the current row selected and in sight."""
        if self._moving:
            return  # once, when the move is over
        self._updating = True
        try:
            self.model.reload()
            idx = self.model.index(self.model.current_row, 0)
            self.view.setCurrentIndex(idx)
            self.view.scrollTo(idx)
        finally:
            self._updating = False

    def _chosen(self, current: QtCore.QModelIndex, _previous: QtCore.QModelIndex) -> None:
        if self._updating or not current.isValid():
            return
        self.go_to(current.row())

    def go_to(self, row: int) -> None:
        """Undo or redo, one step at a time, until the document is at ``row`` (0: before every step)."""
        h = self.doc.history
        if h.in_macro:
            self.refresh()  # an edit is being recorded: the history cannot move now
            return
        if self.before is not None:
            self.before()
        row = max(0, min(row, h.count))
        self._moving = True
        try:
            # One batch: the views redraw once for the whole move, not once per step.
            with self.doc.batch():
                while h.index > row and h.can_undo():
                    self.doc.undo()
                while h.index < row and h.can_redo():
                    self.doc.redo()
        finally:
            self._moving = False
            self.refresh()
        log.debug("history moved to step %d of %d", h.index, h.count)
