"""At 1024×700 the four views keep most of the window: the side panels are tabbed and narrowed."""

from __future__ import annotations

from PySide6 import QtWidgets


def _settle(qtbot, win, w: int, h: int) -> None:  # type: ignore[no-untyped-def]
    win.resize(w, h)
    qtbot.waitUntil(lambda: win.width() == w and win.height() == h, timeout=5000)
    for _ in range(5):
        QtWidgets.QApplication.processEvents()


def test_views_are_wide_enough_at_1024_by_700(make_window, qtbot):
    win = make_window(size=(1360, 880))
    _settle(qtbot, win, 1024, 700)
    widths = [v.width() for v in win.views.views]
    # Before: about 170 px each. Two columns of views now share at least 55 % of the window.
    assert min(widths) >= 260, widths
    assert sum(widths[:2]) >= 0.5 * win.width()
    for v in win.views.views:
        w, h = v.plane.viewport_size()
        assert w >= 200 and h >= 180  # the plot area itself, axes aside
    # Every panel is still there: tabs on the right, the inspector below them, the list in sight on the left.
    tabbed = {d.windowTitle() for d in win.tabifiedDockWidgets(win.operations_dock)}
    assert tabbed == {"Properties", "Measure"}
    assert win.inspector_dock.isVisible()
    assert win.objects_dock.isVisible() and win.objects_dock.width() >= 160
    assert win.operations_dock.width() >= 220
    assert win.operations.apply_button.isVisible()
    # The operation panel fits its column (no horizontal scrolling needed to reach Apply).
    scroll = win.operations_dock.widget()
    assert isinstance(scroll, QtWidgets.QScrollArea)
    assert not scroll.horizontalScrollBar().isVisible()
    assert not scroll.verticalScrollBar().isVisible()  # Apply in sight without scrolling


def test_tabs_layout_gives_one_view_the_whole_centre(make_window, qtbot):
    win = make_window(size=(1360, 880))
    _settle(qtbot, win, 1024, 700)
    win.registry["view.tabs_layout"].trigger()
    for _ in range(5):
        QtWidgets.QApplication.processEvents()
    current = win.views.current_view()
    assert current is not None and current.width() >= 530


def test_a_wide_window_keeps_the_default_panel_widths(make_window, qtbot):
    win = make_window(size=(1360, 880))
    _settle(qtbot, win, 1600, 900)
    assert win.objects_dock.width() >= 220 and win.operations_dock.width() >= 290
