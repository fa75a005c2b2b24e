"""QApplication set-up: offscreen-safe start, HiDPI, a palette following the system's light or dark theme.

Everything here runs before the first widget exists. The palette is rebuilt when the system switches
between light and dark (``QStyleHints.colorSchemeChanged``) unless the user picked a theme in the
preferences; the views listen to the application's palette change and recolour their backgrounds.
"""

from __future__ import annotations

import os
import sys

from PySide6 import QtCore, QtGui, QtWidgets

ORGANIZATION = "MR Modeler"
APPLICATION = "mrm"
DISPLAY_NAME = "MR Modeler"

#: Themes a user can pick in the preferences.
THEMES = ("system", "light", "dark")


def has_display() -> bool:
    """True when a window can be shown: a platform was forced, or an X11/Wayland display exists."""
    if os.environ.get("QT_QPA_PLATFORM"):
        return True
    if sys.platform.startswith("linux") or "bsd" in sys.platform:
        return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
    return True


#: glibc's malloc settings for the window's process and its worker processes (which inherit them): big blocks
#: from the heap, not from their own mappings, and freed memory kept for the next ones.
MALLOC_ENV = {"MALLOC_MMAP_MAX_": "0", "MALLOC_TRIM_THRESHOLD_": str(1 << 36)}


def keep_freed_memory() -> bool:
    """Keep the memory of freed big arrays in the process for the next ones (Linux, glibc); True if set.

    Each big numpy array used to be a mapping of its own, unmapped when freed, so every derivation of a
    10⁸-pixel object page-faulted gigabytes of fresh memory in again. On a virtual machine that reports
    freed pages to its host (virtio-balloon free page reporting) those faults stalled the whole machine for
    20-90 ms at a time — the window included, whatever its threads did: a probe in another process saw the
    same gaps. Kept by the allocator, freed memory is reused without a fault. The cost: a process keeps
    about its peak size (the window returns free heap beyond 2 GB). ``MRM_KEEP_MEMORY=0`` turns it off.
    """
    if not sys.platform.startswith("linux") or os.environ.get("MRM_KEEP_MEMORY", "1") == "0":
        return False
    import ctypes

    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):  # not glibc
        return False
    for key, value in MALLOC_ENV.items():
        os.environ.setdefault(key, value)  # the worker processes read these when they start
    m_trim_threshold, m_mmap_max = -1, -4  # glibc's <malloc.h>
    return bool(mallopt(m_mmap_max, 0)) and bool(mallopt(m_trim_threshold, 2**31 - 1))


def create_application(argv: list[str] | None = None, *, offscreen: bool = False) -> QtWidgets.QApplication:
    """Return the process's QApplication, creating and configuring it on the first call.

    Parameters
    ----------
    argv : list of str, optional
        Arguments for Qt (the program name first); ``sys.argv[:1]`` by default.
    offscreen : bool
        Render without a display (``--screenshot`` on a headless machine); ignored once Qt is running.
    """
    existing = QtWidgets.QApplication.instance()
    if isinstance(existing, QtWidgets.QApplication):
        configure(existing)
        return existing
    if offscreen and not os.environ.get("QT_QPA_PLATFORM"):
        os.environ["QT_QPA_PLATFORM"] = "offscreen"
    # R on one thread in the window's process and its workers (which inherit this): on two cores, R's
    # threads (mrm.geometry.reconstruct) took the core the GUI thread paints on, and a derivation of a
    # 77 M-pixel result stalled it 208-233 ms where one thread left it at 34-96 ms. The user can override.
    os.environ.setdefault("MRM_THREADS", "1")
    keep_freed_memory()
    # Fractional scale factors (150 %) render crisply only without rounding; set before the app exists.
    QtGui.QGuiApplication.setHighDpiScaleFactorRoundingPolicy(
        QtCore.Qt.HighDpiScaleFactorRoundingPolicy.PassThrough
    )
    share_opengl_contexts()
    app = QtWidgets.QApplication(list(argv) if argv else sys.argv[:1])
    configure(app)
    return app


def share_opengl_contexts() -> None:
    """Let every OpenGL view share one set of GL resources; call before the QApplication exists.

    pyqtgraph compiles each shader program once and keeps its id; a 3D view in a second window (a new
    context) would otherwise draw with an id its own context does not know ("invalid value" from
    glUseProgram).
    """
    QtCore.QCoreApplication.setAttribute(QtCore.Qt.ApplicationAttribute.AA_ShareOpenGLContexts)


def _guard_refcount_leak() -> bool:
    """Protect the process from Qt bindings that drop references to None, True and False.

    PySide6 6.12.0 on Python 3.11 releases a reference to None on every Qt call returning ``void``; None's
    count starts near 4,500, so a session aborts ("deallocating None") after a few thousand calls. Python 3.12
    made these objects immortal; on older Pythons we measure the leak and, if there is one, give the three
    objects a count no leak can exhaust — the same thing 3.12 does. Returns True when the guard was needed.
    """
    if sys.version_info >= (3, 12):
        return False
    probe = QtCore.QObject()
    before = sys.getrefcount(None)
    for _ in range(64):
        probe.setObjectName("probe")
    if before - sys.getrefcount(None) < 32:
        return False
    import ctypes

    for obj in (None, True, False):
        ctypes.c_ssize_t.from_address(id(obj)).value += 1 << 40  # ob_refcnt is the first field
    return True


