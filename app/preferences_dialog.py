"""The preferences dialog: model of new projects, theme and colours, brush defaults, autosave, shortcuts."""

from __future__ import annotations

from PySide6 import QtCore, QtGui, QtWidgets

from mrm.app.actions import ActionRegistry
from mrm.app.application import theme_controller
from mrm.app.settings import Preferences
from mrm.core.limits import MAX_OBJECT_PIXELS
from mrm.core.models import Model

#: The entry the pixel-limit message points at (File ▸ Preferences ▸ General).
PIXEL_LIMIT_LABEL = "Largest operation result"


class PreferencesDialog(QtWidgets.QDialog):
    """Edits :class:`Preferences`; changes apply on OK."""

    def __init__(
        self, prefs: Preferences, actions: ActionRegistry, parent: QtWidgets.QWidget | None = None
    ) -> None:
        super().__init__(parent)
        self.setObjectName("preferencesDialog")
        self.setWindowTitle("Preferences")
        self.prefs = prefs
        self.registry = actions
        tabs = QtWidgets.QTabWidget(self)
        tabs.addTab(self._general(), "General")
        tabs.addTab(self._appearance(), "Appearance")
        tabs.addTab(self._shortcuts(), "Shortcuts")
        buttons = QtWidgets.QDialogButtonBox(
            QtWidgets.QDialogButtonBox.StandardButton.Ok | QtWidgets.QDialogButtonBox.StandardButton.Cancel,
            self,
        )
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        lay = QtWidgets.QVBoxLayout(self)
        lay.addWidget(tabs)
        lay.addWidget(buttons)
        self.resize(560, 520)

    # ------------------------------------------------------------------ pages
    def _general(self) -> QtWidgets.QWidget:
        w = QtWidgets.QWidget(self)
        f = QtWidgets.QFormLayout(w)
        self.model = QtWidgets.QComboBox(w)
        self.model.setObjectName("prefModel")
        self.model.addItems(list(Model.names()))
        self.model.setCurrentText(self.prefs.default_model)
        self.model.setToolTip("; ".join(f"{m}: {m.kernel}" for m in Model))
        f.addRow("Discretization model of new projects", self.model)
        self.brush = QtWidgets.QSpinBox(w)
        self.brush.setObjectName("prefBrush")
        self.brush.setRange(1, 256)
        self.brush.setSuffix(" px")
        self.brush.setValue(self.prefs.brush_size)
        f.addRow("Brush size", self.brush)
        self.brush_shape = QtWidgets.QComboBox(w)
        self.brush_shape.addItems(["round", "square"])
        self.brush_shape.setCurrentText(self.prefs.brush_shape)
        f.addRow("Brush shape", self.brush_shape)
        self.snap = QtWidgets.QCheckBox("Snap to the vertices and edges of objects", w)
        self.snap.setObjectName("prefSnap")
        self.snap.setChecked(self.prefs.snap_to_objects)
        self.snap.setToolTip("Also View ▸ Snap to Objects (Shift+S); hold Alt to place a point freely")
        f.addRow("Drawing", self.snap)
        self.autosave = QtWidgets.QSpinBox(w)
        self.autosave.setObjectName("prefAutosave")
        self.autosave.setRange(0, 3600)
        self.autosave.setSuffix(" s")
        self.autosave.setSpecialValueText("off")
        self.autosave.setValue(self.prefs.autosave_seconds)
        f.addRow("Autosave unsaved work every", self.autosave)
        self.pixel_limit = QtWidgets.QDoubleSpinBox(w)
        self.pixel_limit.setObjectName("prefPixelLimit")
        self.pixel_limit.setDecimals(0)
        # Up to the largest pixel object a document holds (ADR 0010): a higher setting could only fail later.
        self.pixel_limit.setRange(1_000, MAX_OBJECT_PIXELS)
        self.pixel_limit.setSingleStep(10_000_000)
        self.pixel_limit.setGroupSeparatorShown(True)
        self.pixel_limit.setSuffix(" pixels")
        self.pixel_limit.setValue(self.prefs.pixel_limit)
        self.pixel_limit.setToolTip(
            "An operation whose result would be larger is refused before it runs (memory: about one byte "
            f"per pixel for each representation). At most {MAX_OBJECT_PIXELS:,} pixels, the largest pixel "
            "object a document holds."
        )
        f.addRow(PIXEL_LIMIT_LABEL, self.pixel_limit)
        return w

    def _appearance(self) -> QtWidgets.QWidget:
        w = QtWidgets.QWidget(self)
        f = QtWidgets.QFormLayout(w)
        self.theme = QtWidgets.QComboBox(w)
        self.theme.setObjectName("prefTheme")
        self.theme.addItems(["system", "light", "dark"])
        self.theme.setCurrentText(self.prefs.theme)
        f.addRow("Theme", self.theme)
        self.grid = QtWidgets.QDoubleSpinBox(w)
        self.grid.setRange(2.0, 100.0)
        self.grid.setSuffix(" screen px per pixel")
        self.grid.setValue(self.prefs.pixel_grid_threshold)
        f.addRow("Show the pixel grid from", self.grid)
        self.colour_buttons: list[QtWidgets.QPushButton] = []
        row = QtWidgets.QHBoxLayout()
        for c in self.prefs.object_colours():
            b = QtWidgets.QPushButton(w)
            b.setFixedSize(26, 22)
            self._set_button_colour(b, c)
            b.clicked.connect(lambda _c=False, btn=b: self._pick(btn))
            row.addWidget(b)
            self.colour_buttons.append(b)
        row.addStretch(1)
        f.addRow("Colours of new objects", row)
        return w

    def _shortcuts(self) -> QtWidgets.QWidget:
        w = QtWidgets.QWidget(self)
        lay = QtWidgets.QVBoxLayout(w)
        self.table = QtWidgets.QTableWidget(w)
        self.table.setObjectName("shortcutTable")
        ids = self.registry.ids()
        self.table.setColumnCount(2)
        self.table.setRowCount(len(ids))
        self.table.setHorizontalHeaderLabels(["Command", "Shortcut"])
        self.table.verticalHeader().hide()
        self.table.horizontalHeader().setSectionResizeMode(0, QtWidgets.QHeaderView.ResizeMode.Stretch)
        self.editors: dict[str, QtWidgets.QKeySequenceEdit] = {}
        for r, aid in enumerate(ids):
            a = self.registry[aid]
            item = QtWidgets.QTableWidgetItem(a.text().replace("&", ""))
            item.setToolTip(aid)
            item.setFlags(QtCore.Qt.ItemFlag.ItemIsEnabled)
            self.table.setItem(r, 0, item)
            ed = QtWidgets.QKeySequenceEdit(a.shortcut(), self.table)
            ed.setObjectName(f"shortcut_{aid}")
            self.table.setCellWidget(r, 1, ed)
            self.editors[aid] = ed
        lay.addWidget(self.table)
        reset = QtWidgets.QPushButton("Restore defaults", w)
        reset.clicked.connect(self._reset_shortcuts)
        lay.addWidget(reset, 0, QtCore.Qt.AlignmentFlag.AlignRight)
        return w

    # ------------------------------------------------------------------ helpers
    def _set_button_colour(self, b: QtWidgets.QPushButton, c: str) -> None:
        b.setProperty("colour", c)
        b.setStyleSheet(f"background-color: {c}; border: 1px solid rgba(0,0,0,90); border-radius: 3px;")

    def _pick(self, b: QtWidgets.QPushButton) -> None:
        c = QtWidgets.QColorDialog.getColor(QtGui.QColor(b.property("colour")), self, "Object colour")
        if c.isValid():
            self._set_button_colour(b, c.name())

    def _reset_shortcuts(self) -> None:
        for aid, ed in self.editors.items():
            ed.setKeySequence(QtGui.QKeySequence(self.registry.default_shortcut(aid)))

    def accept(self) -> None:
        p = self.prefs
        p.default_model = self.model.currentText()
        p.brush_size = self.brush.value()
        p.brush_shape = self.brush_shape.currentText()
        p.snap_to_objects = self.snap.isChecked()
        p.autosave_seconds = self.autosave.value()
        p.pixel_limit = int(self.pixel_limit.value())
        p.theme = self.theme.currentText()
        p.pixel_grid_threshold = self.grid.value()
        p.set_object_colours([str(b.property("colour")) for b in self.colour_buttons])
        overrides = {}
        for aid, ed in self.editors.items():
            text = ed.keySequence().toString(QtGui.QKeySequence.SequenceFormat.PortableText)
            if text != self.registry.default_shortcut(aid):
                overrides[aid] = text
        p.set_shortcut_overrides(overrides)
        theme_controller().set_preference(p.theme)
        p.sync()
        super().accept()
