"""The four representation views of 3D objects (voxel sets, polyhedra), on OpenGL, sharing one camera.

Each view draws the document's 3D objects (``DocObject.dimension == 3``) as the plane views draw the 2D
ones: the **discrete** view the surfels of the voxels (the faces between a voxel of A and one outside), the
**region** view the same surfaces coloured by component (cavity surfaces red), the **analytical** view each
digital plane segment in its own colour, and the **Euclidean** view the polyhedron R(A) (or the polyhedron
itself) with the edges of its faces. Drawing data (:mod:`mrm.views.gl_mesh`) is made on a worker beyond
:attr:`View3D.PREPARE_SYNC` elements, as in the plane views, and the representations come from the scene,
computed on its workers.

The camera (:class:`Camera3D`) is one for the four views: orbiting, panning or zooming in one moves the
others (left drag orbits, Ctrl + left drag or middle drag pans, the wheel zooms), and Fit, Front, Top and Side
set it for all. OpenGL needs a real display: under Qt's ``offscreen`` platform (the test suite's default) the
views are not created and :class:`View3DArea` says why instead (docs/adr/0055).
"""

from __future__ import annotations

import logging
import math
from typing import Any, ClassVar

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets

from mrm.document import Changes, DocObject
from mrm.document.derive import Rep
from mrm.views import gl_mesh
from mrm.views.base_view import PreparedDrawing
from mrm.views.scene import Scene

log = logging.getLogger(__name__)

#: Qt platforms without OpenGL widgets (QOpenGLWidget aborts the process there).
NO_OPENGL_PLATFORMS = ("offscreen", "minimal")

Box3 = tuple[tuple[float, float, float], tuple[float, float, float]]


def opengl_available() -> bool:
    """True when the running Qt platform can show OpenGL widgets."""
    return QtGui.QGuiApplication.platformName() not in NO_OPENGL_PLATFORMS


