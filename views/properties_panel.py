"""The object properties panel: name, colour, opacity and the vertex coordinates of the selected object.

Every edit made here is one of the model's commands pushed on the document's history — one undo step each:
``RenameObject``, ``RestyleObject`` (colour, opacity), ``MoveVertex`` (a typed coordinate) and
``DeleteVertex`` (Delete on a row). Coordinates are
shown as the shortest text that reads back as the same float, so what is shown is exactly what is stored;
a typed value that would make the polygon cross itself is refused with the reason and nothing changes.

A pixel object's vertices are those of its Euclidean representation R(A); moving one makes the polygon the
object's source (as the vertex tool does).
"""

from __future__ import annotations

import logging
from dataclasses import replace
from typing import Any

from PySide6 import QtCore, QtGui, QtWidgets

from mrm.core.errors import MRMError
from mrm.core.numbers import read_number
from mrm.document.commands import RenameObject, RestyleObject
from mrm.document.edits import DeleteVertex, MoveVertex
from mrm.views import geometry_edit as ge
from mrm.views.measure import num_text

log = logging.getLogger(__name__)
Qt = QtCore.Qt
_ROOT = QtCore.QModelIndex()

COLUMNS = ("polygon", "ring", "#", "x", "y")
_ROLES = frozenset((Qt.ItemDataRole.DisplayRole, Qt.ItemDataRole.EditRole, Qt.ItemDataRole.TextAlignmentRole))


