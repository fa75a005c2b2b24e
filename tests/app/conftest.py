"""GUI test fixtures: a main-window factory that owns cleanup, settings isolated per test, task runners.

Every window gets its own INI settings file and autosave folder under the test's tmp_path, so no test reads
or writes the user's preferences or leaves files behind. The default runner is synchronous: derived
representations and operations finish before the triggering call returns, which makes the GUI
deterministic; tests of threading and cancelling ask for the real runner.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from PySide6 import QtCore, QtWidgets

from mrm.app.application import configure
from mrm.app.main_window import MainWindow
from mrm.app.settings import Preferences, make_settings
from mrm.app.tasks import SynchronousTaskRunner, TaskRunner
from mrm.views.failures import FAILURE_RECORD


@pytest.fixture(autouse=True)
def _configured_app(qapp: QtWidgets.QApplication) -> QtWidgets.QApplication:
    configure(qapp)
    return qapp


@pytest.fixture(autouse=True)
def _no_unexpected_failure(request, caplog) -> Iterator[None]:  # type: ignore[no-untyped-def]
    """Fail a test in which background work failed unexpectedly (a bug), unless it uses ``expect_failures``.

    The window shows such a failure as a message and logs its traceback (:mod:`mrm.views.failures`) instead
    of raising it: without this check a bug in a worker would only colour a status line red.
    """
    yield
    if "expect_failures" in request.fixturenames:
        return
    bad = [r for r in caplog.get_records("call") if getattr(r, FAILURE_RECORD, False)]
    if bad:
        pytest.fail("unexpected failure in background work:\n" + "\n".join(r.getMessage() for r in bad))


@pytest.fixture
def expect_failures(caplog) -> Callable[[], list[str]]:  # type: ignore[no-untyped-def]
    """For a test that provokes a failure: the check above is off; returns a function listing them."""
    return lambda: [r.getMessage() for r in caplog.get_records("call") if getattr(r, FAILURE_RECORD, False)]


@pytest.fixture
def prefs(tmp_path: Path) -> Preferences:
    """Preferences backed by an INI file of this test only."""
    return Preferences(make_settings(tmp_path / "settings" / "mrm.ini"))


@pytest.fixture
def sync_runner() -> SynchronousTaskRunner:
    return SynchronousTaskRunner()


@pytest.fixture
def autosave_dir(tmp_path: Path) -> Path:
    d = tmp_path / "autosave"
    d.mkdir()
    return d


WindowFactory = Callable[..., MainWindow]


@pytest.fixture
def make_window(qtbot, prefs: Preferences, autosave_dir: Path) -> Iterator[WindowFactory]:  # type: ignore[no-untyped-def]
    """``make_window(threaded=False, size=(1200, 800))`` → a shown main window, closed at teardown.

    ``size=None`` keeps the size the window gives itself (a user's first start); ``restore=True`` restores
    the geometry and dock layout the last window saved, before showing it, as ``mrm`` does.
    """
    windows: list[MainWindow] = []

    def factory(
        *,
        threaded: bool = False,
        size: tuple[int, int] | None = (1200, 800),
        prefs_: Preferences | None = None,
        restore: bool = False,
    ) -> MainWindow:
        runner = TaskRunner() if threaded else SynchronousTaskRunner()
        w = MainWindow(prefs_ or prefs, runner=runner, autosave_dir=autosave_dir)
        if size is not None:
            w.resize(*size)
        if restore:
            w.restore_window_state()
        w.show()
        qtbot.waitExposed(w)
        w.activateWindow()  # window shortcuts only reach the active window
        qtbot.waitUntil(lambda: QtWidgets.QApplication.activeWindow() is w, timeout=5000)
        windows.append(w)
        return w

    yield factory
    for w in windows:
        w.close_now(discard_autosave=True)
        w.deleteLater()
    QtWidgets.QApplication.processEvents()
    QtCore.QCoreApplication.sendPostedEvents(None, QtCore.QEvent.Type.DeferredDelete)
    import gc

    gc.collect()
