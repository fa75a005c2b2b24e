"""Edit ▸ Transform 3D Object (Ctrl+T): a polyhedron moved, scaled and rotated by numbers, one undo step."""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore, QtWidgets

from mrm.document.commands import AddObject
from mrm.geometry.polyhedra import Polyhedron
from tests.app.helpers import press_key, shown_dialog

Qt = QtCore.Qt
VERTICES = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4]], float)
TRIANGLES = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]


def _type(qtbot, dlg, name: str, text: str) -> None:  # type: ignore[no-untyped-def]
    box = dlg.findChild(QtWidgets.QDoubleSpinBox, name)
    box.lineEdit().selectAll()
    qtbot.keyClicks(box.lineEdit(), text)
    box.interpretText()


def test_ctrl_t_moves_scales_and_rotates_a_polyhedron_in_one_undo_step(make_window, qtbot):
    win = make_window()
    tet = Polyhedron(VERTICES, TRIANGLES)
    obj = win.doc.make_object(tet, name="tet")
    win.doc.push(AddObject(obj))
    win.doc.set_selection([obj.id])
    assert win.registry["edit.transform_3d"].isEnabled()
    press_key(qtbot, win.views.discrete, Qt.Key.Key_T, Qt.KeyboardModifier.ControlModifier)
    dlg = shown_dialog(qtbot, "transform3dDialog")
    _type(qtbot, dlg, "move_x", "10")
    _type(qtbot, dlg, "move_z", "-1.5")
    _type(qtbot, dlg, "scale", "2")
    _type(qtbot, dlg, "angle", "90")  # about z, the default axis
    qtbot.mouseClick(
        dlg.findChild(QtWidgets.QDialogButtonBox).button(QtWidgets.QDialogButtonBox.StandardButton.Ok),
        Qt.MouseButton.LeftButton,
    )
    qtbot.waitUntil(lambda: win.doc.get(obj.id).source != tet, timeout=10_000)
    # about the box centre c = (2, 2, 2): (x, y, z) -> c + 2·(−(y − 2), x − 2, z − 2) + (10, 0, −1.5)
    c = np.array([2.0, 2.0, 2.0])
    u = VERTICES - c
    expected = c + 2 * np.stack([-u[:, 1], u[:, 0], u[:, 2]], axis=1) + np.array([10.0, 0.0, -1.5])
    assert win.doc.get(obj.id).source == Polyhedron(expected, TRIANGLES)
    win.doc.history.undo()
    assert win.doc.get(obj.id).source == tet


def test_a_mirror_keeps_the_solid_outward_and_a_flattening_map_is_refused():
    tet = Polyhedron(VERTICES, TRIANGLES)
    mirrored = tet.affine(np.diag([-1.0, 1.0, 1.0]))
    assert mirrored.signed_volume > 0 and np.isclose(mirrored.signed_volume, tet.signed_volume)
    import pytest

    from mrm.core.errors import InvalidGeometryError

    with pytest.raises(InvalidGeometryError, match="flattens"):
        tet.affine(np.diag([1.0, 1.0, 0.0]))


def test_the_command_is_off_unless_a_polyhedron_is_selected(make_window):
    win = make_window()
    assert not win.registry["edit.transform_3d"].isEnabled()
