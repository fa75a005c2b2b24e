"""The main window's menu bar and tool bars: which actions they hold, in which order.

The actions themselves (text, shortcut, what they do) are declared once in :mod:`mrm.app.actions`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from PySide6 import QtCore, QtGui, QtWidgets

from mrm.core.models import Model

if TYPE_CHECKING:
    from mrm.app.main_window import MainWindow

TOOL_ACTIONS = {
    "tool.select": "select",
    "tool.polygon": "polygon",
    "tool.vertex": "vertex",
    "tool.paint": "paint",
    "tool.erase": "erase",
    "tool.fill_hole": "fill_hole",
    "tool.delete_component": "delete_component",
    "tool.measure": "measure",
}


def build_menus(win: MainWindow) -> None:
    """File, Edit, Tools, View, Operations and Help; the window keeps the menus it fills later."""
    a = win.registry
    mb = win.menuBar()
    m = mb.addMenu("&File")
    a.menu(m, ["file.new", "file.open"])
    win.recent_menu = m.addMenu("Open &Recent")
    win.recent_menu.setObjectName("recentMenu")
    win.examples_menu = m.addMenu("Open E&xample")
    win.examples_menu.setObjectName("examplesMenu")
    win.fill_examples_menu()
    a.menu(m, [None, "file.save", "file.save_as", None, "file.import", "file.export", "file.screenshot"])
    a.menu(m, [None, "file.preferences", None, "file.quit"])
    win.update_recent_menu()
    m = mb.addMenu("&Edit")
    a.menu(m, ["edit.undo", "edit.redo", None, "edit.cut", "edit.copy", "edit.paste", "edit.select_all"])
    m.addSeparator()
    a.menu(
        m,
        [
            "edit.rename",
            "edit.colour",
            "edit.properties",
            "edit.transform_3d",
            "edit.duplicate",
            "edit.delete",
            None,
        ],
    )
    a.menu(m, ["edit.split_labels", None])
    a.menu(m, ["edit.select_previous", "edit.select_next"])
    win.model_menu = m.addMenu("Discretization &Model")
    win.model_group = QtGui.QActionGroup(win)
    for name in Model.names():
        act = win.model_menu.addAction(name)
        act.setCheckable(True)
        act.setObjectName(f"model.{name}")
        win.model_group.addAction(act)
        act.triggered.connect(lambda _c=False, n=name: win.set_model(n))
    a.menu(win.model_menu, [None, "edit.compact_limit"])
    m = mb.addMenu("&Tools")
    a.menu(m, list(TOOL_ACTIONS))
    a.menu(m, [None, "tool.brush_larger", "tool.brush_smaller", None, "measure.hausdorff"])
    m = mb.addMenu("&View")
    a.menu(m, ["view.fit", "view.fit_selection", "view.fit_differences"])
    a.menu(m, ["view.zoom_in", "view.zoom_out", "view.actual", None])
    a.menu(m, ["view.grid_layout", "view.tabs_layout", None])
    a.menu(
        m,
        [
            "view.discrete",
            "view.region",
            "view.analytical",
            "view.euclidean",
            None,
            "view.three_d",
            "view.pixel_grid",
        ],
    )
    a.menu(m, ["view.snap"])
    m.addSeparator()
    for d in (
        win.objects_dock,
        win.segments_dock,
        win.operations_dock,
        win.properties_dock,
        win.measure_dock,
        win.history_dock,
        win.inspector_dock,
    ):
        m.addAction(d.toggleViewAction())
    m = mb.addMenu("&Operations")
    a.menu(m, ["ops.panel", "ops.apply", "ops.cancel", "ops.pick_centre", None, "inspect.errors"])
    win.operations.fill_menu(m)
    m = mb.addMenu("&Help")
    a.menu(m, ["help.guide", "help.about"])


def build_toolbars(win: MainWindow) -> None:
    """The File and Tools bars; the brush's size and shape sit in the Tools bar."""
    a = win.registry
    tb = win.addToolBar("File")
    tb.setObjectName("toolbar_file")
    tb.setIconSize(QtCore.QSize(18, 18))
    tb.setToolButtonStyle(QtCore.Qt.ToolButtonStyle.ToolButtonTextOnly)
    for aid in ("file.open", "file.save", None, "edit.undo", "edit.redo", None, "view.fit"):
        if aid is None:
            tb.addSeparator()
        else:
            tb.addAction(a[aid])
    tt = win.addToolBar("Tools")
    tt.setObjectName("toolbar_tools")
    tt.setToolButtonStyle(QtCore.Qt.ToolButtonStyle.ToolButtonTextOnly)
    for aid in TOOL_ACTIONS:
        act = a[aid]
        tt.addAction(act)
    tt.addSeparator()
    tt.addWidget(QtWidgets.QLabel(" Brush ", tt))
    win.brush_spin = QtWidgets.QSpinBox(tt)
    win.brush_spin.setObjectName("brushSize")
    win.brush_spin.setRange(1, 256)
    win.brush_spin.setSuffix(" px")
    win.brush_spin.setValue(win.host.brush_size)
    win.brush_spin.setToolTip("Brush diameter in pixels ([ and ] change it)")
    win.brush_spin.valueChanged.connect(win.set_brush_size)
    tt.addWidget(win.brush_spin)
    win.brush_shape = QtWidgets.QComboBox(tt)
    win.brush_shape.setObjectName("brushShape")
    win.brush_shape.addItems(["round", "square"])
    win.brush_shape.setCurrentText(win.host.brush_shape)
    win.brush_shape.currentTextChanged.connect(win.set_brush_shape)
    tt.addWidget(win.brush_shape)
