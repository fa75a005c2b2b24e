"""Start-up, `mrm --screenshot`, shortcuts, preferences, settings isolation."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from PySide6 import QtCore, QtGui, QtWidgets

from mrm.app.actions import SPECS
from mrm.app.gui import default_example
from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject

ROOT = Path(__file__).resolve().parents[2]
Qt = QtCore.Qt


def _env(tmp_path: Path) -> dict[str, str]:
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    env.pop("QT_QPA_PLATFORM", None)
    env["MRM_SETTINGS_FILE"] = str(tmp_path / "cli-settings.ini")
    env["XDG_DATA_HOME"] = str(tmp_path / "data")
    return env


def test_screenshot_of_a_project(tmp_path):
    out = tmp_path / "shot.png"
    example = default_example()
    assert example is not None  # `mrm` without arguments has a project to open
    r = subprocess.run(
        [sys.executable, "-m", "mrm.app", "--screenshot", str(out), "--size", "1000x700", str(example)],
        capture_output=True, text=True, timeout=300, cwd=ROOT, env=_env(tmp_path),
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    img = QtGui.QImage(str(out))
    assert (img.width(), img.height()) == (1000, 700)
    # The picture shows the object: more than a few distinct colours inside the views.
    colours = {img.pixel(x, y) for x in range(300, 700, 7) for y in range(100, 600, 7)}
    assert len(colours) > 5


def test_gui_without_display_says_so(tmp_path):
    r = subprocess.run(
        [sys.executable, "-m", "mrm.app"],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=ROOT,
        env=_env(tmp_path),
    )
    assert r.returncode == 2
    assert "no display" in r.stderr and "--screenshot" in r.stderr
    r = subprocess.run(
        [sys.executable, "-m", "mrm.app", "--screenshot", str(tmp_path / "x.png"), "missing.mrm"],
        capture_output=True, text=True, timeout=120, cwd=ROOT, env=_env(tmp_path),
    )  # fmt: skip
    assert r.returncode == 2 and "missing.mrm" in r.stderr and "Traceback" not in r.stderr


def test_help_lists_the_window_options_and_the_subcommands(tmp_path):
    r = subprocess.run(
        [sys.executable, "-m", "mrm.app", "--help"], capture_output=True, text=True, timeout=120, cwd=ROOT,
        env=_env(tmp_path),
    )  # fmt: skip
    assert r.returncode == 0
    assert "--screenshot" in r.stdout and "discretize" in r.stdout


def test_every_command_has_a_distinct_shortcut(make_window):
    win = make_window()
    assert win.registry.conflicts() == []
    without = [s.id for s in SPECS if not win.registry[s.id].shortcuts()]
    assert without == ["help.about"]


def test_tool_keys_switch_tools(make_window, qtbot):
    win = make_window()
    view = win.views.discrete.plane
    view.setFocus()
    keys = {
        "P": "polygon",
        "V": "vertex",
        "B": "paint",
        "E": "erase",
        "F": "fill_hole",
        "X": "delete_component",
    }
    for letter, tool in [*keys.items(), ("S", "select")]:
        key = getattr(Qt.Key, f"Key_{letter}")
        qtbot.keyClick(view, key)
        assert win.tools.tool.name == tool
        assert win.registry[f"tool.{tool}"].isChecked()
    qtbot.keyClick(view, Qt.Key.Key_BracketRight)
    assert win.host.brush_size == 4
    qtbot.keyClick(
        view, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier
    )  # undo with nothing to undo: no-op


def test_undo_redo_shortcuts_and_titles(make_window, qtbot):
    win = make_window()
    win.doc.push(AddObject(win.doc.make_object(PixelSet.box(0, 0, 3, 3), name="box")))
    assert win.registry["edit.undo"].text() == "&Undo Add box"
    assert win.windowTitle().startswith("Untitled") and win.isWindowModified()
    view = win.views.discrete.plane
    view.setFocus()
    qtbot.keyClick(view, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert len(win.doc) == 0 and not win.isWindowModified()
    assert win.registry["edit.redo"].isEnabled()
    win.registry["edit.redo"].trigger()
    assert len(win.doc) == 1


def test_model_switch_is_undoable_and_rederives(make_window, qtbot):
    from shapely.geometry import Polygon

    win = make_window()
    # An edge along the pixel sides: the models disagree on it (standard takes the side's lower/left pixel).
    sq = Polygon([(-0.5, -0.5), (3.5, -0.5), (3.5, 3.5), (-0.5, 3.5)])
    obj = win.doc.make_object(sq, name="sq")
    win.doc.push(AddObject(obj, select=True))
    std = win.scene.get(obj.id, "discrete")
    win.model_menu.actions()[1].trigger()  # supercover
    assert win.doc.model == "supercover"
    qtbot.waitUntil(lambda: "supercover" in win.status.model_label.text())
    sup = win.scene.get(obj.id, "discrete")
    assert sup != std and std.issubset(sup)
    win.registry["edit.undo"].trigger()
    assert win.doc.model == "standard"


def test_preferences_dialog_changes_settings(make_window, qtbot, prefs):
    from mrm.app.preferences_dialog import PreferencesDialog

    win = make_window()
    dlg = PreferencesDialog(prefs, win.registry, win)
    dlg.model.setCurrentText("gauss")
    dlg.brush.setValue(7)
    dlg.editors["tool.polygon"].setKeySequence(QtGui.QKeySequence("Ctrl+Shift+Y"))
    dlg.accept()
    assert prefs.default_model == "gauss" and prefs.brush_size == 7
    assert win.brush_spin.value() == 7
    assert win.registry["tool.polygon"].shortcut().toString() == "Ctrl+Shift+Y"
    win.registry["file.new"].trigger()
    assert win.doc.model == "gauss"  # new projects use the preferred model
    # Settings went to this test's own file, nowhere else.
    prefs.sync()
    assert Path(prefs.settings.fileName()).parent.parent == Path(prefs.settings.fileName()).parents[1]
    assert "gauss" in Path(prefs.settings.fileName()).read_text()
    _ = QtWidgets
