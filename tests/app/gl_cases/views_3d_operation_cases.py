"""The paper's operations on 3D objects, seen in the 3D views (issue 30): Figure 12 on an octahedron.

Run by tests/app/test_views_3d.py under its own Xvfb with GLX (see views_3d_cases.py).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PySide6 import QtCore, QtGui

from tests.app.gl_cases.views_3d_cases import _frame

Qt = QtCore.Qt
EXAMPLES = Path(__file__).parents[3] / "resources" / "examples"


def _greys(img: QtGui.QImage) -> int:
    """Pixels of a neutral grey (the differing voxels' light and dark grey, shaded), not the background."""
    img = img.convertToFormat(QtGui.QImage.Format.Format_RGB32)
    w, h = img.width(), img.height()
    arr = np.frombuffer(img.constBits(), np.uint8).reshape(h, img.bytesPerLine() // 4, 4)[:, :w, :3]
    rgb = arr.reshape(-1, 3).astype(int)
    spread = rgb.max(axis=1) - rgb.min(axis=1)
    background = rgb[0]
    return int(np.sum((spread <= 12) & (rgb.max(axis=1) >= 40) & np.any(rgb != background, axis=1)))


def test_figure_12_in_3d_opens_in_the_3d_views_and_draws_its_differing_voxels_in_grey(make_window, qtbot):
    win = make_window(threaded=True)
    assert win.files.open(EXAMPLES / "fig12-3d-octahedron.mrm", ask=False)
    qtbot.waitUntil(lambda: win.views.dimension == 3 and win.views.area3d is not None, timeout=10_000)
    qtbot.waitUntil(win.is_drawn, timeout=120_000)
    area = win.views.area3d
    view = area.by_name("discrete3d")
    result = next(o for o in win.doc.objects if o.name == "DSS 5")
    win.doc.set_selection([result.id])
    insp = win.inspector
    qtbot.waitUntil(lambda: insp.difference3d is not None, timeout=300_000)
    # The account: a certified interval within the √3 bound, and the voxel counts of the two greys.
    assert "(certified)" in insp.measured_label.text() and "within the bound" in insp.measured_label.text()
    light, dark = len(insp.measurement.difference.light), len(insp.measurement.difference.dark)
    assert light > 0 and dark > 0 and f"{light:,} voxels only in the result" in insp.measured_label.text()
    qtbot.wait(50)
    before = _greys(_frame(view))
    insp.overlay.setChecked(True)  # "Show the differences in the discrete view"
    qtbot.wait(50)
    shown = _greys(_frame(view))
    assert shown > before + 2000, (before, shown)
    # the axis gizmo is whole over them: its x axis drawn to the right (the greys' face culling once hid it)
    from mrm.views.view3d import GIZMO_COLOURS
    from tests.app.gl_cases.views_3d_cases import _corner_hues

    area.buttons["front"].click()
    right, left, _up, _down = _corner_hues(view, GIZMO_COLOURS[0])
    assert right > 20 and left == 0
    insp.overlay.setChecked(False)
    qtbot.wait(50)
    assert _greys(_frame(view)) < shown - 2000
