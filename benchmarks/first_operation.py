"""The first operation after a start: how long Apply takes on a small object, by how soon it is pressed.

Run:  .venv/bin/python benchmarks/first_operation.py [--delays 0.5,2,10] [--repeat 3] [--load 0]

Each measurement is a fresh ``mrm`` start-up in a child process (the real start path of :mod:`mrm.app.gui`:
the window painted, the kernels loaded, the worker processes warmed), on the display of ``DISPLAY`` (offscreen
without one). Once the document is open the child waits ``delay`` seconds, then clicks Apply of DSS 2 on a
193-pixel disk and measures the time until the result is added (the Operations panel's ``applied``).
``--load N`` runs N busy Python loops meanwhile (a loaded machine). The issue: 8–9 s for the first operation,
0.01 s for the next ones.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def _disk_project(folder: Path) -> Path:
    import numpy as np

    from mrm.core.grids import PixelSet
    from mrm.document import Document, Settings
    from mrm.document.commands import AddObject
    from mrm.io.project import save_project

    doc = Document(Settings())
    yy, xx = np.mgrid[0:17, 0:17]
    obj = doc.make_object(PixelSet((xx - 8) ** 2 + (yy - 8) ** 2 <= 61, (0, 0)), name="disk")  # 193 pixels
    doc.push(AddObject(obj, select=True))
    path = folder / "disk.mrm"
    save_project(doc, path)
    return path


def child(project: str, delay: float) -> None:
    """One start-up: open ``project``, wait ``delay`` s, Apply DSS 2, print the figures as JSON."""
    t_start = time.perf_counter()
    from PySide6 import QtCore, QtTest, QtWidgets

    from mrm.app.application import create_application, has_display
    from mrm.app.main_window import MainWindow
    from mrm.app.processes import close_pool
    from mrm.app.settings import Preferences, make_settings
    from mrm.app.startup import prepare_then, when_exposed

    app = create_application([sys.argv[0]], offscreen=not has_display())
    home = Path(tempfile.mkdtemp(prefix="mrm-first-op-"))  # no preferences or autosaves of the user
    prefs = Preferences(make_settings(home / "mrm.ini"))
    win = MainWindow(prefs, autosave_dir=home / "autosave")
    win.show()
    out: dict[str, float] = {}

    def click() -> None:
        panel = win.operations
        panel.select_operation("dss")
        panel.control("alpha").set_value(2.0)
        out["clicked"] = time.perf_counter() - t_start
        QtTest.QTest.mouseClick(panel.apply_button, QtCore.Qt.MouseButton.LeftButton)

    def applied(_ids: list[int]) -> None:
        out["operation"] = time.perf_counter() - t_start - out["clicked"]
        out["message"] = win.operations.status.text()  # type: ignore[assignment]
        # Not app.quit(): Qt 6 closes the windows first, and this one would ask to save.
        QtCore.QTimer.singleShot(0, win.close_now)

    def load() -> None:
        win.files.open(Path(project), ask=False)
        out["loaded"] = time.perf_counter() - t_start
        QtCore.QTimer.singleShot(round(delay * 1000), click)

    win.operations.applied.connect(applied)
    when_exposed(win, lambda: prepare_then(win, load))
    QtCore.QTimer.singleShot(300_000, win.close_now)
    app.exec()
    QtWidgets.QApplication.processEvents()
    close_pool()
    print(json.dumps(out))


def _busy() -> None:
    while True:
        pass


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--delays", default="0.5,2,10", help="seconds between the document opening and Apply")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--load", type=int, default=0, help="busy Python loops running meanwhile")
    p.add_argument("--child", nargs=2, metavar=("PROJECT", "DELAY"), help=argparse.SUPPRESS)
    a = p.parse_args()
    if a.child:
        child(a.child[0], float(a.child[1]))
        return
    import multiprocessing

    hogs = [multiprocessing.Process(target=_busy, daemon=True) for _ in range(a.load)]
    for h in hogs:
        h.start()
    try:
        with tempfile.TemporaryDirectory() as tmp:
            project = _disk_project(Path(tmp))
            print(f"display: {os.environ.get('DISPLAY') or 'offscreen'}; busy loops: {a.load}")
            print(f"{'Apply after':>12} {'first op (s)':>14}  each run")
            for delay in (float(d) for d in a.delays.split(",")):
                runs = []
                for _ in range(a.repeat):
                    r = subprocess.run(
                        [sys.executable, __file__, "--child", str(project), str(delay)],
                        capture_output=True,
                        text=True,
                        check=True,
                    )
                    got = json.loads(r.stdout.strip().splitlines()[-1])
                    runs.append(got.get("operation", float("inf")))  # inf: not done within 5 minutes
                each = " ".join(f"{v:.2f}" for v in runs)
                print(f"{delay:>10.1f} s {statistics.median(runs):>14.2f}  {each}")
    finally:
        for h in hogs:
            h.kill()


if __name__ == "__main__":
    main()