class Camera3D(QtCore.QObject):
    """One camera for the four 3D views: a change made in one pane is copied to the others."""

    changed = QtCore.Signal()

    #: (elevation, azimuth) in degrees of the named directions of view. Front looks along +y, side along −x.
    PRESETS: ClassVar[dict[str, tuple[float, float]]] = {
        "front": (0.0, -90.0),
        "top": (90.0, -90.0),
        "side": (0.0, 0.0),
        "iso": (30.0, -60.0),
    }

    def __init__(self, parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.panes: list[Any] = []
        self._syncing = False

    def add_pane(self, pane: Any) -> None:
        self.panes.append(pane)
        if len(self.panes) > 1:
            pane.setCameraParams(**self.params())

    def params(self) -> dict[str, Any]:
        """The shared camera's parameters (centre, distance, elevation, azimuth, field of view)."""
        p = dict(self.panes[0].cameraParams()) if self.panes else {}
        p.pop("rotation", None)  # pyqtgraph's quaternion mode is not used: euler angles only
        return p

    def sync_from(self, source: Any) -> None:
        """Copy ``source``'s camera to every other pane."""
        if self._syncing:
            return
        self._syncing = True
        try:
            params = dict(source.cameraParams())
            params.pop("rotation", None)
            for pane in self.panes:
                if pane is not source:
                    pane.setCameraParams(**params)
        finally:
            self._syncing = False
        self.changed.emit()

    def set(self, **params: Any) -> None:
        """Set parameters (``center``, ``distance``, ``elevation``, ``azimuth``) on every pane."""
        if not self.panes:
            return
        first = self.panes[0]
        first.setCameraParams(**params)
        self.sync_from(first)

    def fit(self, box: Box3 | None) -> None:
        """Centre on ``box`` and back off until it is seen whole (keeping the direction of view)."""
        if box is None or not self.panes:
            return
        lo, hi = np.asarray(box[0], float), np.asarray(box[1], float)
        centre = (lo + hi) / 2
        radius = max(float(np.linalg.norm(hi - lo)) / 2, 1.0)
        fov = float(self.panes[0].opts.get("fov", 60.0))
        distance = radius / math.sin(math.radians(fov) / 2) * 1.05
        self.set(center=QtGui.QVector3D(*map(float, centre)), distance=distance)

    def preset(self, name: str) -> None:
        """Look from the front, the top, the side or obliquely (``iso``), keeping centre and distance."""
        elevation, azimuth = self.PRESETS[name]
        self.set(elevation=elevation, azimuth=azimuth)


def _gl() -> Any:
    # Imported only where OpenGL runs: importing pyqtgraph.opengl loads PyOpenGL.
    import pyqtgraph.opengl as gl

    return gl


_HEADLIGHT = "mrm-headlight"


def headlight_shader() -> str:
    """The name of the views' shader: a light at the camera, so that faces towards the viewer are bright.

    pyqtgraph's ``shaded`` program lights from a fixed direction behind the viewer's left shoulder in eye
    space, which leaves faces wound counter-clockwise towards the camera (the model's outward orientation)
    at their 20 % ambient level. Here brightness follows the eye-space normal's component towards the
    viewer, whichever way a face is wound, so the three face directions of a voxel surface stay distinct.
    """
    from pyqtgraph.opengl import shaders

    if _HEADLIGHT not in shaders.ShaderProgram.names:
        vertex = shaders.getShaderProgram("shaded").shaders[0].code
        fragment = """
            #ifdef GL_ES
            precision mediump float;
            #endif
            varying vec4 v_color;
            varying vec3 v_normal;
            void main() {
                vec3 n = normalize(v_normal);
                float p = 0.35 + 0.5 * abs(n.z) + 0.15 * abs(dot(n, normalize(vec3(0.5, 0.8, 0.3))));
                gl_FragColor = vec4(v_color.rgb * p, v_color.a);
            }
        """
        shaders.ShaderProgram(_HEADLIGHT, [shaders.VertexShader(vertex), shaders.FragmentShader(fragment)])
    return _HEADLIGHT


def make_pane(camera: Camera3D, parent: QtWidgets.QWidget) -> Any:
    """A pyqtgraph GLViewWidget whose camera moves are shared through ``camera``."""
    gl = _gl()

    class GLPane(gl.GLViewWidget):  # type: ignore[misc, name-defined]
        def mouseMoveEvent(self, ev: QtGui.QMouseEvent) -> None:
            super().mouseMoveEvent(ev)
            if ev.buttons():
                camera.sync_from(self)

        def wheelEvent(self, ev: QtGui.QWheelEvent) -> None:
            super().wheelEvent(ev)
            camera.sync_from(self)

    pane = GLPane(parent)
    pane.setObjectName("glPane")
    pane.setBackgroundColor(pane.palette().color(QtGui.QPalette.ColorRole.Base))
    pane.setMinimumSize(120, 90)
    camera.add_pane(pane)
    return pane


class View3D(PreparedDrawing, QtWidgets.QFrame):
    """Base of the four 3D views: a header and an OpenGL pane drawing each visible 3D object."""

    name = "base3d"
    title = ""
    subtitle = ""
    #: The representation whose readiness and errors the header reports.
    rep: Rep = "discrete"

    #: Emitted after each refresh (tests wait for it).
    refreshed = QtCore.Signal()

    def __init__(self, scene: Scene, camera: Camera3D, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName(f"view3d_{self.name}")
        self.scene = scene
        self.camera = camera
        self.setFrameShape(QtWidgets.QFrame.Shape.StyledPanel)
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.setSpacing(0)
        header = QtWidgets.QWidget(self)
        header.setObjectName("viewHeader")
        hl = QtWidgets.QHBoxLayout(header)
        hl.setContentsMargins(8, 3, 6, 3)
        hl.addWidget(QtWidgets.QLabel(f"<b>{self.title}</b>", header))
        sub = QtWidgets.QLabel(self.subtitle, header)
        sub.setObjectName("viewSubtitle")
        hl.addWidget(sub, 2)
        self.status_label = QtWidgets.QLabel("", header)
        self.status_label.setObjectName("viewStatus")
        self.status_label.setAlignment(
            QtCore.Qt.AlignmentFlag.AlignRight | QtCore.Qt.AlignmentFlag.AlignVCenter
        )
        for lab in (sub, self.status_label):
            lab.setSizePolicy(QtWidgets.QSizePolicy.Policy.Ignored, QtWidgets.QSizePolicy.Policy.Preferred)
        hl.addWidget(self.status_label, 3)
        lay.addWidget(header)
        self.pane = make_pane(camera, self)
        lay.addWidget(self.pane, 1)
        #: obj_id -> (the drawing data it shows, its GL items)
        self._items: dict[int, tuple[Any, list[Any]]] = {}
        self._waiting: set[int] = set()
        self.init_prepared_drawing()
        self._timer = QtCore.QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self.refresh)
        scene.documentChanged.connect(self._on_changes)
        scene.derivedReady.connect(lambda _i: self._timer.start())
        self._timer.start()

    # ------------------------------------------------------------------ scheduling
    def _on_changes(self, _changes: Changes) -> None:
        self._timer.start()

    def mark_dirty(self, _obj_id: int) -> None:
        self._timer.start()

    def objects(self) -> list[DocObject]:
        """The visible 3D objects of the document, bottom first."""
        return [o for o in self.scene.doc.objects if o.dimension == 3 and o.style.visible]

    def is_drawn(self) -> bool:
        """True when nothing is waiting to be drawn or computed."""
        return not self._timer.isActive() and not self._waiting and not self.is_preparing()

    def refresh(self) -> None:
        """Bring the drawn items up to date with the document's 3D objects and their representations."""
        self._timer.stop()
        shown = {o.id: o for o in self.objects()}
        for i in [i for i in self._items if i not in shown]:
            self._remove(i)
        self._waiting.clear()
        errors = []
        for obj in shown.values():
            data = self.drawing_data(obj)
            if data is None:
                error = self.scene.error(obj.id, self.rep)
                if error:
                    errors.append(f"{obj.name}: {error}")
                else:
                    self._waiting.add(obj.id)
                continue
            old = self._items.get(obj.id)
            if old is not None and old[0] is data:
                continue
            self._remove(obj.id)
            items = self.make_items(obj, data)
            for it in items:
                self.pane.addItem(it)
            self._items[obj.id] = (data, items)
        if errors:
            self.status_label.setText(f"<span style='color:#c0392b'>{errors[0]}</span>")
            self.status_label.setToolTip("\n".join(errors))
        else:
            self.status_label.setText("computing…" if self._waiting else "")
            self.status_label.setToolTip("")
        self.refreshed.emit()

    def _remove(self, obj_id: int) -> None:
        _data, items = self._items.pop(obj_id, (None, []))
        for it in items:
            self.pane.removeItem(it)
        self.forget_prepared(obj_id)

    def bounds(self) -> Box3 | None:
        """The box holding every drawn vertex (None when nothing is drawn)."""
        boxes = [d["box"] for d, _items in self._items.values() if d.get("box") is not None]
        if not boxes:
            return None
        lo = np.min([b[0] for b in boxes], axis=0)
        hi = np.max([b[1] for b in boxes], axis=0)
        return (tuple(map(float, lo)), tuple(map(float, hi)))  # type: ignore[return-value]

    # ------------------------------------------------------------------ per view
    def drawing_data(self, obj: DocObject) -> dict[str, Any] | None:
        """The mesh of ``obj`` in this view, or None while its representation or mesh is being computed."""
        raise NotImplementedError

    def make_items(self, obj: DocObject, data: dict[str, Any]) -> list[Any]:
        """The GL items drawing ``data`` (a triangle mesh with one colour per triangle, optional lines)."""
        gl = _gl()
        items = []
        if data["vertices"].size:
            md = gl.MeshData(vertexes=data["vertices"], faces=data["triangles"], faceColors=data["colours"])
            items.append(
                gl.GLMeshItem(meshdata=md, smooth=False, shader=headlight_shader(), glOptions="opaque")
            )
        lines = data.get("lines")
        if lines is not None and lines.size:
            colour = gl_mesh.rgba("#202020")
            items.append(
                gl.GLLinePlotItem(pos=lines, color=colour, width=1.5, mode="lines", glOptions="opaque")
            )
        return items

    # ------------------------------------------------------------------ shared drawing data
    def surfel_data(self, obj: DocObject, colour_of: Any) -> dict[str, Any] | None:
        """Surfel meshes of a voxel object's surfaces, coloured by ``colour_of(region, surfaces)``."""
        if obj.kind == "labels":
            return None  # a label volume's surfaces come with its meshes (issue 29, item 5)
        region = self.scene.get(obj.id, "region")
        if region is None:
            return None
        n = int(region.n_surfels)

        def compute() -> dict[str, Any]:
            surfaces = region.surfaces
            voxels = np.concatenate([s.voxels for s in surfaces]) if surfaces else np.zeros((0, 3), np.int64)
            dirs = np.concatenate([s.directions for s in surfaces]) if surfaces else np.zeros(0, np.uint8)
            vertices, triangles = gl_mesh.surfel_mesh(voxels, dirs)
            return _with_box(
                {"vertices": vertices, "triangles": triangles, "colours": colour_of(region, surfaces)}
            )

        return self.prepared(obj.id, "surfels", region, n, compute)


def _with_box(data: dict[str, Any]) -> dict[str, Any]:
    v = data["vertices"]
    data["box"] = (tuple(v.min(axis=0)), tuple(v.max(axis=0))) if v.size else None
    return data


class DiscreteView3D(View3D):
    """The voxels, drawn by their surfels in the object's colour."""

    name = "discrete3d"
    title = "Discrete"
    subtitle = "voxels (their surfaces)"
    rep: Rep = "region"

    def drawing_data(self, obj: DocObject) -> dict[str, Any] | None:
        colour = obj.style.fill

        def colours(_region: Any, surfaces: Any) -> Any:
            n = sum(len(s) for s in surfaces)
            return np.tile(np.array(gl_mesh.rgba(colour), np.float32), (2 * n, 1))

        return self.surfel_data(obj, colours)


class RegionView3D(View3D):
    """The surfaces of the components, one colour per component; cavity surfaces in red."""

    name = "region3d"
    title = "Region"
    subtitle = "components and cavities"
    rep: Rep = "region"

    def drawing_data(self, obj: DocObject) -> dict[str, Any] | None:
        def colours(_region: Any, surfaces: Any) -> Any:
            k = len(gl_mesh.COMPONENT_COLOURS_3D)
            index = (
                np.concatenate(
                    [
                        np.full(len(s), k if s.cavity >= 0 else (s.component - 1) % k, np.int64)
                        for s in surfaces
                    ]
                )
                if surfaces
                else np.zeros(0, np.int64)
            )
            return gl_mesh.palette_colours(index, (*gl_mesh.COMPONENT_COLOURS_3D, gl_mesh.CAVITY_COLOUR))

        return self.surfel_data(obj, colours)


class AnalyticalView3D(View3D):
    """The digital plane segments of the surfaces, neighbouring segments in different colours."""

    name = "analytical3d"
    title = "Analytical"
    subtitle = "digital plane segments"
    rep: Rep = "analytical"

    def drawing_data(self, obj: DocObject) -> dict[str, Any] | None:
        if obj.kind == "labels":
            return None
        ana = self.scene.get(obj.id, "analytical")
        region = self.scene.get(obj.id, "region")
        if ana is None or region is None:
            return None
        seg = ana.segmentation

        def compute() -> dict[str, Any]:
            vertices, triangles = gl_mesh.surfel_mesh(seg.voxel, seg.direction)
            # the surfels' neighbours, numbered over all surfaces in the segmentation's order
            offsets = np.cumsum([0, *[len(s) for s in region.surfaces]])
            neighbours = (
                np.concatenate([s.neighbours + o for s, o in zip(region.surfaces, offsets[:-1], strict=True)])
                if region.surfaces
                else None
            )
            index = gl_mesh.segment_colour_indices(seg.segment_of, neighbours)
            colours = gl_mesh.palette_colours(index[seg.segment_of], gl_mesh.SEGMENT_COLOURS_3D)
            return _with_box({"vertices": vertices, "triangles": triangles, "colours": colours})

        return self.prepared(obj.id, "segments", ana, int(seg.segment_of.size), compute)


class EuclideanView3D(View3D):
    """The polyhedron: its triangles in the object's colour and the edges of its faces."""

    name = "euclidean3d"
    title = "Euclidean"
    subtitle = "polyhedron and its faces"
    rep: Rep = "euclidean"

    def drawing_data(self, obj: DocObject) -> dict[str, Any] | None:
        if obj.kind == "labels":
            return None
        poly = self.scene.get(obj.id, "euclidean")
        if poly is None:
            return None
        colour = obj.style.fill

        def compute() -> dict[str, Any]:
            vertices = np.asarray(poly.vertices, np.float32)
            triangles = np.asarray(poly.triangles, np.int32)
            colours = np.tile(np.array(gl_mesh.rgba(colour), np.float32), (len(triangles), 1))
            lines = gl_mesh.face_edges(poly.vertices, poly.triangles, poly.face_of_triangle)
            return _with_box(
                {"vertices": vertices, "triangles": triangles, "colours": colours, "lines": lines}
            )

        return self.prepared(obj.id, "polyhedron", poly, int(poly.n_triangles), compute)


class View3DArea(QtWidgets.QWidget):
    """The four 3D views in a 2×2 grid with the camera's buttons, or a note where OpenGL is unavailable."""

    def __init__(self, scene: Scene, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("view3dArea")
        self.scene = scene
        self.camera = Camera3D(self)
        self.views: list[View3D] = []
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.setSpacing(2)
        if not opengl_available():
            note = QtWidgets.QLabel(
                "The 3D views need OpenGL, which this display does not offer "
                f"(Qt platform '{QtGui.QGuiApplication.platformName()}'). "
                "Run MR Modeler on a desktop or under Xvfb to see 3D objects.",
                self,
            )
            note.setObjectName("noOpenGL")
            note.setWordWrap(True)
            note.setAlignment(QtCore.Qt.AlignmentFlag.AlignCenter)
            lay.addWidget(note, 1)
            return
        bar = QtWidgets.QHBoxLayout()
        bar.setContentsMargins(6, 2, 6, 0)
        self.buttons: dict[str, QtWidgets.QToolButton] = {}
        for key, text, tip in (
            ("fit", "Fit", "Show every 3D object whole (Home)"),
            ("front", "Front", "Look along +y"),
            ("top", "Top", "Look down the z axis"),
            ("side", "Side", "Look along −x"),
            ("iso", "Oblique", "Look from above, at an angle"),
        ):
            b = QtWidgets.QToolButton(self)
            b.setObjectName(f"camera_{key}")
            b.setText(text)
            b.setToolTip(tip)
            b.setAutoRaise(True)
            b.clicked.connect(self.fit if key == "fit" else (lambda _c=False, k=key: self.camera.preset(k)))
            bar.addWidget(b)
            self.buttons[key] = b
        bar.addStretch(1)
        lay.addLayout(bar)
        grid = QtWidgets.QGridLayout()
        grid.setSpacing(4)
        for k, cls in enumerate((DiscreteView3D, RegionView3D, AnalyticalView3D, EuclideanView3D)):
            view = cls(scene, self.camera, self)
            grid.addWidget(view, k // 2, k % 2)
            grid.setColumnStretch(k % 2, 1)
            grid.setRowStretch(k // 2, 1)
            self.views.append(view)
            view.refreshed.connect(self._fit_first)
        lay.addLayout(grid, 1)
        self.camera.preset("iso")
        self._fitted = False
        scene.documentChanged.connect(self._on_changes)

    def _on_changes(self, changes: Changes) -> None:
        if changes.reset:
            self._fitted = False

    def _fit_first(self) -> None:
        # The first time something is drawn (and after File ▸ Open), frame it.
        if not self._fitted and self.bounds() is not None:
            self._fitted = True
            self.fit()

    def bounds(self) -> Box3 | None:
        """The box holding what the four views draw."""
        boxes = [b for v in self.views if (b := v.bounds()) is not None]
        if not boxes:
            return None
        lo = np.min([b[0] for b in boxes], axis=0)
        hi = np.max([b[1] for b in boxes], axis=0)
        return (tuple(map(float, lo)), tuple(map(float, hi)))  # type: ignore[return-value]

    def fit(self) -> None:
        """Frame every drawn 3D object in the four views."""
        self.camera.fit(self.bounds())

    def is_drawn(self) -> bool:
        """True when the four views have drawn everything (always, without OpenGL)."""
        return all(v.is_drawn() for v in self.views)

    def by_name(self, name: str) -> View3D:
        for v in self.views:
            if v.name == name:
                return v
        raise KeyError(name)
