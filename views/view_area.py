"""The four representation views in a 2×2 grid or as tabs, sharing one camera (linked pan and zoom).

The 3D objects have four views of their own (:class:`mrm.views.view3d.View3DArea`), made the first time
they are shown: :meth:`ViewArea.set_dimension` switches between the plane views and the 3D views.
"""

from __future__ import annotations

from typing import Any

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
    #: 2 or 3: which views are shown.
    dimensionChanged = QtCore.Signal(int)

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
        self._dimension = 2
        self.area3d: Any = None  # the 3D views, made when first shown (they load OpenGL)
        self.set_layout_mode("grid")
        for v in self.views:
            self.camera.add_view(v.plane)
        scene.documentChanged.connect(self._reveal_new)

    # ------------------------------------------------------------------ framing
    def visible_rect(self) -> tuple[float, float, float, float] | None:
        """The plane rectangle every shown view shows whole (None before the views have a size)."""
        c = self.camera
        sizes = [v.plane.viewport_size() for v in self.visible_views() if v.isVisible()]
        sizes = [(w, h) for w, h in sizes if w > 4 and h > 4]
        if not sizes:
            return None
        hw = min(w for w, _h in sizes) / (2 * c.scale)
        hh = min(h for _w, h in sizes) / (2 * c.scale)
        return (c.cx - hw, c.cy - hh, c.cx + hw, c.cy + hh)

    def frame(self, box: tuple[float, float, float, float]) -> None:
        """Show ``box`` (with a pixel of room around it) whole in every view."""
        x0, y0, x1, y1 = box
        self.camera.fit((x0 - 1, y0 - 1, x1 + 1, y1 + 1))

    def _reveal_new(self, ch: Any) -> None:
        """Bring new objects (an operation's results, a paste, an import) into view when they are outside.

        The first object is framed; a further one widens the view to take it in, keeping what was shown. An
        object already in view moves nothing. A whole new document (File ▸ Open) is framed by the window.
        """
        if ch.reset or not ch.inserted:
            return
        doc = self.scene.doc
        # the plane views frame plane objects; 3D ones have the 3D views' own Fit
        flat = [i for i in ch.inserted if i in doc and doc.get(i).dimension == 2]
        box = joint_box(object_box(self.scene.source(i)) for i in flat)
        shown = self.visible_rect()
        if box is None or shown is None or _inside(box, shown):
            return
        if all(i in ch.inserted for i in (o.id for o in doc.plane_objects)):
            self.frame(box)
        else:
            self.camera.fit(joint_box([box, shown]) or box, margin=0.02)

    @property
    def dimension(self) -> int:
        """2 while the plane views are shown, 3 while the 3D views are."""
        return self._dimension

    def set_dimension(self, dimension: int) -> None:
        """Show the plane views (2) or the 3D views (3)."""
        if dimension not in (2, 3) or dimension == self._dimension:
            return
        self._dimension = dimension
        if dimension == 3:
            if self.area3d is None:
                from mrm.views.view3d import View3DArea  # loads OpenGL only when 3D is first shown

                self.area3d = View3DArea(self.scene, self)
                self._stack.addWidget(self.area3d)
            self._stack.setCurrentWidget(self.area3d)
        else:
            self._stack.setCurrentWidget(self._grid_page if self._mode == "grid" else self._tabs)
            QtCore.QTimer.singleShot(0, self._reapply_camera)
        self.dimensionChanged.emit(dimension)

    def set_dimension_checked(self, three_d: bool) -> None:
        """The 3D Views action's slot: its check state chooses the views."""
        self.set_dimension(3 if three_d else 2)

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
            if self._dimension == 2:
                self._stack.setCurrentWidget(self._grid_page)
        else:
            for v in self.views:
                self._grid.removeWidget(v)
                self._tabs.addTab(v, v.title)
            self._tabs.setCurrentWidget(current or self.discrete)
            if self._dimension == 2:
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
        flat = all(v.is_drawn() for v in self.views)
        return flat and (self.area3d is None or self.area3d.is_drawn())

    def by_name(self, name: str) -> RepresentationView:
        for v in self.views:
            if v.name == name:
                return v
        raise KeyError(name)


def object_box(source: Any) -> tuple[float, float, float, float] | None:
    """The plane rectangle an object's source covers (a pixel is the unit square about its centre)."""
    if hasattr(source, "bounds"):
        return None if source.is_empty else tuple(float(v) for v in source.bounds)  # type: ignore[return-value]
    b = getattr(source, "bbox", None)
    if b is None:
        return None
    return (b[0] - 0.5, b[1] - 0.5, b[2] + 0.5, b[3] + 0.5)


def joint_box(
    boxes: Any,
) -> tuple[float, float, float, float] | None:
    """The smallest rectangle holding every box given (None boxes skipped; None if there are none)."""
    got = [b for b in boxes if b is not None]
    if not got:
        return None
    return (min(b[0] for b in got), min(b[1] for b in got), max(b[2] for b in got), max(b[3] for b in got))


def _inside(box: tuple[float, float, float, float], rect: tuple[float, float, float, float]) -> bool:
    return rect[0] <= box[0] and rect[1] <= box[1] and box[2] <= rect[2] and box[3] <= rect[3]
