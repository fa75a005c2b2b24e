"""The main window: four linked views, the object list, operations, inspector, segment table, menus."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from PySide6 import QtCore, QtGui, QtWidgets

from mrm.app.actions import ActionRegistry
from mrm.app.files import FileController
from mrm.app.settings import Preferences
from mrm.app.status import StatusBar
from mrm.app.tasks import TaskRunner
from mrm.app.undo import UndoAdapter
from mrm.document import Changes, Document, Settings
from mrm.views.object_list import ObjectList
from mrm.views.scene import Scene
from mrm.views.tool_controller import ToolController
from mrm.views.tools import ToolHost
from mrm.views.view_area import ViewArea

TOOL_ACTIONS = {
    "tool.select": "select",
    "tool.polygon": "polygon",
    "tool.vertex": "vertex",
    "tool.paint": "paint",
    "tool.erase": "erase",
    "tool.fill_hole": "fill_hole",
    "tool.delete_component": "delete_component",
}


class MainWindow(QtWidgets.QMainWindow):
    """MR Modeler's window. Tests build it through a factory fixture with their own settings and runner."""

    def __init__(
        self,
        prefs: Preferences,
        *,
        runner: TaskRunner | None = None,
        autosave_dir: str | os.PathLike[str] | None = None,
    ) -> None:
        super().__init__()
        self.setObjectName("mainWindow")
        self.prefs = prefs
        self.runner = runner if runner is not None else TaskRunner(self)
        if self.runner.parent() is None:
            self.runner.setParent(self)
        self.doc = Document(Settings(model=prefs.default_model))
        self.runner.revision_getter = lambda: self.doc.revision
        self.scene = Scene(self.doc, self.runner, self)
        self.views = ViewArea(self.scene, self)
        self.setCentralWidget(self.views)
        self.registry = ActionRegistry(self, prefs.shortcut_overrides())
        self.host = ToolHost(self.scene, self)
        self.host.brush_size = prefs.brush_size
        self.host.brush_shape = prefs.brush_shape
        self.host.discrete_view = self.views.discrete
        self.host.analytical_view = self.views.analytical
        self.host.colours = prefs.object_colours()
        self.tools = ToolController(self.host, [v.plane for v in self.views.views], self)
        self.undo = UndoAdapter(
            self.doc, self.registry["edit.undo"], self.registry["edit.redo"], self, before=self.tools.cancel
        )
        self.status = StatusBar(self.scene, self)
        self.setStatusBar(self.status)
        self._build_docks()
        self.files = FileController(self, autosave_dir)
        self._build_menus()
        self._build_toolbars()
        self._connect()
        self.setAcceptDrops(True)
        self.resize(1360, 880)
        self.views.set_layout_mode(prefs.layout)
        self.registry["view.grid_layout" if prefs.layout == "grid" else "view.tabs_layout"].setChecked(True)
        self.registry["view.pixel_grid"].setChecked(True)
        self.registry["tool.select"].setChecked(True)
        self.update_title()
        self._closing = False
        self._discard_on_close = True

    # ------------------------------------------------------------------ construction
    def _build_docks(self) -> None:
        self.object_list = ObjectList(self.doc, self)
        self.objects_dock = self._dock(
            "Objects", self.object_list, QtCore.Qt.DockWidgetArea.LeftDockWidgetArea
        )
        from mrm.views.inspector import ErrorInspector
        from mrm.views.operation_panel import OperationPanel
        from mrm.views.segment_table import SegmentTable

        self.operations = OperationPanel(self.scene, self.runner, self)
        self.operations_dock = self._dock(
            "Operations", self.operations, QtCore.Qt.DockWidgetArea.RightDockWidgetArea
        )
        self.inspector = ErrorInspector(self.scene, self.runner, self)
        self.inspector_dock = self._dock(
            "Error inspector", self.inspector, QtCore.Qt.DockWidgetArea.RightDockWidgetArea
        )
        self.segments = SegmentTable(self.scene, self)
        self.segments_dock = self._dock(
            "Segments", self.segments, QtCore.Qt.DockWidgetArea.LeftDockWidgetArea
        )
        self.setCorner(QtCore.Qt.Corner.BottomLeftCorner, QtCore.Qt.DockWidgetArea.LeftDockWidgetArea)
        self.resizeDocks([self.objects_dock, self.segments_dock], [220, 520], QtCore.Qt.Orientation.Vertical)
        self.resizeDocks(
            [self.operations_dock, self.inspector_dock], [300, 480], QtCore.Qt.Orientation.Vertical
        )
        self.resizeDocks([self.objects_dock], [290], QtCore.Qt.Orientation.Horizontal)
        self.resizeDocks([self.operations_dock], [310], QtCore.Qt.Orientation.Horizontal)

    def _dock(
        self, title: str, widget: QtWidgets.QWidget, area: QtCore.Qt.DockWidgetArea
    ) -> QtWidgets.QDockWidget:
        d = QtWidgets.QDockWidget(title, self)
        d.setObjectName(f"dock_{title.lower().replace(' ', '_')}")
        d.setWidget(widget)
        d.setFeatures(
            QtWidgets.QDockWidget.DockWidgetFeature.DockWidgetMovable
            | QtWidgets.QDockWidget.DockWidgetFeature.DockWidgetClosable
            | QtWidgets.QDockWidget.DockWidgetFeature.DockWidgetFloatable
        )
        self.addDockWidget(area, d)
        return d

    def _build_menus(self) -> None:
        a = self.registry
        mb = self.menuBar()
        m = mb.addMenu("&File")
        a.menu(m, ["file.new", "file.open"])
        self.recent_menu = m.addMenu("Open &Recent")
        self.recent_menu.setObjectName("recentMenu")
        a.menu(m, [None, "file.save", "file.save_as", None, "file.import", "file.export", "file.screenshot"])
        a.menu(m, [None, "file.preferences", None, "file.quit"])
        self.update_recent_menu()
        m = mb.addMenu("&Edit")
        a.menu(m, ["edit.undo", "edit.redo", None, "edit.rename", "edit.duplicate", "edit.delete", None])
        a.menu(m, ["edit.select_previous", "edit.select_next"])
        self.model_menu = m.addMenu("Discretization &Model")
        self._model_group = QtGui.QActionGroup(self)
        for name in ("standard", "supercover", "gauss"):
            act = self.model_menu.addAction(name)
            act.setCheckable(True)
            act.setObjectName(f"model.{name}")
            self._model_group.addAction(act)
            act.triggered.connect(lambda _c=False, n=name: self.set_model(n))
        m = mb.addMenu("&Tools")
        a.menu(m, list(TOOL_ACTIONS))
        a.menu(m, [None, "tool.brush_larger", "tool.brush_smaller"])
        m = mb.addMenu("&View")
        a.menu(m, ["view.fit", "view.fit_selection", "view.zoom_in", "view.zoom_out", "view.actual", None])
        a.menu(m, ["view.grid_layout", "view.tabs_layout", None])
        a.menu(
            m, ["view.discrete", "view.region", "view.analytical", "view.euclidean", None, "view.pixel_grid"]
        )
        m.addSeparator()
        for d in (self.objects_dock, self.operations_dock, self.inspector_dock, self.segments_dock):
            m.addAction(d.toggleViewAction())
        m = mb.addMenu("&Operations")
        a.menu(m, ["ops.panel", "ops.apply", "ops.cancel", None, "inspect.errors"])
        self.operations.fill_menu(m)
        m = mb.addMenu("&Help")
        a.menu(m, ["help.guide", "help.about"])

    def _build_toolbars(self) -> None:
        a = self.registry
        tb = self.addToolBar("File")
        tb.setObjectName("toolbar_file")
        tb.setIconSize(QtCore.QSize(18, 18))
        tb.setToolButtonStyle(QtCore.Qt.ToolButtonStyle.ToolButtonTextOnly)
        for aid in ("file.open", "file.save", None, "edit.undo", "edit.redo", None, "view.fit"):
            if aid is None:
                tb.addSeparator()
            else:
                tb.addAction(a[aid])
        tt = self.addToolBar("Tools")
        tt.setObjectName("toolbar_tools")
        tt.setToolButtonStyle(QtCore.Qt.ToolButtonStyle.ToolButtonTextOnly)
        for aid in TOOL_ACTIONS:
            act = a[aid]
            tt.addAction(act)
        tt.addSeparator()
        tt.addWidget(QtWidgets.QLabel(" Brush ", tt))
        self.brush_spin = QtWidgets.QSpinBox(tt)
        self.brush_spin.setObjectName("brushSize")
        self.brush_spin.setRange(1, 256)
        self.brush_spin.setSuffix(" px")
        self.brush_spin.setValue(self.host.brush_size)
        self.brush_spin.setToolTip("Brush diameter in pixels ([ and ] change it)")
        self.brush_spin.valueChanged.connect(self.set_brush_size)
        tt.addWidget(self.brush_spin)
        self.brush_shape = QtWidgets.QComboBox(tt)
        self.brush_shape.setObjectName("brushShape")
        self.brush_shape.addItems(["round", "square"])
        self.brush_shape.setCurrentText(self.host.brush_shape)
        self.brush_shape.currentTextChanged.connect(self.set_brush_shape)
        tt.addWidget(self.brush_shape)

    def _connect(self) -> None:
        a = self.registry
        self.scene.documentChanged.connect(self._on_changes)
        self.undo.cleanChanged.connect(lambda _clean: self.update_title())
        for aid, tool in TOOL_ACTIONS.items():
            a[aid].toggled.connect(lambda on, t=tool: on and self.tools.set_tool(t))
        self.tools.toolChanged.connect(self._tool_changed)
        self.host.message.connect(self.show_message)
        self.host.error.connect(lambda text: self.show_message(text, 5000, error=True))
        self.object_list.errorRaised.connect(lambda text: self.show_message(text, 5000, error=True))
        for v in self.views.views:
            v.plane.cursorMoved.connect(self.status.set_cursor)
        self.runner.busyChanged.connect(self.status.set_busy)
        self.runner.progressChanged.connect(self.status.set_progress)
        self.status.cancelRequested.connect(self.cancel_task)
        a.connect("file.new", self.files.new)
        a.connect("file.open", lambda: self.files.open())
        a.connect("file.save", self.files.save)
        a.connect("file.save_as", lambda: self.files.save_as())
        a.connect("file.import", self.files.import_dialog)
        a.connect("file.export", self.files.export_dialog)
        a.connect("file.screenshot", self.save_picture_dialog)
        a.connect("file.preferences", self.show_preferences)
        a.connect("file.quit", self.close)
        a.connect("edit.delete", self.delete_selection)
        a.connect("edit.duplicate", self.duplicate_selection)
        a.connect("edit.rename", self.rename_selection)
        a.connect("edit.select_next", lambda: self.select_step(+1))
        a.connect("edit.select_previous", lambda: self.select_step(-1))
        a.connect("tool.brush_larger", lambda: self.brush_spin.setValue(self.brush_spin.value() + 1))
        a.connect("tool.brush_smaller", lambda: self.brush_spin.setValue(self.brush_spin.value() - 1))
        a.connect("view.fit", self.fit_all)
        a.connect("view.fit_selection", self.fit_selection)
        a.connect("view.zoom_in", lambda: self.views.camera.zoom(1.25))
        a.connect("view.zoom_out", lambda: self.views.camera.zoom(0.8))
        a.connect(
            "view.actual", lambda: self.views.camera.set(self.views.camera.cx, self.views.camera.cy, 1.0)
        )
        a["view.grid_layout"].toggled.connect(lambda on: on and self.set_layout("grid"))
        a["view.tabs_layout"].toggled.connect(lambda on: on and self.set_layout("tabs"))
        for aid, name in (
            ("view.discrete", "discrete"),
            ("view.region", "region"),
            ("view.analytical", "analytical"),
            ("view.euclidean", "euclidean"),
        ):
            a.connect(aid, lambda n=name: self.views.show_view(self.views.by_name(n)))
        a["view.pixel_grid"].toggled.connect(self.set_pixel_grid)
        a.connect("ops.panel", self.show_operations)
        a.connect("ops.apply", self.operations.apply)
        a.connect("ops.cancel", self.cancel_task)
        a.connect("inspect.errors", self.show_inspector)
        a.connect("help.guide", self.show_guide)
        a.connect("help.about", self.show_about)
        self.prefs.changed.connect(self._pref_changed)

    # ------------------------------------------------------------------ state
    def _on_changes(self, ch: Changes) -> None:
        self.object_list.on_changes(ch)
        if ch.settings or ch.reset:
            for act in self._model_group.actions():
                act.setChecked(act.text() == self.doc.model)
        self.registry["edit.delete"].setEnabled(bool(self.doc.selection))

    def update_title(self) -> None:
        name = self.doc.path.name if self.doc.path else "Untitled"
        self.setWindowTitle(f"{name}[*] — MR Modeler")
        self.setWindowModified(self.doc.is_modified)
        self.setWindowFilePath(str(self.doc.path) if self.doc.path else "")

    def update_recent_menu(self) -> None:
        m = self.recent_menu
        m.clear()
        files = self.prefs.recent_files()
        for k, f in enumerate(files):
            act = m.addAction(f"&{k + 1} {Path(f).name}")
            act.setToolTip(f)
            act.setStatusTip(f)
            act.triggered.connect(lambda _c=False, p=f: self.files.open(p))
        if files:
            m.addSeparator()
            m.addAction("Clear Recent Files", self._clear_recent)
        m.setEnabled(bool(files))

    def _clear_recent(self) -> None:
        self.prefs.clear_recent_files()
        self.update_recent_menu()

    def _tool_changed(self, name: str) -> None:
        for aid, tool in TOOL_ACTIONS.items():
            if tool == name:
                self.registry[aid].setChecked(True)

    def _pref_changed(self, key: str) -> None:
        if key == "shortcuts":
            self.registry.apply_shortcuts(self.prefs.shortcut_overrides())
        elif key == "appearance/object_colours":
            self.host.colours = self.prefs.object_colours()
        elif key == "tools/brush_size" and self.brush_spin.value() != self.prefs.brush_size:
            self.brush_spin.setValue(self.prefs.brush_size)
        elif key == "tools/brush_shape":
            self.brush_shape.setCurrentText(self.prefs.brush_shape)
        elif key == "appearance/grid_threshold":
            for v in self.views.views:
                v.plane.grid.threshold = self.prefs.pixel_grid_threshold
                v.plane.grid.update()

    # ------------------------------------------------------------------ messages
    def show_message(self, text: str, ms: int = 0, *, error: bool = False) -> None:
        self.status.setStyleSheet("QStatusBar { color: #c0392b; }" if error else "")
        self.status.showMessage(text, ms)

    def show_error(self, title: str, text: str) -> QtWidgets.QMessageBox:
        """A window-modal message that does not block the caller (so no work waits on the user)."""
        box = QtWidgets.QMessageBox(self)
        box.setObjectName("errorDialog")
        box.setIcon(QtWidgets.QMessageBox.Icon.Critical)
        box.setWindowTitle(title)
        box.setText(title)
        box.setInformativeText(text)
        box.setAttribute(QtCore.Qt.WidgetAttribute.WA_DeleteOnClose)
        box.open()
        self.show_message(f"{title}: {text.splitlines()[0] if text else ''}", 8000, error=True)
        return box

    # ------------------------------------------------------------------ commands
    def set_model(self, name: str) -> None:
        from mrm.commands import ChangeSettings

        if name != self.doc.model:
            self.doc.push(ChangeSettings.model(self.doc, name))

    def set_layout(self, mode: str) -> None:
        self.views.set_layout_mode(mode)
        self.prefs.layout = mode

    def set_pixel_grid(self, on: bool) -> None:
        for v in self.views.views:
            v.plane.grid.enabled = on
            v.plane.grid.update()

    def set_brush_size(self, size: int) -> None:
        self.host.brush_size = int(size)
        self.prefs.brush_size = int(size)
        self.host.overlayChanged.emit()
        self.show_message(f"brush: {size} px", 1500)

    def set_brush_shape(self, shape: str) -> None:
        self.host.brush_shape = shape
        self.prefs.brush_shape = shape
        self.host.overlayChanged.emit()

    def cancel_task(self) -> None:
        if self.tools.cancel():
            return
        if self.operations.is_running():
            self.operations.cancel()
            return
        self.operations.cancel()  # its preview
        # Then what follows an operation or an edit: the derivations and the inspector's measurement.
        self.scene.cancel_derivations()
        self.inspector.cancel()

    def delete_selection(self) -> None:
        from mrm.commands import RemoveObjects

        if self.doc.selection:
            self.doc.push(RemoveObjects(list(self.doc.selection)))

    def duplicate_selection(self) -> None:
        from mrm.commands import AddObject

        obj = self.scene.primary()
        if obj is None:
            return
        copy = self.doc.make_object(
            obj.source, name=f"{obj.name} copy", style=obj.style, provenance=obj.provenance
        )
        self.doc.push(AddObject(copy, self.doc.index_of(obj.id) + 1, select=True))

    def rename_selection(self) -> None:
        obj = self.scene.primary()
        if obj is None:
            return
        idx = self.object_list.model.index(self.object_list.model.row_of(obj.id), 2)
        self.objects_dock.show()
        self.object_list.view.setCurrentIndex(idx)
        self.object_list.view.edit(idx)

    def select_step(self, step: int) -> None:
        ids = self.object_list.model.ids()
        if not ids:
            return
        cur = self.doc.selection[0] if self.doc.selection else None
        k = ids.index(cur) + step if cur in ids else 0
        self.doc.set_selection([ids[k % len(ids)]])

    def fit_all(self) -> None:
        self._fit([o for o in self.doc.objects if o.style.visible])

    def fit_selection(self) -> None:
        obj = self.scene.primary()
        self._fit([obj] if obj is not None else [])

    def _fit(self, objs: list[Any]) -> None:
        boxes = []
        for o in objs:
            src = self.scene.source(o.id)
            if hasattr(src, "bounds"):
                if not src.is_empty:
                    boxes.append(tuple(src.bounds))
            else:
                b = src.bbox
                if b is not None:
                    boxes.append((b[0] - 0.5, b[1] - 0.5, b[2] + 0.5, b[3] + 0.5))
        if not boxes:
            self.views.camera.fit((-8, -6, 24, 18))
            return
        xs0, ys0, xs1, ys1 = zip(*boxes, strict=True)
        self.views.camera.fit((min(xs0) - 1, min(ys0) - 1, max(xs1) + 1, max(ys1) + 1))

    def show_operations(self) -> None:
        self.operations_dock.show()
        self.operations_dock.raise_()
        self.operations.setFocus()

    def show_inspector(self) -> None:
        self.inspector_dock.show()
        self.inspector_dock.raise_()

    def show_preferences(self) -> None:
        from mrm.app.preferences_dialog import PreferencesDialog

        dlg = PreferencesDialog(self.prefs, self.registry, self)
        dlg.open()

    def show_about(self) -> None:
        QtWidgets.QMessageBox.about(
            self,
            "About MR Modeler",
            "<b>MR Modeler</b><br>A multi-representation modeler for 2D discrete geometry, after "
            "G. Largeteau-Skapin &amp; E. Andres, <i>Discrete-Euclidean operations</i>, "
            "Discrete Applied Mathematics 157(3), 2009.",
        )

    def show_guide(self) -> None:
        """Show the user guide in a window of the application (F1)."""
        from mrm.app.help import HelpWindow

        win = getattr(self, "help_window", None)
        if win is None:
            win = self.help_window = HelpWindow(self)
        win.show()
        if QtGui.QGuiApplication.platformName() != "offscreen":  # offscreen warns it cannot raise
            win.raise_()
        win.activateWindow()

    def save_picture_dialog(self) -> None:
        fn, _ = QtWidgets.QFileDialog.getSaveFileName(
            self, "Save window picture", "mrm-window.png", "PNG (*.png)"
        )
        if fn:
            self.grab().save(fn, "PNG")

    # ------------------------------------------------------------------ drawing state
    def is_drawn(self) -> bool:
        """True when every view shows the current document (nothing dirty, nothing computing)."""
        return self.views.is_drawn() and not self.scene.is_computing()

    # ------------------------------------------------------------------ drag and drop
    def dragEnterEvent(self, ev: QtGui.QDragEnterEvent) -> None:
        if ev.mimeData().hasUrls() and any(u.isLocalFile() for u in ev.mimeData().urls()):
            ev.acceptProposedAction()
        else:
            ev.ignore()

    def dropEvent(self, ev: QtGui.QDropEvent) -> None:
        paths = [Path(u.toLocalFile()) for u in ev.mimeData().urls() if u.isLocalFile()]
        if paths:
            ev.acceptProposedAction()
            QtCore.QTimer.singleShot(0, lambda: self.files.drop(paths))

    # ------------------------------------------------------------------ closing
    def closeEvent(self, ev: QtGui.QCloseEvent) -> None:
        if not self._closing and not self.files.maybe_save():
            ev.ignore()
            return
        self._shutdown(discard_autosave=self._discard_on_close)
        ev.accept()

    def close_now(self, *, discard_autosave: bool = True) -> None:
        """Close without asking (tests, or after the user already answered)."""
        self._closing = True
        self._discard_on_close = discard_autosave
        self.close()

    def _shutdown(self, *, discard_autosave: bool) -> None:
        geometry, state = self.saveGeometry(), self.saveState()
        self.prefs.set_window_state(geometry, state)
        self.tools.cancel()
        self.runner.shutdown()
        self.files.close(discard_autosave=discard_autosave)
        self.undo.close()
        self.scene.close()
        self.prefs.sync()