class VertexModel(QtCore.QAbstractTableModel):
    """The vertices of one geometry (lazy: a table of 10⁵ rows costs only the rows drawn)."""

    edited = QtCore.Signal(object, float, float)  # VertexRef, x, y
    refused = QtCore.Signal(str)

    def __init__(self, parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.xy: Any = None
        self.geom: Any = None
        self.refs: Any = []

    def set_geometry(self, geom: Any, table: tuple[Any, Any] | None = None) -> None:
        """Show the vertices of ``geom``.

        ``table`` is its :func:`~mrm.views.geometry_edit.vertex_table` when already made (on a worker, for
        a big geometry).
        """
        if geom is self.geom:
            return  # the same value (immutable): keep the rows, and any editor open on them
        self.geom = geom
        self.beginResetModel()
        if geom is None or geom.is_empty:
            self.xy, self.refs = None, []
        else:
            self.xy, self.refs = table if table is not None else ge.vertex_table(geom)
        self.endResetModel()

    def rowCount(self, parent: QtCore.QModelIndex | QtCore.QPersistentModelIndex = _ROOT) -> int:
        return 0 if parent.isValid() else len(self.refs)

    def columnCount(self, parent: QtCore.QModelIndex | QtCore.QPersistentModelIndex = _ROOT) -> int:
        return 0 if parent.isValid() else len(COLUMNS)

    def headerData(self, section: int, orientation: Qt.Orientation, role: int = 0) -> object:
        if role == Qt.ItemDataRole.DisplayRole and orientation == Qt.Orientation.Horizontal:
            return COLUMNS[section]
        return None

    def data(self, index: QtCore.QModelIndex | QtCore.QPersistentModelIndex, role: int = 0) -> object:
        # The view asks about ten roles per cell at every paint: the ones never answered cost nothing.
        if role not in _ROLES or not index.isValid():
            return None
        r, c = index.row(), index.column()
        if role in (Qt.ItemDataRole.DisplayRole, Qt.ItemDataRole.EditRole):
            if c < 3:
                return self.refs[r][c]
            return num_text(float(self.xy[r, c - 3]))
        if role == Qt.ItemDataRole.TextAlignmentRole and c >= 3:
            return int(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
        return None

    def flags(self, index: QtCore.QModelIndex | QtCore.QPersistentModelIndex) -> Qt.ItemFlag:
        f = Qt.ItemFlag.ItemIsEnabled | Qt.ItemFlag.ItemIsSelectable
        if index.isValid() and index.column() >= 3:
            f |= Qt.ItemFlag.ItemIsEditable
        return f

    def setData(
        self, index: QtCore.QModelIndex | QtCore.QPersistentModelIndex, value: object, role: int = 0
    ) -> bool:
        if not index.isValid() or role != Qt.ItemDataRole.EditRole or index.column() < 3:
            return False
        r = index.row()
        try:
            # The one reader of numbers (mrm.core.numbers), rounded once to the float64 a vertex holds.
            v = float(read_number(str(value), "a coordinate"))
        except (MRMError, OverflowError) as e:
            self.refused.emit(str(e))
            return False
        x, y = float(self.xy[r, 0]), float(self.xy[r, 1])
        if index.column() == 3:
            x = v
        else:
            y = v
        if (x, y) == (float(self.xy[r, 0]), float(self.xy[r, 1])):
            return False
        ref = self.refs[r]
        # After the view has closed its editor: the edit resets this model (the geometry is a new value).
        QtCore.QTimer.singleShot(0, lambda: self.edited.emit(ref, x, y))
        return True


class VertexTable(QtWidgets.QTableView):
    """The vertex table, with its own keys.

    Here F2 edits the current coordinate (elsewhere it renames the object), Delete removes the current
    vertex (elsewhere it deletes the object) and Ctrl+C copies the selected cells as text (elsewhere it copies
    the object). The coordinates are shown whole — the exact float64 value, as :func:`repr` writes it — the
    x and y columns as wide as the values in sight (the table scrolls sideways when the panel is narrow).
    """

    deleteRequested = QtCore.Signal(int)  # row

    _OWN_KEYS = (Qt.Key.Key_F2, Qt.Key.Key_Delete, Qt.Key.Key_Backspace)
    #: The coordinate columns.
    XY = (3, 4)

    def __init__(self, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setTextElideMode(Qt.TextElideMode.ElideNone)  # never "10.162819…": the columns fit the values
        self._fit_timer = QtCore.QTimer(self)
        self._fit_timer.setSingleShot(True)
        self._fit_timer.setInterval(0)
        self._fit_timer.timeout.connect(self.fit_coordinates)
        self.verticalScrollBar().valueChanged.connect(lambda _v: self._fit_timer.start())

    def setModel(self, model: QtCore.QAbstractItemModel | None) -> None:
        super().setModel(model)
        if model is not None:
            model.modelReset.connect(self._fit_timer.start)
            model.dataChanged.connect(lambda *_a: self._fit_timer.start())
        self._fit_timer.start()

    def fit_coordinates(self) -> None:
        """Widen the x and y columns to the widest value in sight (a few dozen rows, never all of them)."""
        model = self.model()
        if model is None:
            return
        header = self.horizontalHeader()
        rows = model.rowCount()
        top = max(0, self.rowAt(0))
        bottom = self.rowAt(self.viewport().height() - 1)
        bottom = min(rows - 1, top + 200) if bottom < 0 else bottom
        fm = self.fontMetrics()
        pad = 2 * self.style().pixelMetric(QtWidgets.QStyle.PixelMetric.PM_FocusFrameHMargin) + 8
        for c in self.XY:
            title = str(model.headerData(c, Qt.Orientation.Horizontal, Qt.ItemDataRole.DisplayRole) or "")
            need = header.fontMetrics().horizontalAdvance(title)
            for r in range(top, bottom + 1):
                need = max(need, fm.horizontalAdvance(str(model.index(r, c).data() or "")))
            if header.sectionSize(c) < need + pad:
                header.resizeSection(c, need + pad)

    def showEvent(self, ev: QtGui.QShowEvent) -> None:
        super().showEvent(ev)
        self._fit_timer.start()

    def resizeEvent(self, ev: QtGui.QResizeEvent) -> None:
        super().resizeEvent(ev)
        self._fit_timer.start()

    def copy_selection(self) -> str:
        """The selected cells as text (tab between columns, a line per row), put on the clipboard."""
        indexes = sorted(self.selectedIndexes(), key=lambda i: (i.row(), i.column()))
        if not indexes and self.currentIndex().isValid():
            indexes = [self.currentIndex()]
        lines: dict[int, list[str]] = {}
        for i in indexes:
            lines.setdefault(i.row(), []).append(str(i.data() or ""))
        text = "\n".join("\t".join(cells) for cells in lines.values())
        if text:
            QtGui.QGuiApplication.clipboard().setText(text)
        return text

    def event(self, ev: QtCore.QEvent) -> bool:
        if ev.type() == QtCore.QEvent.Type.ShortcutOverride:
            assert isinstance(ev, QtGui.QKeyEvent)
            own = ev.key() in self._OWN_KEYS and ev.modifiers() == Qt.KeyboardModifier.NoModifier
            if own or ev.matches(QtGui.QKeySequence.StandardKey.Copy):
                ev.accept()
                return True
        return super().event(ev)

    def keyPressEvent(self, ev: QtGui.QKeyEvent) -> None:
        if ev.matches(QtGui.QKeySequence.StandardKey.Copy):
            self.copy_selection()
            ev.accept()
            return
        if ev.key() in (Qt.Key.Key_Delete, Qt.Key.Key_Backspace) and self.state() != self.State.EditingState:
            if self.currentIndex().isValid():
                self.deleteRequested.emit(self.currentIndex().row())
            ev.accept()
            return
        super().keyPressEvent(ev)


class PropertiesPanel(QtWidgets.QWidget):
    """The Properties dock."""

    def __init__(self, scene: Any, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("propertiesPanel")
        self.scene = scene
        self.obj_id: int | None = None
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(6, 6, 6, 6)
        self.title = QtWidgets.QLabel("Select an object to see and edit its properties.", self)
        self.title.setObjectName("propertiesTitle")
        self.title.setWordWrap(True)
        lay.addWidget(self.title)
        self.form_box = QtWidgets.QWidget(self)
        form = QtWidgets.QFormLayout(self.form_box)
        form.setContentsMargins(0, 0, 0, 0)
        self.name_edit = QtWidgets.QLineEdit(self.form_box)
        self.name_edit.setObjectName("propName")
        self.name_edit.setToolTip("The object's name (type it, then press Enter)")
        self.name_edit.textEdited.connect(self._name_typed)
        self.name_edit.editingFinished.connect(self._rename)
        #: The object a typed, not yet committed name is for (None: the field shows the stored name).
        self._naming: int | None = None
        form.addRow("Name", self.name_edit)
        crow = QtWidgets.QHBoxLayout()
        self.colour_button = QtWidgets.QToolButton(self.form_box)
        self.colour_button.setObjectName("propColourButton")
        self.colour_button.setToolTip("Choose the fill colour")
        self.colour_button.clicked.connect(self.choose_colour)
        self.colour_edit = QtWidgets.QLineEdit(self.form_box)
        self.colour_edit.setObjectName("propColour")
        self.colour_edit.setPlaceholderText("#rrggbb")
        self.colour_edit.setToolTip("Fill colour as #rrggbb (press Enter)")
        self.colour_edit.editingFinished.connect(self._colour_typed)
        crow.addWidget(self.colour_button)
        crow.addWidget(self.colour_edit, 1)
        form.addRow("Colour", crow)
        self.opacity = QtWidgets.QSpinBox(self.form_box)
        self.opacity.setObjectName("propOpacity")
        self.opacity.setRange(0, 100)
        self.opacity.setSuffix(" %")
        self.opacity.setKeyboardTracking(False)
        self.opacity.setToolTip("Fill opacity")
        self.opacity.valueChanged.connect(self._opacity_changed)
        form.addRow("Opacity", self.opacity)
        self.source_label = QtWidgets.QLabel("", self.form_box)
        self.source_label.setObjectName("propSource")
        self.source_label.setWordWrap(True)
        form.addRow("Source", self.source_label)
        lay.addWidget(self.form_box)
        self.vertex_note = QtWidgets.QLabel("", self)
        self.vertex_note.setWordWrap(True)
        self.vertex_note.setObjectName("propVertexNote")
        lay.addWidget(self.vertex_note)
        self.vertices = VertexModel(self)
        self.vertices.edited.connect(self._move_vertex)
        self.vertices.refused.connect(self._refused)
        self.table = VertexTable(self)
        self.table.setObjectName("propVertices")
        self.table.setModel(self.vertices)
        self.table.deleteRequested.connect(self._delete_vertex)
        self.table.verticalHeader().setVisible(False)
        self.table.verticalHeader().setDefaultSectionSize(self.fontMetrics().height() + 6)
        hdr = self.table.horizontalHeader()
        for c in range(3):
            hdr.setSectionResizeMode(c, QtWidgets.QHeaderView.ResizeMode.ResizeToContents)
        for c in VertexTable.XY:  # as wide as the exact values (VertexTable.fit_coordinates), never elided
            hdr.setSectionResizeMode(c, QtWidgets.QHeaderView.ResizeMode.Interactive)
        hdr.setStretchLastSection(True)
        self.table.setEditTriggers(
            QtWidgets.QAbstractItemView.EditTrigger.DoubleClicked
            | QtWidgets.QAbstractItemView.EditTrigger.EditKeyPressed
            | QtWidgets.QAbstractItemView.EditTrigger.AnyKeyPressed
        )
        lay.addWidget(self.table, 1)
        # A label map's legend (ADR 0033): each label's colour and pixel count, instead of a vertex table.
        self.legend = QtWidgets.QTreeWidget(self)
        self.legend.setObjectName("propLegend")
        self.legend.setRootIsDecorated(False)
        self.legend.setHeaderLabels(["label", "pixels"])
        self.legend.setVisible(False)
        lay.addWidget(self.legend, 1)
        self._legend_for: Any = None
        self.status = QtWidgets.QLabel("", self)
        self.status.setObjectName("propStatus")
        self.status.setWordWrap(True)
        lay.addWidget(self.status)
        self._syncing = False
        self._tabling: Any = None  # the geometry whose vertex table a worker is making
        scene.documentChanged.connect(self._doc_changed)
        scene.derivedReady.connect(self._derived_ready)
        self.refresh()

    # ------------------------------------------------------------------ document → panel
    def _doc_changed(self, ch: Any) -> None:
        if ch.selection or ch.reset or ch.removed or ch.settings or (self.obj_id in ch.changed):
            self.refresh()

    def _derived_ready(self, obj_id: int) -> None:
        if obj_id == self.obj_id and self.vertices.xy is None:
            self.refresh()

    def refresh(self) -> None:
        # Either dimension: a 3D object's name, colour and opacity are edited here too.
        obj = self.scene.selected()
        self.obj_id = obj.id if obj is not None else None
        self.form_box.setEnabled(obj is not None)
        self.table.setEnabled(obj is not None)
        self._syncing = True
        try:
            if obj is None:
                self.title.setText("Select an object to see and edit its properties.")
                self._naming = None
                self.name_edit.clear()
                self.colour_edit.clear()
                self.source_label.clear()
                self.vertex_note.clear()
                self.vertices.set_geometry(None)
                self.legend.setVisible(False)
                self.table.setVisible(True)
                return
            self.title.setText(f"<b>{obj.name}</b>")
            if self._naming != obj.id:
                # Another object (or nothing typed): show its name; a name typed for another object is
                # dropped, never given to this one.
                self._naming = None
                self.name_edit.setText(obj.name)
            fill = obj.style.fill[:7]
            self.colour_edit.setText(fill)
            pm = QtGui.QPixmap(16, 16)
            pm.fill(QtGui.QColor(fill))
            self.colour_button.setIcon(QtGui.QIcon(pm))
            self.opacity.setValue(round(obj.style.opacity * 100))
            from mrm.views.object_list import provenance_text, source_text

            src = source_text(obj)
            self.source_label.setText(
                f"{src} · {provenance_text(obj.provenance)}" if obj.provenance is not None else src
            )
            if obj.dimension == 3:  # no vertex table (yet): what it is and what its R is
                self.vertices.set_geometry(None)
                self.table.setVisible(False)
                self.legend.setVisible(False)
                self.vertex_note.setText(self._solid_note(obj))
                return
            labels = obj.kind == "labels"
            self.table.setVisible(not labels)
            self.legend.setVisible(labels)
            if labels:
                self.vertices.set_geometry(None)
                self._show_legend(obj)
                return
            geom = self.scene.get(obj.id, "euclidean")
            if geom is not None and self._table_on_worker(geom):
                self.vertices.set_geometry(None)
                self.vertex_note.setText("listing the vertices…")
                return
            self.vertices.set_geometry(geom)
            if geom is None:
                err = self.scene.error(obj.id, "euclidean")
                self.vertex_note.setText(err or "computing the polygon…")
            elif obj.kind == "discrete":
                self.vertex_note.setText(
                    f"{len(self.vertices.refs)} vertices of the continuation R(A); editing one makes the "
                    "polygon the object's source."
                )
            else:
                self.vertex_note.setText(
                    f"{len(self.vertices.refs)} vertices (double-click a coordinate, or F2, to type it)."
                )
        finally:
            self._syncing = False

    def _solid_note(self, obj: Any) -> str:
        """The note on a 3D object: its polyhedron's size (R(A) of voxels, made on a worker) and R's note."""
        where = "It is drawn in the 3D views (F3)."
        if obj.kind == "labels":
            return f"A label volume (3D). {where} `mrm polygonize` gives one closed mesh per region."
        poly = self.scene.get(obj.id, "euclidean")
        if poly is None:
            err = self.scene.error(obj.id, "euclidean")
            return f"{where} R(A): {err}" if err else f"{where} Computing R(A)…"
        size = f"{poly.n_triangles:,} triangles, {poly.n_vertices:,} vertices"
        if obj.kind == "euclidean":
            return f"A polyhedron of {size}. {where}"
        note = self.scene.r_note(obj.id)
        return f"R(A), exact (D(R(A)) = A): {size}. {where}" + (f" {note}." if note else "")

    #: Label maps with more pixels than this get their legend counted on a worker; at most this many labels
    #: are listed (the views colour the others alike: the colours cycle).
    LEGEND_SYNC = 1_000_000
    LEGEND_ROWS = 1000

    def _show_legend(self, obj: Any) -> None:
        """List a label map's labels with their colours and pixel counts (counted on a worker if big)."""
        from mrm.views.label_maps import legend_rows

        lm = obj.source
        if self._legend_for is lm:
            return
        self._legend_for = lm
        self.legend.clear()
        self.vertex_note.setText("counting the labels…")

        def show(rows: list[tuple[int, str, int]]) -> None:
            if self._legend_for is not lm:
                return
            items = []
            for label, colour, pixels in rows[: self.LEGEND_ROWS]:
                item = QtWidgets.QTreeWidgetItem([str(label), f"{pixels:,}"])
                pm = QtGui.QPixmap(12, 12)
                pm.fill(QtGui.QColor(colour))
                item.setIcon(0, QtGui.QIcon(pm))
                items.append(item)
            self.legend.addTopLevelItems(items)
            more = len(rows) - self.LEGEND_ROWS
            self.vertex_note.setText(
                f"Label map: {len(rows):,} labels, colours by label"
                + (f" (the first {self.LEGEND_ROWS:,} listed; {more:,} more)" if more > 0 else "")
                + ". Its polygons are its gauss subdivision; Edit ▸ Split into Objects gives one object "
                "per label."
            )

        runner = getattr(self.scene, "runner", None)
        if runner is None or lm.labels.size <= self.LEGEND_SYNC:
            show(legend_rows(lm))
        else:
            runner.submit("properties:legend", lambda _p: legend_rows(lm), on_result=show)

    #: Geometries with more coordinates than this get their vertex table made on a worker (about 50 ms on
    #: the GUI thread at this size).
    TABLE_SYNC = 50_000

    def _table_on_worker(self, geom: Any) -> bool:
        """True while the vertex table of ``geom`` is being made on a worker (it is shown when ready)."""
        import shapely

        runner = getattr(self.scene, "runner", None)
        if (
            runner is None
            or geom is self.vertices.geom
            or int(shapely.get_num_coordinates(geom)) <= self.TABLE_SYNC
        ):
            return False
        if self._tabling is geom:
            return True
        self._tabling = geom
        obj_id = self.obj_id

        def done(table: tuple[Any, Any]) -> None:
            if self._tabling is geom:
                self._tabling = None
            if obj_id == self.obj_id and self.scene.get(obj_id, "euclidean") is geom:
                self.vertices.set_geometry(geom, table)
                self.refresh()

        def failed(exc: BaseException) -> None:
            if self._tabling is geom:
                self._tabling = None
            raise exc

        runner.submit(
            "properties:vertices", lambda _p: ge.vertex_table(geom), on_result=done, on_error=failed
        )
        return True

    def is_busy(self) -> bool:
        """True while the vertex table is being made."""
        return self._tabling is not None

    # ------------------------------------------------------------------ panel → document (commands)
    def _push(self, cmd: Any) -> bool:
        try:
            self.scene.doc.push(cmd)
        except MRMError as e:
            self._refused(str(e))
            return False
        self.status.setText("")
        return True

    def _refused(self, text: str) -> None:
        self.status.setText(f"<span style='color:#c0392b'>refused: {text}</span>")

    def _current(self) -> Any:
        if self.obj_id is None or self.obj_id not in self.scene.doc:
            return None
        return self.scene.doc.get(self.obj_id)

    def _name_typed(self, _text: str) -> None:
        if self._naming is None:
            self._naming = self.obj_id  # the name being typed is for the object shown now

    def _rename(self) -> None:
        """Enter, or the field losing the focus: rename the object the name was typed for, if any was."""
        target, self._naming = self._naming, None
        if self._syncing or target is None or target not in self.scene.doc:
            return
        obj = self.scene.doc.get(target)
        name = self.name_edit.text().strip()
        if name and name != obj.name:
            self._push(RenameObject(obj.id, name))
        if target == self.obj_id:
            self.name_edit.setText(self.scene.doc.get(target).name)  # what is stored (an empty name: kept)

    def _colour_typed(self) -> None:
        obj = self._current()
        text = self.colour_edit.text().strip()
        if self._syncing or obj is None:
            return
        if not QtGui.QColor.isValidColorName(text) or not text.startswith("#") or len(text) != 7:
            self._refused(f"{text!r} is not a colour #rrggbb")
            return
        self.set_colour(text)

    def set_colour(self, colour: str) -> None:
        obj = self._current()
        if obj is None or colour.lower() == obj.style.fill[:7]:
            return
        self._push(RestyleObject(obj.id, replace(obj.style, fill=colour.lower())))

    def choose_colour(self) -> None:
        obj = self._current()
        if obj is None:
            return
        c = QtWidgets.QColorDialog.getColor(QtGui.QColor(obj.style.fill[:7]), self, f"Colour of {obj.name}")
        if c.isValid():
            self.set_colour(c.name())

    def _opacity_changed(self, value: int) -> None:
        obj = self._current()
        if self._syncing or obj is None:
            return
        new = value / 100.0
        if round(obj.style.opacity * 100) != value:
            self._push(RestyleObject(obj.id, replace(obj.style, opacity=new)))

    def _move_vertex(self, ref: Any, x: float, y: float) -> None:
        obj = self._current()
        if obj is not None:
            self._push(MoveVertex(obj.id, ref, (x, y)))

    def _delete_vertex(self, row: int) -> None:
        obj = self._current()
        if obj is not None and 0 <= row < len(self.vertices.refs):
            self._push(DeleteVertex(obj.id, self.vertices.refs[row]))

    def focus_name(self) -> None:
        self.name_edit.setFocus()
        self.name_edit.selectAll()
