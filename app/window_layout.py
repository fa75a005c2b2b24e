"""How the main window's panels are placed and sized: docks, their default widths, fitting the screen.

The window (:class:`mrm.app.main_window.MainWindow`) calls these when it is built, restored and resized. They
place and resize its docks only; what the panels hold and do is theirs.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from PySide6 import QtCore, QtGui, QtWidgets

if TYPE_CHECKING:
    from mrm.app.main_window import MainWindow

#: The first window's size, made smaller on a smaller screen (:meth:`MainWindow.fit_to_screen`).
DEFAULT_SIZE = (1360, 880)
#: Room left for the window's frame and title bar while the window manager has not said how big they are.
FRAME_ALLOWANCE = (16, 48)

#: Side panels' widths at the default size and their least useful widths (the views get the rest).
LEFT_WIDTH, RIGHT_WIDTH = 230, 300
LEFT_MIN, RIGHT_MIN = 170, 230


def fit_to_screen(win: MainWindow) -> None:
    """Make the window, its frame included, fit the available area of the screen it is on.

    A 1360×880 window on a 1024×700 screen had its right column and status bar off the screen; a saved
    geometry from a bigger screen is fitted the same way.
    """
    screen = QtGui.QGuiApplication.screenAt(win.geometry().center()) or win.screen()
    if screen is None:
        return
    avail = screen.availableGeometry()
    frame = win.frameGeometry()
    extra_w, extra_h = frame.width() - win.width(), frame.height() - win.height()
    if extra_w == 0 and extra_h == 0 and not win.isVisible():
        extra_w, extra_h = FRAME_ALLOWANCE
    least = win.minimumSizeHint()
    w = max(least.width(), min(win.width(), avail.width() - extra_w))
    h = max(least.height(), min(win.height(), avail.height() - extra_h))
    if (w, h) != (win.width(), win.height()):
        win.resize(w, h)
    # Then keep it on the screen: its frame's top-left moved in just enough.
    x = max(avail.left(), min(frame.left(), avail.right() + 1 - (w + extra_w)))
    y = max(avail.top(), min(frame.top(), avail.bottom() + 1 - (h + extra_h)))
    if (x, y) != (frame.left(), frame.top()):
        win.move(x, y)


def fit_side_panels(win: MainWindow, window_width: int) -> None:
    """Side panels at their default widths, narrowed on a small window so the views keep 55 % of it."""
    spare = max(0, window_width * 45 // 100 - 10)
    left = max(LEFT_MIN, min(LEFT_WIDTH, spare * LEFT_WIDTH // (LEFT_WIDTH + RIGHT_WIDTH)))
    right = max(RIGHT_MIN, min(RIGHT_WIDTH, spare - left))
    win.resizeDocks([win.objects_dock], [left], QtCore.Qt.Orientation.Horizontal)
    win.resizeDocks([win.operations_dock], [right], QtCore.Qt.Orientation.Horizontal)


def fit_operations_height(win: MainWindow) -> None:
    """Give the Operations tab the height its fields and Apply need on a short window.

    The inspector below it gets the rest, and keeps at least a third of the column.
    """
    area = win.operations_dock.widget()
    if not isinstance(area, QtWidgets.QScrollArea) or win.inspector_dock.isFloating():
        return
    if win.operations_dock.isFloating() or not win.inspector_dock.isVisible():
        return
    panel = win.operations
    width = area.viewport().width()
    need = panel.heightForWidth(width) if panel.hasHeightForWidth() else panel.sizeHint().height()
    if area.viewport().height() >= need:
        return
    total = win.operations_dock.height() + win.inspector_dock.height()
    extra = win.operations_dock.height() - area.viewport().height()
    ops = min(need + extra + 24, total * 2 // 3)  # + the tab bar: resizeDocks sizes the tab group
    pair = [win.operations_dock, win.inspector_dock]
    win.resizeDocks(pair, [ops, total - ops], QtCore.Qt.Orientation.Vertical)


def make_dock(
    win: MainWindow, title: str, widget: QtWidgets.QWidget, area: QtCore.Qt.DockWidgetArea
) -> QtWidgets.QDockWidget:
    """A movable, closable, floatable dock holding ``widget``."""
    d = QtWidgets.QDockWidget(title, win)
    d.setObjectName(f"dock_{title.lower().replace(' ', '_')}")
    d.setWidget(widget)
    widget.setMinimumWidth(min(widget.minimumSizeHint().width(), RIGHT_MIN))
    d.setFeatures(
        QtWidgets.QDockWidget.DockWidgetFeature.DockWidgetMovable
        | QtWidgets.QDockWidget.DockWidgetFeature.DockWidgetClosable
        | QtWidgets.QDockWidget.DockWidgetFeature.DockWidgetFloatable
    )
    win.addDockWidget(area, d)
    return d


def scrolled(panel: QtWidgets.QWidget) -> QtWidgets.QScrollArea:
    """``panel`` in a scroll area: a narrow or short side column scrolls instead of squeezing the views."""
    area = QtWidgets.QScrollArea()
    area.setObjectName(f"{panel.objectName()}Scroll")
    area.setWidget(panel)
    area.setWidgetResizable(True)
    area.setFrameShape(QtWidgets.QFrame.Shape.NoFrame)
    area.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarPolicy.ScrollBarAsNeeded)
    return area
