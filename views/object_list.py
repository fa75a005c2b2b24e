"""The object list: visibility, colour, name and source representation of every object; drag to reorder.

The top row is the object drawn on top (the document's last). Every change made here is a command pushed
on the document's history: toggling visibility, choosing a colour, renaming, dropping a row elsewhere.
"""

from __future__ import annotations

import json
from dataclasses import replace

from PySide6 import QtCore, QtGui, QtWidgets

from mrm.core.errors import MRMError
from mrm.document import Changes, DocObject, Document
from mrm.document.commands import RemoveObjects, RenameObject, ReorderObjects, RestyleObject

MIME = "application/x-mrm-object-ids"

_ROOT = QtCore.QModelIndex()  # the invalid index: the model's root

COL_VISIBLE, COL_COLOUR, COL_NAME, COL_SOURCE = range(4)
HEADERS = ("", "", "Name", "Source")

SOURCE_TEXT = {"euclidean": "polygon", "discrete": "pixels", "labels": "label map"}
#: The same for 3D objects (docs/design.md §11), which the plane views do not draw.
SOURCE_TEXT_3D = {"discrete": "voxels (3D)", "labels": "label volume (3D)", "euclidean": "polyhedron (3D)"}


def source_text(o: DocObject) -> str:
    """What an object's source is, as the object list and the Properties panel say it."""
    return SOURCE_TEXT_3D[o.kind] if o.dimension == 3 else SOURCE_TEXT[o.kind]


#: How the Source column names the operation that made an object (its parameters follow).
OPERATION_TEXT = {
    "dss": "DSS",
    "discrete_rotation": "rotation",
    "simplify": "simplification",
    "union": "union",
    "corefine": "co-refinement",
}


def provenance_text(prov: object) -> str:
    """``DSS α = 5``, ``rotation 30°``, ``co-refinement A ∖ B``: what made an object, for people."""
    op = str(getattr(prov, "operation", ""))
    params = dict(getattr(prov, "params", {}) or {})
    name = OPERATION_TEXT.get(op, op.replace("_", " "))
    if "alpha" in params:
        return f"{name} α = {params['alpha']:g}" if isinstance(params["alpha"], float | int) else name
    if "angle" in params and isinstance(params["angle"], float | int):
        return f"{name} {params['angle']:g}°"
    if "part" in params:
        from mrm.ops.boolean import PART_TITLES

        return f"{name} {PART_TITLES.get(str(params['part']), params['part'])}"
    return name


