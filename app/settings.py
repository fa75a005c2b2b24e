"""User preferences and session state, kept in QSettings.

Tests and ``MRM_SETTINGS_FILE`` point the settings at an INI file of their own, so tests never read or write
the user's real preferences (the test suite sets ``MRM_SETTINGS_ISOLATED``, which without an explicit file
means a fresh temporary one).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Any

from PySide6 import QtCore, QtGui

from mrm.app.application import APPLICATION, ORGANIZATION
from mrm.core.models import DEFAULT_MODEL, Model

#: Colours given to new objects in turn (colour-blind-safe, after Okabe & Ito / Tableau).
DEFAULT_OBJECT_COLOURS = (
    "#0072b2",
    "#e69f00",
    "#009e73",
    "#cc79a7",
    "#d55e00",
    "#56b4e9",
    "#8c6d31",
    "#7f3c8d",
)

MAX_RECENT = 10


def make_settings(path: str | os.PathLike[str] | None = None) -> QtCore.QSettings:
    """Return the QSettings to use.

    In order: ``path`` (an INI file), ``$MRM_SETTINGS_FILE``, a temporary file when ``$MRM_SETTINGS_ISOLATED``
    is set (tests), else the user's native settings for the organisation and application.
    """
    if path is None:
        path = os.environ.get("MRM_SETTINGS_FILE") or None
    if path is None and os.environ.get("MRM_SETTINGS_ISOLATED"):
        path = Path(tempfile.mkdtemp(prefix="mrm-settings-")) / "mrm.ini"
    if path is not None:
        return QtCore.QSettings(str(path), QtCore.QSettings.Format.IniFormat)
    return QtCore.QSettings(ORGANIZATION, APPLICATION)


class Preferences(QtCore.QObject):
    """Typed access to the preferences, with defaults; ``changed`` says which key changed."""

    changed = QtCore.Signal(str)

    def __init__(self, settings: QtCore.QSettings, parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.settings = settings

    # ------------------------------------------------------------------ generic
    def _get(self, key: str, default: Any, kind: type) -> Any:
        v = self.settings.value(key, default)
        if v is None:
            return default
        try:
            if kind is bool and isinstance(v, str):
                return v.lower() in ("1", "true", "yes")
            return kind(v)
        except (TypeError, ValueError):
            return default

    def _set(self, key: str, value: Any) -> None:
        if self.settings.value(key) == value:
            return
        self.settings.setValue(key, value)
        self.changed.emit(key)

    def sync(self) -> None:
        """Write pending changes to storage."""
        self.settings.sync()

    # ------------------------------------------------------------------ documents
    @property
    def default_model(self) -> str:
        """Discretization model of new projects."""
        m = self._get("project/default_model", str(DEFAULT_MODEL), str)
        return m if m in Model.names() else str(DEFAULT_MODEL)

    @default_model.setter
    def default_model(self, m: str) -> None:
        self._set("project/default_model", m if m in Model.names() else str(DEFAULT_MODEL))

    @property
    def autosave_seconds(self) -> int:
        """Seconds between autosaves of a modified document (0 = off)."""
        return max(0, self._get("project/autosave_seconds", 60, int))

    @autosave_seconds.setter
    def autosave_seconds(self, s: int) -> None:
        self._set("project/autosave_seconds", max(0, int(s)))

    def recent_files(self) -> list[str]:
        """Most recent first, existing files only."""
        v = self.settings.value("files/recent", [])
        if isinstance(v, str):
            v = [v]
        return [str(p) for p in (v or []) if Path(str(p)).is_file()][:MAX_RECENT]

    def add_recent_file(self, path: str | os.PathLike[str]) -> None:
        p = str(Path(path).resolve())
        files = [p] + [f for f in self.recent_files() if f != p]
        self.settings.setValue("files/recent", files[:MAX_RECENT])
        self.changed.emit("files/recent")

    def clear_recent_files(self) -> None:
        self.settings.setValue("files/recent", [])
        self.changed.emit("files/recent")

    @property
    def last_directory(self) -> str:
        return self._get("files/last_directory", str(Path.home()), str)

    @last_directory.setter
    def last_directory(self, d: str) -> None:
        self._set("files/last_directory", str(d))

    # ------------------------------------------------------------------ appearance
    @property
    def theme(self) -> str:
        t = self._get("appearance/theme", "system", str)
        return t if t in ("system", "light", "dark") else "system"

    @theme.setter
    def theme(self, t: str) -> None:
        self._set("appearance/theme", t)

    def object_colours(self) -> list[str]:
        v = self.settings.value("appearance/object_colours", None)
        if isinstance(v, str):
            v = [v]
        cols = [str(c) for c in (v or []) if QtGui.QColor(str(c)).isValid()]
        return cols or list(DEFAULT_OBJECT_COLOURS)

    def set_object_colours(self, colours: list[str]) -> None:
        self.settings.setValue("appearance/object_colours", [str(c) for c in colours])
        self.changed.emit("appearance/object_colours")

    @property
    def pixel_grid_threshold(self) -> float:
        """Screen pixels per plane unit above which the pixel grid is drawn."""
        return max(2.0, self._get("appearance/grid_threshold", 8.0, float))

    @pixel_grid_threshold.setter
    def pixel_grid_threshold(self, v: float) -> None:
        self._set("appearance/grid_threshold", float(v))

    @property
    def layout(self) -> str:
        """'grid' (2×2) or 'tabs'."""
        v = self._get("appearance/layout", "grid", str)
        return v if v in ("grid", "tabs") else "grid"

    @layout.setter
    def layout(self, v: str) -> None:
        self._set("appearance/layout", v)

    # ------------------------------------------------------------------ tools
    @property
    def brush_size(self) -> int:
        """Brush diameter in pixels."""
        return min(256, max(1, self._get("tools/brush_size", 3, int)))

    @brush_size.setter
    def brush_size(self, v: int) -> None:
        self._set("tools/brush_size", min(256, max(1, int(v))))

    @property
    def brush_shape(self) -> str:
        v = self._get("tools/brush_shape", "round", str)
        return v if v in ("round", "square") else "round"

    @brush_shape.setter
    def brush_shape(self, v: str) -> None:
        self._set("tools/brush_shape", v)

    @property
    def snap_to_objects(self) -> bool:
        """Whether drawn and dragged points snap to the vertices and edges of objects (on by default)."""
        return bool(self._get("tools/snap_to_objects", True, bool))

    @snap_to_objects.setter
    def snap_to_objects(self, v: bool) -> None:
        self._set("tools/snap_to_objects", bool(v))

    # ------------------------------------------------------------------ operations
    @property
    def live_preview(self) -> bool:
        """Whether the Operations panel previews its result while parameters change (off by default)."""
        return bool(self._get("operations/live_preview", False, bool))

    @live_preview.setter
    def live_preview(self, v: bool) -> None:
        self._set("operations/live_preview", bool(v))

    @property
    def pixel_limit(self) -> int:
        """The largest operation result allowed, in pixels (Preferences ▸ General ▸ Largest result)."""
        from mrm.core.limits import DEFAULT_PIXEL_LIMIT, MAX_OBJECT_PIXELS

        # Never beyond the largest pixel object a document holds: a result over it would be refused anyway.
        v = self._get("operations/pixel_limit", DEFAULT_PIXEL_LIMIT, int)
        return min(MAX_OBJECT_PIXELS, max(1_000, v))

    @pixel_limit.setter
    def pixel_limit(self, v: int) -> None:
        from mrm.core.limits import MAX_OBJECT_PIXELS

        self._set("operations/pixel_limit", min(MAX_OBJECT_PIXELS, max(1_000, int(v))))

    # ------------------------------------------------------------------ shortcuts
    def shortcut_overrides(self) -> dict[str, str]:
        """User-defined shortcuts by action id ('' = none)."""
        s = self.settings
        s.beginGroup("shortcuts")
        try:
            return {k: str(s.value(k, "")) for k in s.childKeys()}
        finally:
            s.endGroup()

    def set_shortcut_overrides(self, overrides: dict[str, str]) -> None:
        s = self.settings
        s.beginGroup("shortcuts")
        s.remove("")
        for k, v in overrides.items():
            s.setValue(k, v)
        s.endGroup()
        self.changed.emit("shortcuts")

    # ------------------------------------------------------------------ window state
    def window_state(self) -> tuple[QtCore.QByteArray | None, QtCore.QByteArray | None]:
        g = self.settings.value("window/geometry")
        st = self.settings.value("window/state")
        return (
            g if isinstance(g, QtCore.QByteArray) else None,
            st if isinstance(st, QtCore.QByteArray) else None,
        )

    def set_window_state(self, geometry: QtCore.QByteArray, state: QtCore.QByteArray) -> None:
        self.settings.setValue("window/geometry", geometry)
        self.settings.setValue("window/state", state)
