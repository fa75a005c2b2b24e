"""The four representation views in a 2×2 grid or as tabs, sharing one camera (linked pan and zoom)."""

from __future__ import annotations

from PySide6 import QtCore, QtWidgets

from mrm.views.analytical_view import AnalyticalView
from mrm.views.base_view import RepresentationView
from mrm.views.canvas import Camera
from mrm.views.discrete_view import DiscreteView
from mrm.views.euclidean_view import EuclideanView
from mrm.views.region_view import RegionView
from mrm.views.scene import Scene


class ViewArea(QtWidgets.QWidget):
    """Holds the discrete, region, analytical and Euclidean views; ``layout_mode`` is 'grid' or 'tabs'."""

    layoutChanged = QtCore.Signal(str)

    def __init__(self, scene: Scene, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("viewArea")
        self.scene = scene
        self.camera = Camera(self)
        self.discrete = DiscreteView(scene)
        self.region = RegionView(scene)
        self.analytical = AnalyticalView(scene)
        self.euclidean = EuclideanView(scene)
        self.views: list[RepresentationView] = [self.discrete, self.region, self.analytical, self.euclidean]
        self._stack = QtWidgets.QStackedLayout(self)
        self._grid_page = QtWidgets.QWidget(self)
        self._grid = QtWidgets.QGridLayout(self._grid_page)
        self._grid.setContentsMargins(0, 0, 0, 0)
        self._grid.setSpacing(4)
        for k in range(2):
            self._grid.setColumnStretch(k, 1)
            self._grid.setRowStretch(k, 1)
        self._tabs = QtWidgets.QTabWidget(self)
        self._tabs.setDocumentMode(True)
        self._tabs.currentChanged.connect(self._tab_changed)
        self._stack.addWidget(self._grid_page)
        self._stack.addWidget(self._tabs)
        self._mode = ""
        self.set_layout_mode("grid")
        for v in self.views:
            self.camera.add_view(v.plane)

    @property
    def layout_mode(self) -> str:
        return self._mode

    def set_layout_mode(self, mode: str) -> None:
        if mode not in ("grid", "tabs") or mode == self._mode:
            return
        current = self.current_view()
        self._mode = mode
        if mode == "grid":
            while self._tabs.count():
                self._tabs.removeTab(0)
            for k, v in enumerate(self.views):
                self._grid.addWidget(v, k // 2, k % 2)
                v.show()
            self._stack.setCurrentWidget(self._grid_page)
        else:
            for v in self.views:
                self._grid.removeWidget(v)
                self._tabs.addTab(v, v.title)
            self._tabs.setCurrentWidget(current or self.discrete)
            self._stack.setCurrentWidget(self._tabs)
        QtCore.QTimer.singleShot(0, self._reapply_camera)
        self.layoutChanged.emit(mode)

    def _reapply_camera(self) -> None:
        c = self.camera
        c.set(c.cx, c.cy, c.scale)

    def _tab_changed(self, _index: int) -> None:
        self._reapply_camera()

    def current_view(self) -> RepresentationView | None:
        if self._mode == "tabs":
            w = self._tabs.currentWidget()
            return w if isinstance(w, RepresentationView) else None
        for v in self.views:
            if v.plane.hasFocus():
                return v
        return None

    def show_view(self, view: RepresentationView) -> None:
        """Bring ``view`` forward (its tab) and give it the keyboard focus."""
        if self._mode == "tabs":
            self._tabs.setCurrentWidget(view)
        view.plane.setFocus()

    def visible_views(self) -> list[RepresentationView]:
        if self._mode == "tabs":
            v = self.current_view()
            return [v] if v is not None else []
        return list(self.views)

    def is_drawn(self) -> bool:
        return all(v.is_drawn() for v in self.views)

    def by_name(self, name: str) -> RepresentationView:
        for v in self.views:
            if v.name == name:
                return v
        raise KeyError(name)