class ObjectListModel(QtCore.QAbstractTableModel):
    """Rows = objects, top row drawn on top."""

    errorRaised = QtCore.Signal(str)

    def __init__(self, doc: Document, parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self._rows: list[int] = []
        self._reload()

    def _reload(self) -> None:
        self._rows = list(reversed(self.doc.ids))

    def on_changes(self, ch: Changes) -> None:
        if ch.reset or ch.inserted or ch.removed or ch.reordered:
            self.beginResetModel()
            self._reload()
            self.endResetModel()
            return
        for i in ch.changed:
            if i in self._rows:
                r = self._rows.index(i)
                self.dataChanged.emit(self.index(r, 0), self.index(r, len(HEADERS) - 1))

    def obj(self, row: int) -> DocObject:
        return self.doc.get(self._rows[row])

    def row_of(self, obj_id: int) -> int:
        return self._rows.index(obj_id)

    def ids(self) -> list[int]:
        return list(self._rows)

    # ------------------------------------------------------------------ read
    def rowCount(self, parent: QtCore.QModelIndex | QtCore.QPersistentModelIndex = _ROOT) -> int:
        return 0 if parent.isValid() else len(self._rows)

    def columnCount(self, parent: QtCore.QModelIndex | QtCore.QPersistentModelIndex = _ROOT) -> int:
        return 0 if parent.isValid() else len(HEADERS)

    def headerData(self, section: int, orientation: QtCore.Qt.Orientation, role: int = 0) -> object:
        if orientation == QtCore.Qt.Orientation.Horizontal and role == QtCore.Qt.ItemDataRole.DisplayRole:
            return HEADERS[section]
        return None

    def data(self, index: QtCore.QModelIndex | QtCore.QPersistentModelIndex, role: int = 0) -> object:
        if not index.isValid():
            return None
        o = self.obj(index.row())
        c = index.column()
        R = QtCore.Qt.ItemDataRole
        if c == COL_VISIBLE and role == R.CheckStateRole:
            return QtCore.Qt.CheckState.Checked if o.style.visible else QtCore.Qt.CheckState.Unchecked
        if c == COL_COLOUR and role == R.DecorationRole:
            return QtGui.QColor(o.style.fill)
        if c == COL_NAME and role in (R.DisplayRole, R.EditRole):
            return o.name
        if c == COL_SOURCE and role == R.DisplayRole:
            text = source_text(o)
            return f"{text} · {provenance_text(o.provenance)}" if o.provenance is not None else text
        if role == R.ToolTipRole:
            rep = {"euclidean": "Euclidean (polygons)", "labels": "label map (labels)"}.get(
                o.kind, "discrete (pixels)"
            )
            tip = f"{o.name}\nsource: the {rep} representation"
            if o.provenance is not None:
                tip += f"\nproduced by {provenance_text(o.provenance)}"
                if o.provenance.params:
                    tip += " (" + ", ".join(f"{k}={v}" for k, v in o.provenance.params.items()) + ")"
            return tip
        if c == COL_SOURCE and role == R.ForegroundRole:
            return QtGui.QPalette().color(QtGui.QPalette.ColorRole.PlaceholderText)
        return None

    def flags(self, index: QtCore.QModelIndex | QtCore.QPersistentModelIndex) -> QtCore.Qt.ItemFlag:
        F = QtCore.Qt.ItemFlag
        if not index.isValid():
            return F.ItemIsDropEnabled
        f = F.ItemIsEnabled | F.ItemIsSelectable | F.ItemIsDragEnabled
        if index.column() == COL_VISIBLE:
            f |= F.ItemIsUserCheckable
        if index.column() == COL_NAME:
            f |= F.ItemIsEditable
        return f

    # ------------------------------------------------------------------ write (commands)
    def _push(self, cmd: object) -> bool:
        try:
            self.doc.push(cmd)  # type: ignore[arg-type]
        except MRMError as e:
            self.errorRaised.emit(str(e))
            return False
        return True

    def setData(
        self, index: QtCore.QModelIndex | QtCore.QPersistentModelIndex, value: object, role: int = 0
    ) -> bool:
        if not index.isValid():
            return False
        o = self.obj(index.row())
        R = QtCore.Qt.ItemDataRole
        if index.column() == COL_VISIBLE and role == R.CheckStateRole:
            visible = QtCore.Qt.CheckState(value) == QtCore.Qt.CheckState.Checked
            return self._push(RestyleObject(o.id, replace(o.style, visible=visible)))
        if index.column() == COL_NAME and role == R.EditRole:
            name = str(value).strip()
            if not name or name == o.name:
                return False
            return self._push(RenameObject(o.id, name))
        return False

    # ------------------------------------------------------------------ drag and drop
    def supportedDropActions(self) -> QtCore.Qt.DropAction:
        return QtCore.Qt.DropAction.MoveAction

    def supportedDragActions(self) -> QtCore.Qt.DropAction:
        return QtCore.Qt.DropAction.MoveAction

    def mimeTypes(self) -> list[str]:
        return [MIME]

    def mimeData(self, indexes: list[QtCore.QModelIndex]) -> QtCore.QMimeData:  # type: ignore[override]
        rows = sorted({i.row() for i in indexes if i.isValid()})
        md = QtCore.QMimeData()
        md.setData(MIME, QtCore.QByteArray(json.dumps([self._rows[r] for r in rows]).encode()))
        return md

    def dropMimeData(
        self,
        data: QtCore.QMimeData,
        action: QtCore.Qt.DropAction,
        row: int,
        column: int,
        parent: QtCore.QModelIndex | QtCore.QPersistentModelIndex,
    ) -> bool:
        if action != QtCore.Qt.DropAction.MoveAction or not data.hasFormat(MIME):
            return False
        try:
            moved = [int(i) for i in json.loads(bytes(data.data(MIME).data()).decode())]
        except (ValueError, TypeError):
            return False
        if row < 0:
            row = parent.row() if parent.isValid() else len(self._rows)
        self.move_rows(moved, row)
        # The command already reordered the document and reset the model: tell the view not to remove rows.
        return False

    def move_rows(self, moved: list[int], row: int) -> None:
        """Put the objects ``moved`` (ids) before list row ``row`` (top row = 0), as one undo step."""
        moved = [i for i in moved if i in self._rows]
        if not moved:
            return
        before = self._rows[:row]
        rows = [i for i in before if i not in moved] + moved + [i for i in self._rows[row:] if i not in moved]
        if rows != self._rows:
            self._push(
                ReorderObjects(
                    list(reversed(rows)), label="Move object" if len(moved) == 1 else "Move objects"
                )
            )


class ColourDelegate(QtWidgets.QStyledItemDelegate):
    """Draws the colour column as a rounded swatch."""

    def paint(
        self,
        painter: QtGui.QPainter,
        option: QtWidgets.QStyleOptionViewItem,
        index: QtCore.QModelIndex | QtCore.QPersistentModelIndex,
    ) -> None:
        if index.column() != COL_COLOUR:
            super().paint(painter, option, index)
            return
        QtWidgets.QApplication.style().drawPrimitive(
            QtWidgets.QStyle.PrimitiveElement.PE_PanelItemViewItem, option, painter, option.widget
        )
        colour = index.data(QtCore.Qt.ItemDataRole.DecorationRole)
        r = option.rect.adjusted(4, 4, -4, -4)
        side = min(r.width(), r.height())
        r = QtCore.QRect(r.center().x() - side // 2, r.center().y() - side // 2, side, side)
        painter.save()
        painter.setRenderHint(QtGui.QPainter.RenderHint.Antialiasing)
        painter.setPen(QtGui.QPen(QtGui.QColor(0, 0, 0, 90)))
        painter.setBrush(QtGui.QColor(colour))
        painter.drawRoundedRect(r, 3, 3)
        painter.restore()


class ObjectList(QtWidgets.QWidget):
    """The dock content: the list, plus buttons to raise, lower and delete."""

    errorRaised = QtCore.Signal(str)

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("objectList")
        self.doc = doc
        self.model = ObjectListModel(doc, self)
        self.model.errorRaised.connect(self.errorRaised)
        self.view = QtWidgets.QTreeView(self)
        self.view.setObjectName("objectTree")
        self.view.setModel(self.model)
        self.view.setRootIsDecorated(False)
        self.view.setUniformRowHeights(True)
        self.view.setAlternatingRowColors(True)
        self.view.setSelectionMode(QtWidgets.QAbstractItemView.SelectionMode.ExtendedSelection)
        self.view.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectionBehavior.SelectRows)
        self.view.setDragDropMode(QtWidgets.QAbstractItemView.DragDropMode.InternalMove)
        self.view.setDefaultDropAction(QtCore.Qt.DropAction.MoveAction)
        self.view.setDragEnabled(True)
        self.view.setAcceptDrops(True)
        self.view.setDropIndicatorShown(True)
        self.view.setEditTriggers(
            QtWidgets.QAbstractItemView.EditTrigger.DoubleClicked
            | QtWidgets.QAbstractItemView.EditTrigger.EditKeyPressed
        )
        self.view.setItemDelegate(ColourDelegate(self.view))
        hdr = self.view.header()
        hdr.setStretchLastSection(False)
        hdr.setSectionResizeMode(COL_VISIBLE, QtWidgets.QHeaderView.ResizeMode.Fixed)
        hdr.setSectionResizeMode(COL_COLOUR, QtWidgets.QHeaderView.ResizeMode.Fixed)
        hdr.setSectionResizeMode(COL_NAME, QtWidgets.QHeaderView.ResizeMode.Stretch)
        # The Source column takes what its text needs, up to 45 % of the list and never room a name needs:
        # the names come first in a narrow panel (the whole source text is in the tooltip).
        hdr.setSectionResizeMode(COL_SOURCE, QtWidgets.QHeaderView.ResizeMode.Interactive)
        hdr.resizeSection(COL_VISIBLE, 28)
        hdr.resizeSection(COL_COLOUR, 26)
        self.model.modelReset.connect(self._fit_source_column)
        self.model.dataChanged.connect(lambda *_a: self._fit_source_column())
        self.view.clicked.connect(self._clicked)
        self.view.selectionModel().selectionChanged.connect(self._selection_from_view)
        self.model.modelReset.connect(self._selection_from_doc)

        bar = QtWidgets.QHBoxLayout()
        bar.setContentsMargins(0, 0, 0, 0)
        self.raise_button = self._button(
            "▲", "Raise the selected objects (drawn above the others)", self.raise_selected
        )
        self.lower_button = self._button("▼", "Lower the selected objects", self.lower_selected)
        self.delete_button = self._button("✕", "Delete the selected objects", self.delete_selected)
        bar.addWidget(self.raise_button)
        bar.addWidget(self.lower_button)
        bar.addStretch(1)
        bar.addWidget(self.delete_button)
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(4, 4, 4, 4)
        lay.setSpacing(4)
        lay.addWidget(self.view, 1)
        lay.addLayout(bar)
        self._syncing = False

    def _fit_source_column(self) -> None:
        rows = self.model.rowCount()
        need = self.view.sizeHintForColumn(COL_SOURCE) if rows else 60
        hdr = self.view.header()
        width = self.view.viewport().width()
        # The names first: the Source column gets what the longest name leaves, at most 45 % of the list.
        names = self.view.sizeHintForColumn(COL_NAME) if rows else 0
        room = width - hdr.sectionSize(COL_VISIBLE) - hdr.sectionSize(COL_COLOUR) - names
        hdr.resizeSection(COL_SOURCE, max(50, min(need, int(width * 0.45), room)))

    def resizeEvent(self, ev: QtGui.QResizeEvent) -> None:
        super().resizeEvent(ev)
        self._fit_source_column()

    def _button(self, text: str, tip: str, slot: object) -> QtWidgets.QToolButton:
        b = QtWidgets.QToolButton(self)
        b.setText(text)
        b.setToolTip(tip)
        b.setAutoRaise(True)
        b.clicked.connect(slot)
        return b

    # ------------------------------------------------------------------ document → view
    def on_changes(self, ch: Changes) -> None:
        self.model.on_changes(ch)
        if ch.selection or ch.reset:
            self._selection_from_doc()

    def _selection_from_doc(self) -> None:
        if self._syncing:
            return
        self._syncing = True
        try:
            sm = self.view.selectionModel()
            sel = QtCore.QItemSelection()
            for i in self.doc.selection:
                if i in self.model.ids():
                    r = self.model.row_of(i)
                    sel.select(self.model.index(r, 0), self.model.index(r, len(HEADERS) - 1))
            sm.select(sel, QtCore.QItemSelectionModel.SelectionFlag.ClearAndSelect)
            if self.doc.selection and self.doc.selection[0] in self.model.ids():
                idx = self.model.index(self.model.row_of(self.doc.selection[0]), COL_NAME)
                sm.setCurrentIndex(idx, QtCore.QItemSelectionModel.SelectionFlag.NoUpdate)
                self.view.scrollTo(idx)
        finally:
            self._syncing = False

    # ------------------------------------------------------------------ view → document
    def _selection_from_view(self, *_args: object) -> None:
        if self._syncing:
            return
        rows = sorted({i.row() for i in self.view.selectionModel().selectedRows()})
        ids = [self.model.ids()[r] for r in rows]
        cur = self.view.selectionModel().currentIndex()
        if cur.isValid() and cur.row() in rows:
            first = self.model.ids()[cur.row()]
            ids = [first] + [i for i in ids if i != first]
        self._syncing = True
        try:
            self.doc.set_selection(ids)
        finally:
            self._syncing = False

    def _clicked(self, index: QtCore.QModelIndex) -> None:
        if index.column() == COL_COLOUR:
            self.choose_colour(self.model.obj(index.row()).id)

    def choose_colour(self, obj_id: int) -> None:
        o = self.doc.get(obj_id)
        c = QtWidgets.QColorDialog.getColor(QtGui.QColor(o.style.fill), self, f"Colour of {o.name}")
        if c.isValid():
            self.model._push(RestyleObject(o.id, replace(o.style, fill=c.name())))

    def raise_selected(self) -> None:
        self._shift(-1)

    def lower_selected(self) -> None:
        self._shift(+1)

    def _shift(self, step: int) -> None:
        ids = self.model.ids()
        sel = [i for i in ids if i in self.doc.selection]
        if not sel:
            return
        rows = [ids.index(i) for i in sel]
        target = max(0, min(rows) - 1) if step < 0 else min(len(ids), max(rows) + 2)
        self.model.move_rows(sel, target)

    def delete_selected(self) -> None:
        if self.doc.selection:
            self.model._push(RemoveObjects(list(self.doc.selection)))
