"""The 3D views: their OpenGL cases under a private Xvfb, and the offscreen platform's note instead of them.

pyqtgraph's OpenGL widgets abort the process under ``QT_QPA_PLATFORM=offscreen`` (the rest of the suite), so
the cases in ``gl_cases/`` run in a pytest of their own, on an Xvfb with GLX that this test starts (Mesa's
llvmpipe), with ``--headed`` and the xcb platform. Their report is this test's failure message.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
from PySide6 import QtCore, QtWidgets

from mrm.core.grids import VoxelSet
from mrm.document.commands import AddObject
from tests.app.helpers import press_key
from tests.app.xserver import start_xvfb, stop

ROOT = Path(__file__).resolve().parents[2]
CASES = Path(__file__).with_name("gl_cases")


def _case_count() -> int:
    """The number of test functions in the case files (each must run and pass)."""
    return sum(
        len(re.findall(r"^def test_", f.read_text(encoding="utf-8"), re.MULTILINE))
        for f in CASES.glob("*_cases.py")
    )


def test_the_3d_views_draw_and_turn_together_on_a_real_x_server_with_opengl(tmp_path: Path) -> None:
    proc, display = start_xvfb(tmp_path, size="1600x1200x24", glx=True)
    try:
        env = {k: v for k, v in os.environ.items() if k not in ("QT_QPA_PLATFORM", "WAYLAND_DISPLAY")}
        env.update(DISPLAY=display, QT_QPA_PLATFORM="xcb")
        done = subprocess.run(
            [
                sys.executable,
                "-m",
                "pytest",
                "-n0",
                "--headed",
                "-p",
                "no:cacheprovider",
                "-q",
                "-rA",
                *sorted(str(f) for f in CASES.glob("*_cases.py")),
            ],
            cwd=ROOT,
            env=env,
            capture_output=True,
            text=True,
            timeout=900,
        )
    finally:
        stop(proc)
    report = done.stdout[-6000:] + done.stderr[-2000:]
    assert done.returncode == 0, report
    count = _case_count()
    assert count >= 5  # every case ran (none skipped, none left out of the run)
    assert re.search(rf"^{count} passed\b", done.stdout, re.MULTILINE), report


def test_without_opengl_the_3d_views_say_why_and_the_window_keeps_working(make_window, qtbot) -> None:
    win = make_window()
    z, y, x = np.mgrid[-3:4, -3:4, -3:4]
    obj = win.doc.make_object(VoxelSet(np.abs(x) + np.abs(y) + np.abs(z) <= 3, (-3, -3, -3)), name="octa")
    win.doc.push(AddObject(obj))
    press_key(qtbot, win.views.discrete, QtCore.Qt.Key.Key_F3)
    assert win.views.dimension == 3 and win.registry["view.three_d"].isChecked()
    note = win.views.area3d.findChild(QtWidgets.QLabel, "noOpenGL")
    assert note is not None and note.isVisible() and "OpenGL" in note.text()
    assert win.views.area3d.views == []
    win.registry["view.three_d"].trigger()
    assert win.views.dimension == 2 and win.views.discrete.isVisible()