def configure(app: QtWidgets.QApplication) -> None:
    """Set names, style, palette and pyqtgraph defaults on ``app`` (idempotent)."""
    if app.property("mrm_configured"):
        return
    app.setProperty("mrm_configured", True)
    _guard_refcount_leak()
    # Every Qt callback into Python (each paint, each boundingRect) takes the GIL back from the workers;
    # a worker running Python gives it up only at the switch interval, 5 ms by default, so a repaint of the
    # four views could wait hundreds of such turns while a derivation runs. 1 ms halves those stalls
    # (ADR 0019).
    sys.setswitchinterval(min(sys.getswitchinterval(), 0.001))
    app.setOrganizationName(ORGANIZATION)
    app.setApplicationName(APPLICATION)
    app.setApplicationDisplayName(DISPLAY_NAME)
    app.setDesktopFileName("mr-modeler")
    # Fusion draws the same on every platform and honours a custom palette fully (the native styles do not).
    app.setStyle("Fusion")
    # Big outlines are drawn through Qt's item caches (views/items.py), which live in QPixmapCache: room
    # for a few views' worth of them (the default 10 MB holds two full-screen pictures).
    QtGui.QPixmapCache.setCacheLimit(max(QtGui.QPixmapCache.cacheLimit(), 96 * 1024))
    import pyqtgraph as pg

    # Keep pyqtgraph's QPainter path (no OpenGL: it needs a display) and its default image axis order:
    # the views pass axisOrder per item so nothing global changes behind another library's back.
    pg.setConfigOptions(useOpenGL=False, antialias=True)
    ThemeController(app).apply()  # parented to the app, which keeps it alive


def theme_controller() -> ThemeController:
    """Return the controller that owns the palette of the running application."""
    app = QtWidgets.QApplication.instance()
    assert isinstance(app, QtWidgets.QApplication)
    ctl = app.findChild(ThemeController, "mrm_theme_controller")
    if ctl is None:
        configure(app)
        ctl = app.findChild(ThemeController, "mrm_theme_controller")
    assert ctl is not None
    return ctl


class ThemeController(QtCore.QObject):
    """Builds the light or dark palette and follows the system's colour scheme."""

    themeChanged = QtCore.Signal(bool)  # dark?

    def __init__(self, app: QtWidgets.QApplication) -> None:
        super().__init__(app)
        self.setObjectName("mrm_theme_controller")
        self._app = app
        self._preference = "system"
        self._light_palette = QtGui.QPalette(app.style().standardPalette())
        hints = QtGui.QGuiApplication.styleHints()
        hints.colorSchemeChanged.connect(self._system_changed)

    def set_preference(self, theme: str) -> None:
        """Fix the theme ('light', 'dark') or follow the system ('system')."""
        if theme not in THEMES:
            theme = "system"
        self._preference = theme
        self.apply()

    def is_dark(self) -> bool:
        """True when the dark palette is (or would be) in force."""
        if self._preference == "dark":
            return True
        if self._preference == "light":
            return False
        scheme = QtGui.QGuiApplication.styleHints().colorScheme()
        return scheme == QtCore.Qt.ColorScheme.Dark

    def apply(self) -> None:
        """Install the palette that matches the preference and the system's scheme."""
        dark = self.is_dark()
        self._app.setPalette(dark_palette() if dark else QtGui.QPalette(self._light_palette))
        self.themeChanged.emit(dark)

    def _system_changed(self, _scheme: QtCore.Qt.ColorScheme) -> None:
        if self._preference == "system":
            self.apply()


def dark_palette() -> QtGui.QPalette:
    """A dark Fusion palette with enough contrast for text, selections and disabled items."""
    c = QtGui.QColor
    roles = QtGui.QPalette.ColorRole
    group = QtGui.QPalette.ColorGroup
    p = QtGui.QPalette()
    base, window, text = c(32, 33, 36), c(45, 47, 51), c(222, 224, 227)
    p.setColor(roles.Window, window)
    p.setColor(roles.WindowText, text)
    p.setColor(roles.Base, base)
    p.setColor(roles.AlternateBase, c(40, 42, 46))
    p.setColor(roles.ToolTipBase, c(55, 58, 63))
    p.setColor(roles.ToolTipText, text)
    p.setColor(roles.PlaceholderText, c(140, 143, 148))
    p.setColor(roles.Text, text)
    p.setColor(roles.Button, window)
    p.setColor(roles.ButtonText, text)
    p.setColor(roles.BrightText, c(255, 90, 90))
    p.setColor(roles.Light, c(70, 72, 77))
    p.setColor(roles.Midlight, c(58, 60, 65))
    p.setColor(roles.Mid, c(38, 39, 43))
    p.setColor(roles.Dark, c(22, 23, 25))
    p.setColor(roles.Shadow, c(0, 0, 0))
    p.setColor(roles.Highlight, c(61, 126, 214))
    p.setColor(roles.HighlightedText, c(255, 255, 255))
    p.setColor(roles.Link, c(110, 168, 254))
    p.setColor(roles.LinkVisited, c(170, 140, 250))
    for r in (roles.WindowText, roles.Text, roles.ButtonText):
        p.setColor(group.Disabled, r, c(120, 122, 126))
    p.setColor(group.Disabled, roles.Highlight, c(70, 72, 77))
    return p
