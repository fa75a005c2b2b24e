"""The main window: four linked views, the object list, operations, inspector, segment table, menus."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets

from mrm.app.actions import ActionRegistry
from mrm.app.files import FileController
from mrm.app.menus import TOOL_ACTIONS, build_menus, build_toolbars
from mrm.app.settings import Preferences
from mrm.app.status import StatusBar
from mrm.app.tasks import TaskRunner
from mrm.app.undo import UndoAdapter
from mrm.app.window_layout import (
    DEFAULT_SIZE,
    fit_operations_height,
    fit_side_panels,
    fit_to_screen,
    make_dock,
    scrolled,
)
from mrm.document import Changes, Document, Settings
from mrm.views.object_list import ObjectList
from mrm.views.scene import Scene
from mrm.views.tool_base import ToolHost
from mrm.views.tool_controller import ToolController
from mrm.views.view_area import ViewArea


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
        self.transform_dialog: Any = None  # Edit ▸ Transform 3D Object's dialog while it is open
        self.views = ViewArea(self.scene, self)
        self.setCentralWidget(self.views)
        self.registry = ActionRegistry(self, prefs.shortcut_overrides())
        self.host = ToolHost(self.scene, self)
        self.host.brush_size = prefs.brush_size
        self.host.brush_shape = prefs.brush_shape
        self.host.discrete_view = self.views.discrete
        self.host.analytical_view = self.views.analytical
        self.host.colours = prefs.object_colours()
        self.host.snap_to_objects = prefs.snap_to_objects
        self.tools = ToolController(self.host, [v.plane for v in self.views.views], self)
        self.undo = UndoAdapter(
            self.doc, self.registry["edit.undo"], self.registry["edit.redo"], self, before=self.tools.cancel
        )
        self.status = StatusBar(self.scene, self)
        self.setStatusBar(self.status)
        self._build_docks()
        self.files = FileController(self, autosave_dir)
        from mrm.app.clipboard import ClipboardController
        from mrm.app.context_menus import ContextMenus

        self.clipboard = ClipboardController(self)
        self.context_menu: QtWidgets.QMenu | None = None
        self.context_menus = ContextMenus(self)
        build_menus(self)
        build_toolbars(self)
        self._connect()
        self.setAcceptDrops(True)
        self.resize(*DEFAULT_SIZE)
        self.fit_to_screen()
        self.views.set_layout_mode(prefs.layout)
        self.registry["view.grid_layout" if prefs.layout == "grid" else "view.tabs_layout"].setChecked(True)
        self.registry["view.pixel_grid"].setChecked(True)
        self.registry["view.snap"].setChecked(prefs.snap_to_objects)
        self.registry["tool.select"].setChecked(True)
        self.update_action_states()
        self.update_title()
        self._closing = False
        self._discard_on_close = True

    # ------------------------------------------------------------------ construction
    def _build_docks(self) -> None:
        self.object_list = ObjectList(self.doc, self)
        self.objects_dock = make_dock(
            self, "Objects", self.object_list, QtCore.Qt.DockWidgetArea.LeftDockWidgetArea
        )
        from mrm.app import process_jobs
        from mrm.app.preferences_dialog import PIXEL_LIMIT_LABEL
        from mrm.views.inspector import ErrorInspector
        from mrm.views.measure import MeasurePanel
        from mrm.views.operation_panel import OperationPanel
        from mrm.views.properties_panel import PropertiesPanel
        from mrm.views.segment_table import SegmentTable

        right = QtCore.Qt.DockWidgetArea.RightDockWidgetArea
        # The views get the jobs their runner sends to worker processes, and where a preference is set, from
        # here: views never import app/.
        self.operations = OperationPanel(
            self.scene,
            self.runner,
            self,
            plan_job=process_jobs.plan,
            pixel_limit_setting=f"File ▸ Preferences ▸ General ▸ {PIXEL_LIMIT_LABEL}",
        )
        self.operations_dock = make_dock(self, "Operations", scrolled(self.operations), right)
        self.properties = PropertiesPanel(self.scene, self)
        self.properties_dock = make_dock(self, "Properties", self.properties, right)
        self.measure = MeasurePanel(self.scene, self.runner, self)
        self.measure_dock = make_dock(self, "Measure", scrolled(self.measure), right)
        self.inspector = ErrorInspector(self.scene, self.runner, self, measure_job=process_jobs.measure)
        # Scrolled: on a short column its wrapped texts, picture and legend scroll instead of overlapping, and
        # a result's account never makes the window taller than the screen.
        self.inspector_dock = make_dock(self, "Error inspector", scrolled(self.inspector), right)
        # One column on the right (ADR 0020): Operations, Properties and Measure as tabs, the inspector below
        # them, beside the operation whose result it accounts for.
        self.splitDockWidget(self.operations_dock, self.inspector_dock, QtCore.Qt.Orientation.Vertical)
        for d in (self.properties_dock, self.measure_dock):
            self.tabifyDockWidget(self.operations_dock, d)
        self.operations_dock.raise_()
        self.operations.installEventFilter(self)  # its content grows (a status line): keep Apply in sight
        self.setTabPosition(right, QtWidgets.QTabWidget.TabPosition.North)
        self.segments = SegmentTable(self.scene, self)
        self.segments_dock = make_dock(
            self, "Segments", self.segments, QtCore.Qt.DockWidgetArea.LeftDockWidgetArea
        )
        from mrm.views.history_panel import HistoryPanel

        # Below the Objects list, a tab beside Segments (the right column's tabs are full). A click in the
        # list undoes or redoes; a tool's gesture in progress is cancelled first, as Ctrl+Z does.
        left = QtCore.Qt.DockWidgetArea.LeftDockWidgetArea
        self.history_panel = HistoryPanel(self.doc, self, before=self.tools.cancel)
        self.history_dock = make_dock(self, "History", self.history_panel, left)
        self.tabifyDockWidget(self.segments_dock, self.history_dock)
        self.segments_dock.raise_()
        self.setTabPosition(left, QtWidgets.QTabWidget.TabPosition.North)
        self.setCorner(QtCore.Qt.Corner.BottomLeftCorner, QtCore.Qt.DockWidgetArea.LeftDockWidgetArea)
        self.setDockOptions(
            QtWidgets.QMainWindow.DockOption.AnimatedDocks
            | QtWidgets.QMainWindow.DockOption.AllowTabbedDocks
            | QtWidgets.QMainWindow.DockOption.AllowNestedDocks
        )
        self.resizeDocks([self.objects_dock, self.segments_dock], [220, 520], QtCore.Qt.Orientation.Vertical)
        self.resizeDocks(
            [self.operations_dock, self.inspector_dock], [300, 480], QtCore.Qt.Orientation.Vertical
        )
        fit_side_panels(self, 1360)

    def fit_to_screen(self) -> None:
        """Make the window, its frame included, fit its screen's available area (:mod:`.window_layout`)."""
        fit_to_screen(self)

    def _fit_operations_height(self) -> None:
        # A bound method, not a lambda: a timer that fires after the window is gone calls nothing.
        fit_operations_height(self)

    def restore_window_state(self) -> None:
        """The window's saved geometry and dock layout (from the last session), fitted to this screen."""
        geometry, state = self.prefs.window_state()
        if geometry is not None:
            self.restoreGeometry(geometry)
        if state is not None:
            self.restoreState(state)
        self.fit_to_screen()

    def resizeEvent(self, ev: QtGui.QResizeEvent) -> None:
        super().resizeEvent(ev)
        # Only when the window becomes narrower than the panels allow: a user's own dock widths stay.
        central = self.centralWidget()
        if central is not None and central.width() < ev.size().width() * 55 // 100 - 10:
            fit_side_panels(self, ev.size().width())
        # Once the docks have their new sizes (the layout runs after this event).
        QtCore.QTimer.singleShot(0, self._fit_operations_height)

    def eventFilter(self, obj: QtCore.QObject, ev: QtCore.QEvent) -> bool:
        if obj is getattr(self, "operations", None) and ev.type() == QtCore.QEvent.Type.LayoutRequest:
            QtCore.QTimer.singleShot(0, self._fit_operations_height)
        return super().eventFilter(obj, ev)

    def _connect(self) -> None:
        a = self.registry
        self.scene.documentChanged.connect(self._on_changes)
        self.undo.cleanChanged.connect(lambda _clean: self.update_title())
        for aid, tool in TOOL_ACTIONS.items():
            a[aid].toggled.connect(lambda on, t=tool: on and self.tools.set_tool(t))
            if tool != "select":  # chosen by the user (a click, its key), not set back by _tool_changed
                a[aid].triggered.connect(lambda _on=False, aid=aid: self._plane_tool_chosen(aid))
        self.tools.toolChanged.connect(self._tool_changed)
        self.host.message.connect(self.show_message)
        self.host.error.connect(lambda text: self.show_message(text, 5000, error=True))
        self.object_list.errorRaised.connect(lambda text: self.show_message(text, 5000, error=True))
        for v in self.views.views:
            v.plane.cursorMoved.connect(self.status.set_cursor)
        self.runner.busyChanged.connect(self.status.set_busy)
        self.runner.progressChanged.connect(self.status.set_progress)
        # A failure no panel reported (a bug, a broken worker): said here, never lost in a thread.
        self.runner.taskFailed.connect(
            lambda what, text: self.show_message(f"{what}: {text}", 15000, error=True)
        )
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
        a.connect("edit.split_labels", self.split_label_map)
        a.connect("edit.rename", self.rename_selection)
        a.connect("edit.transform_3d", self.transform_3d)
        a.connect("edit.compact_limit", self.choose_compact_limit)
        a.connect("edit.cut", self.clipboard.cut)
        a.connect("edit.copy", self.clipboard.copy)
        a.connect("edit.select_all", self.select_all)
        a.connect("edit.paste", self.clipboard.paste)
        a.connect("edit.colour", self.choose_colour)
        a.connect("edit.properties", self.show_properties)
        a.connect("view.fit_differences", self.fit_differences)
        a.connect("ops.pick_centre", lambda: self.pick_centre(None))
        a.connect("measure.hausdorff", self.measure_hausdorff)
        self.operations.pickRequested.connect(self.pick_centre)
        self.host.measured.connect(self.measure.show_points)
        self.measure.computed.connect(self._hausdorff_marks)
        self.measure.stale.connect(lambda: self.tools.set_marks([]))
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
        a["view.three_d"].toggled.connect(self.views.set_dimension_checked)
        self.views.dimensionChanged.connect(lambda d: a["view.three_d"].setChecked(d == 3))
        a["view.pixel_grid"].toggled.connect(self.set_pixel_grid)
        a["view.snap"].toggled.connect(self.set_snap_to_objects)
        a.connect("ops.panel", self.show_operations)
        a.connect("ops.apply", self.operations.apply)
        a.connect("ops.cancel", self.cancel_task)
        a.connect("inspect.errors", self.show_inspector)
        a.connect("help.guide", self.show_guide)
        a.connect("help.about", self.show_about)
        self.prefs.changed.connect(self._pref_changed)
        for d in self.findChildren(QtWidgets.QDockWidget):
            d.visibilityChanged.connect(lambda shown, dock=d: shown or self._keep_keys_in_sight(dock))
        QtWidgets.QApplication.instance().focusChanged.connect(self._focus_changed)  # type: ignore[union-attr]
        self._watching_focus = True

    # ------------------------------------------------------------------ state
    def _on_changes(self, ch: Changes) -> None:
        self.object_list.on_changes(ch)
        if ch.settings or ch.reset:
            for act in self.model_group.actions():
                act.setChecked(act.text() == self.doc.model)
        if ch.reset:
            # A document of 3D objects only opens in the 3D views, one with plane objects in the plane views.
            solid = any(o.dimension == 3 for o in self.doc.objects)
            self.views.set_dimension(3 if solid and not self.doc.plane_objects else 2)
        self.update_action_states()

    def update_action_states(self) -> None:
        """Enable the object commands that apply to the current selection (menus and shortcuts alike)."""
        a = self.registry
        sel = [i for i in self.doc.selection if i in self.doc]
        for aid in (
            "edit.delete",
            "edit.cut",
            "edit.copy",
            "edit.duplicate",
            "edit.rename",
            "edit.colour",
            "view.fit_selection",
        ):
            a[aid].setEnabled(bool(sel))
        primary = self.scene.primary()
        a["view.fit_differences"].setEnabled(primary is not None and primary.provenance is not None)
        a["edit.split_labels"].setEnabled(primary is not None and primary.kind == "labels")
        a["edit.transform_3d"].setEnabled(self._selected_polyhedron() is not None)
        a["measure.hausdorff"].setEnabled(len(self.doc) >= 2)
        a["edit.select_all"].setEnabled(len(self.doc) > 0)

    def update_title(self) -> None:
        self.setWindowTitle(f"{self.files.document_name()}[*] — MR Modeler")
        self.setWindowModified(self.doc.is_modified)
        self.setWindowFilePath(str(self.doc.path) if self.doc.path else "")

    def fill_examples_menu(self) -> None:
        """File ▸ Open Example: the bundled examples; each opens as an untitled copy."""
        from mrm.resources import example_projects

        m = self.examples_menu
        for p in example_projects():
            act = m.addAction(p.stem)
            act.setObjectName(f"example.{p.stem}")
            act.setStatusTip(f"Open a copy of the example {p.name}")
            act.triggered.connect(lambda _c=False, path=p: self.files.open(path))
        m.setEnabled(bool(m.actions()))

    def update_recent_menu(self) -> None:
        m = self.recent_menu
        m.clear()
        files = self.prefs.recent_files()
        for k, f in enumerate(files):
            # A literal & in a file name is && in a menu text (a single & marks the accelerator key).
            act = m.addAction(f"&{k + 1} {recent_text(f).replace('&', '&&')}")
            act.setToolTip(f)
            act.setStatusTip(f)
            act.triggered.connect(lambda _c=False, p=f: self.files.open(p))
        if files:
            m.addSeparator()
            m.addAction("Clear Recent Files", self._clear_recent)
        m.setEnabled(bool(files))

    # ------------------------------------------------------------------ keyboard focus
    def _focus_changed(self, _old: QtWidgets.QWidget | None, new: QtWidgets.QWidget | None) -> None:
        if new is None or new.window() is not self:
            return
        w: QtWidgets.QWidget | None = new
        while w is not None and not isinstance(w, QtWidgets.QDockWidget):
            w = w.parentWidget()
        if w is not None:
            self._keep_keys_in_sight(w)

    def _keep_keys_in_sight(self, dock: QtWidgets.QDockWidget) -> None:
        """Give the keyboard to the views when it is in a dock out of sight (a tab behind another).

        Qt keeps a tabbed-away dock "visible" (only moved out of the window), so its fields stay in the
        focus chain: a disabled button handed the focus to the hidden Properties name field, which then
        took the tool keys and renamed whatever was selected when it lost the focus (issue 27).
        """
        focus = QtWidgets.QApplication.focusWidget()
        if focus is None or not dock.isAncestorOf(focus):
            return
        if dock.isVisible() and not dock.visibleRegion().isEmpty():
            return
        views = self.views.visible_views()
        if views:
            views[0].plane.setFocus(QtCore.Qt.FocusReason.OtherFocusReason)

    def _clear_recent(self) -> None:
        self.prefs.clear_recent_files()
        self.update_recent_menu()

    def _plane_tool_chosen(self, aid: str) -> None:
        # The drawing and editing tools act in the plane views: chosen while the 3D views were shown, the tool
        # did nothing there that the user could see. Bring the plane views forward and say how to go back.
        if self.views.dimension != 3:
            return
        self.views.set_dimension(2)
        name = self.registry[aid].text().replace("&", "")
        self.show_message(f"{name} works in the plane views (F3 for the 3D views)", 6000)

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
        elif key == "tools/snap_to_objects":
            self.registry["view.snap"].setChecked(self.prefs.snap_to_objects)
        elif key == "tools/brush_shape":
            self.brush_shape.setCurrentText(self.prefs.brush_shape)
        elif key == "appearance/grid_threshold":
            for v in self.views.views:
                v.plane.grid.threshold = self.prefs.pixel_grid_threshold
                v.plane.grid.update()

    # ------------------------------------------------------------------ messages
    def show_message(self, text: str, ms: int = 0, *, error: bool = False) -> None:
        self.status.show_text(text, ms, error=error)

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
        from mrm.document.commands import ChangeSettings

        if name != self.doc.model:
            self.doc.push(ChangeSettings.model(self.doc, name))

    def choose_compact_limit(self) -> None:
        """Edit ▸ Discretization Model ▸ Compact R Limit…: the document's compact limit (ADR 0073), undoable.

        The voxel objects whose safety net has at most this many triangles get a compact R, simplified on a
        worker (about 40–150 µs per triangle of the net); the others keep the safety net.
        """
        from mrm.core import limits

        dlg = QtWidgets.QInputDialog(self)
        dlg.setObjectName("compactLimitDialog")
        dlg.setWindowTitle("Compact R Limit")
        dlg.setInputMode(QtWidgets.QInputDialog.InputMode.IntInput)
        dlg.setIntRange(1, limits.MAX_OBJECT_TRIANGLES)
        dlg.setIntStep(10_000)
        dlg.setIntValue(self.doc.settings.compact_limit)
        spin = dlg.findChild(QtWidgets.QSpinBox)
        if spin is not None:  # 200,000 reads better than 200000
            spin.setGroupSeparatorShown(True)
        dlg.setLabelText(
            "R of a voxel object is made compact when its safety net (its voxels eroded by ¼) has at most\n"
            "this many triangles; above, R is the safety net: exact, but not compact.\n"
            "Simplifying takes about 40–150 µs per triangle of the net, on a worker\n"
            f"(the default, {limits.MAX_COMPACT_R_TRIANGLES:,}, takes 1–3 s). Saved with the project.\n\n"
            "Most triangles of the safety net:"
        )
        dlg.setAttribute(QtCore.Qt.WidgetAttribute.WA_DeleteOnClose)

        def chosen(n: int) -> None:
            from mrm.document.commands import ChangeSettings

            if n != self.doc.settings.compact_limit:
                self.doc.push(ChangeSettings.compact_limit(self.doc, n))

        dlg.intValueSelected.connect(chosen)
        dlg.setWindowModality(QtCore.Qt.WindowModality.WindowModal)
        dlg.open()

    def set_layout(self, mode: str) -> None:
        self.views.set_layout_mode(mode)
        self.prefs.layout = mode

    def set_pixel_grid(self, on: bool) -> None:
        for v in self.views.views:
            v.plane.grid.enabled = on
            v.plane.grid.update()

    def set_snap_to_objects(self, on: bool) -> None:
        """Snap to objects' vertices and edges, or not (View ▸ Snap to Objects); kept in the preferences."""
        changed = self.host.snap_to_objects != bool(on)
        self.host.snap_to_objects = bool(on)
        self.prefs.snap_to_objects = bool(on)
        if changed:
            self.show_message(f"snapping to objects {'on' if on else 'off'} (Shift+S)", 2000)

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
        self.runner.cancel("measure")  # the Hausdorff distance of the Measure panel
        self.runner.cancel("zoom-differences")
        # Then what follows an operation or an edit: the derivations and the inspector's measurement.
        self.scene.cancel_derivations()
        self.inspector.cancel()

    def delete_selection(self) -> None:
        from mrm.document.commands import RemoveObjects

        if self.doc.selection:
            self.doc.push(RemoveObjects(list(self.doc.selection)))

    def split_label_map(self) -> None:
        """Replace the selected label map by one pixel object per label (one undo step, ADR 0033)."""
        from mrm.core.errors import MRMError
        from mrm.document.commands import SplitLabelMap

        obj = self.scene.primary()
        if obj is None or obj.kind != "labels":
            self.show_message("select a label map to split it into one object per label", 4000)
            return
        try:
            self.doc.push(SplitLabelMap(obj.id))
        except MRMError as e:
            self.show_message(str(e), 8000)

    def duplicate_selection(self) -> None:
        from mrm.document.commands import AddObject

        obj = self.scene.primary()
        if obj is None:
            return
        from mrm.views.operation_panel import unique_name

        name = unique_name(f"{obj.name} copy", {o.name for o in self.doc.objects})
        copy = self.doc.make_object(
            obj.source, name=name, style=obj.style, provenance=obj.provenance, georef=obj.georef
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

    def transform_3d(self) -> None:
        """Edit ▸ Transform 3D Object: numbers for a move, a scaling and a rotation; one undo step."""
        from mrm.app.transform3d_dialog import Transform3DDialog

        obj = self._selected_polyhedron()
        if obj is None:
            return
        dlg = Transform3DDialog(obj.name, self)
        self.transform_dialog = dlg

        def done(result: int) -> None:
            self.transform_dialog = None
            if result != QtWidgets.QDialog.DialogCode.Accepted or obj.id not in self.doc:
                return
            poly = self.doc.get(obj.id).source
            lo, hi = poly.bbox
            linear, offset = dlg.map((np.asarray(lo, float) + np.asarray(hi, float)) / 2)
            self.runner.submit(
                f"transform:{obj.id}",
                lambda _p: poly.affine(linear, offset),
                on_result=lambda new: self._transformed(obj.id, poly, new),
                on_error=lambda e: self._transform_failed(obj.name, e),
                label=f"Transforming {obj.name}",
                show_progress=True,
            )

        dlg.finished.connect(done)
        dlg.setWindowModality(QtCore.Qt.WindowModality.WindowModal)
        dlg.open()

    def _selected_polyhedron(self) -> Any:
        """The first selected object when it is a polyhedron (a 3D Euclidean object), else None."""
        sel = self.doc.selection
        obj = self.doc.get(sel[0]) if sel and sel[0] in self.doc else None
        return obj if obj is not None and obj.dimension == 3 and obj.kind == "euclidean" else None

    def _transform_failed(self, name: str, exc: BaseException) -> None:
        from mrm.core.errors import MRMError

        if not isinstance(exc, MRMError):
            raise exc
        self.show_error("Cannot transform", f"{name}: {exc}")

    def _transformed(self, obj_id: int, before: Any, new: Any) -> None:
        from mrm.document.commands import SetSource

        if obj_id in self.doc and self.doc.get(obj_id).source is before:  # not edited meanwhile
            self.doc.push(SetSource(obj_id, new, "Transform 3D object"))

    def select_all(self) -> None:
        """Select every object of the document (Ctrl+A), hidden ones too, as the Objects list shows them."""
        self.doc.set_selection(self.doc.ids)

    def select_step(self, step: int) -> None:
        ids = self.object_list.model.ids()
        if not ids:
            return
        cur = self.doc.selection[0] if self.doc.selection else None
        k = ids.index(cur) + step if cur in ids else 0
        self.doc.set_selection([ids[k % len(ids)]])

    def fit_all(self) -> None:
        if self.views.dimension == 3 and self.views.area3d is not None:
            self.views.area3d.fit()
            return
        self._fit([o for o in self.doc.plane_objects if o.style.visible])

    def fit_selection(self) -> None:
        """Zoom to the selected objects (all of them)."""
        self._fit([self.doc.get(i) for i in self.doc.selection if i in self.doc])

    def fit_differences(self) -> None:
        """Zoom to the pixels where the selected result differs from its direct computation.

        They are the error inspector's light and dark grey pixels: the model's account of the result
        (:func:`mrm.ops.account.account_of`), computed on a worker.
        """
        from mrm.ops.account import account_of

        obj = self.scene.primary()
        if obj is None or obj.provenance is None:
            self.show_message("select a result of an operation to zoom to its differences", 4000)
            return
        prov, name = obj.provenance, obj.name

        def done(acc: Any) -> None:
            diff = acc.difference
            if diff is None:
                why = acc.error or acc.no_bound or "no direct computation to compare with"
                self.show_message(f"{name}: {why}", 6000)
                return
            boxes = [ps.bbox for ps in (diff.light, diff.dark) if ps.bbox is not None]
            if not boxes:
                self.show_message(f"{name}: no pixel differs from the direct result", 5000)
                return
            x0, y0 = min(b[0] for b in boxes), min(b[1] for b in boxes)
            x1, y1 = max(b[2] for b in boxes), max(b[3] for b in boxes)
            self.views.camera.fit((x0 - 2.5, y0 - 2.5, x1 + 2.5, y1 + 2.5))
            self.show_message(
                f"{name}: {diff.count} differing pixels "
                f"({len(diff.light)} light, {len(diff.dark)} dark grey)",
                6000,
            )

        def failed(exc: BaseException) -> None:
            from mrm.core.errors import MRMError

            if not isinstance(exc, MRMError):
                raise exc
            self.show_message(f"{name}: {exc}", 6000, error=True)

        self.runner.submit(
            "zoom-differences",
            lambda progress: account_of(prov, measure=True, progress=progress),
            on_result=done,
            on_error=failed,
            label=f"Differences of {name}",
            show_progress=True,
        )

    def set_visible_selection(self, visible: bool) -> None:
        """Show or hide the selected objects, one undo step."""
        from dataclasses import replace

        from mrm.document.commands import RestyleObject

        ids = [i for i in self.doc.selection if i in self.doc and self.doc.get(i).style.visible != visible]
        if not ids:
            return
        with self.doc.history.macro("Show objects" if visible else "Hide objects"):
            for i in ids:
                o = self.doc.get(i)
                self.doc.push(RestyleObject(i, replace(o.style, visible=visible)))

    def choose_colour(self) -> None:
        if self.scene.primary() is not None:
            self.properties.choose_colour()

    def show_properties(self) -> None:
        self.properties_dock.show()
        self.properties_dock.raise_()
        self.properties.focus_name()

    def pick_centre(self, name: str | None) -> None:
        """The next click in a view sets the operation's centre (``name``: which point parameter)."""
        c = self.operations.centre_control() if name is None else self.operations.control(name)
        if c is None:
            self.show_message(f"{self.operations.op.title if self.operations.op else 'This operation'} "
                              "has no centre", 4000)  # fmt: skip
            return
        self.tools.pick_point(lambda x, y: self.operations.set_centre(x, y, c.info.name))

    def _hausdorff_marks(self, r: Any) -> None:
        """Mark in every view where H(A, B) is reached."""
        w = r.full.witness
        self.tools.set_marks([] if w is None else [(w[0], w[1], f"H = {r.full.value:.4g}")])

    def measure_hausdorff(self) -> None:
        """Hausdorff distance between the two selected objects (or those of the Measure panel)."""
        sel = [i for i in self.doc.selection if i in self.doc]
        if len(sel) >= 2:
            self.measure.set_objects(sel[0], sel[1])
        elif len(sel) == 1:
            # One selected: it is A; B stays the panel's choice, or the next object in the list.
            b = self.measure.b_combo.currentData()
            if b is None or b == sel[0]:
                others = [i for i in self.object_list.model.ids() if i != sel[0]]
                b = others[0] if others else None
            if b is not None:
                self.measure.set_objects(sel[0], b)
        self.measure_dock.show()
        self.measure_dock.raise_()
        self.measure.compute()

    def _fit(self, objs: list[Any]) -> None:
        from mrm.views.view_area import joint_box, object_box

        box = joint_box(object_box(self.scene.source(o.id)) for o in objs)
        if box is None:
            self.views.camera.fit((-8, -6, 24, 18))
            return
        self.views.frame(box)

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
        if self._watching_focus:
            self._watching_focus = False
            QtWidgets.QApplication.instance().focusChanged.disconnect(self._focus_changed)  # type: ignore[union-attr]
        self.tools.cancel()
        self.runner.shutdown()
        self.files.close(discard_autosave=discard_autosave)
        self.undo.close()
        self.history_panel.close_panel()
        self.scene.close()
        self.prefs.sync()


def recent_text(path: str) -> str:
    """A recent file as a menu shows it: ``name.mrm — ~/folder`` (two files of one name differ by folder)."""
    p = Path(path)
    folder = str(p.parent)
    home = str(Path.home())
    if folder == home or folder.startswith(home + os.sep):
        folder = "~" + folder[len(home) :]
    return f"{p.name} — {folder}"
