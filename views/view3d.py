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
from mrm.views.palette import CHOSEN_SEGMENT_COLOUR
from mrm.views.scene import Scene
from mrm.views.view_header import ViewHeader

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


def joint_box3(boxes: Any) -> Box3 | None:
    """The smallest box holding every 3D box given (None boxes skipped; None if there are none)."""
    got = [b for b in boxes if b is not None]
    if not got:
        return None
    lo = np.min([b[0] for b in got], axis=0)
    hi = np.max([b[1] for b in got], axis=0)
    return (tuple(map(float, lo)), tuple(map(float, hi)))  # type: ignore[return-value]


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


#: The axis gizmo's colours (x red, y green, z blue, as in every 3D tool), its radius and margin in pixels.
GIZMO_COLOURS = ("#d62728", "#2ca02c", "#1f77b4")
GIZMO_RADIUS = 26
GIZMO_MARGIN = 12


def gizmo_axes(view: QtGui.QMatrix4x4) -> np.ndarray:
    """Where the x, y and z axes point on the screen: rows (right, up, towards the viewer) per axis.

    The rotation part of the camera's view matrix takes world directions to eye coordinates (x right,
    y up, z towards the viewer); its columns are the world axes seen from the camera.
    """
    m = np.array(view.data(), np.float64).reshape(4, 4).T  # Qt stores the matrix column-major
    return m[:3, :3].T.copy()


def draw_axis_gizmo(painter: QtGui.QPainter, view: QtGui.QMatrix4x4, height: int) -> None:
    """Draw the axis gizmo in the bottom-left corner: x, y and z as the camera sees them, farthest first."""
    axes = gizmo_axes(view)
    centre = QtCore.QPointF(GIZMO_MARGIN + GIZMO_RADIUS, height - GIZMO_MARGIN - GIZMO_RADIUS)
    painter.setRenderHint(QtGui.QPainter.RenderHint.Antialiasing)
    font = painter.font()
    font.setBold(True)
    painter.setFont(font)
    for i in np.argsort(axes[:, 2], kind="stable"):  # the axis pointing away first, the nearest on top
        right, up = axes[i, 0], axes[i, 1]
        tip = QtCore.QPointF(centre.x() + GIZMO_RADIUS * right, centre.y() - GIZMO_RADIUS * up)
        colour = QtGui.QColor(GIZMO_COLOURS[i])
        painter.setPen(QtGui.QPen(colour, 2.5))
        painter.drawLine(centre, tip)
        label = QtCore.QPointF(
            centre.x() + (GIZMO_RADIUS + 8) * right - 4, centre.y() - (GIZMO_RADIUS + 8) * up + 5
        )
        painter.drawText(label, "xyz"[i])


def make_pane(camera: Camera3D, parent: QtWidgets.QWidget) -> Any:
    """A pyqtgraph GLViewWidget whose camera moves are shared through ``camera``."""
    gl = _gl()

    class GLPane(gl.GLViewWidget):  # type: ignore[misc, name-defined]
        #: The view whose tool gets the mouse first (painting on the slice plane); None: the camera only.
        owner: Any = None

        def mousePressEvent(self, ev: QtGui.QMouseEvent) -> None:
            if self.owner is not None and self.owner.pane_press(ev):
                return
            super().mousePressEvent(ev)

        def mouseMoveEvent(self, ev: QtGui.QMouseEvent) -> None:
            if self.owner is not None and self.owner.pane_move(ev):
                return
            super().mouseMoveEvent(ev)
            if ev.buttons():
                camera.sync_from(self)

        def mouseReleaseEvent(self, ev: QtGui.QMouseEvent) -> None:
            if self.owner is not None and self.owner.pane_release(ev):
                return
            super().mouseReleaseEvent(ev)

        def keyPressEvent(self, ev: QtGui.QKeyEvent) -> None:
            if self.owner is not None and self.owner.pane_key(ev):
                return
            super().keyPressEvent(ev)

        def contextMenuEvent(self, ev: QtGui.QContextMenuEvent) -> None:
            menu = self.owner.context_menu() if self.owner is not None else None
            if menu is None or menu.isEmpty():
                super().contextMenuEvent(ev)
                return
            menu.exec(ev.globalPos())

        def wheelEvent(self, ev: QtGui.QWheelEvent) -> None:
            super().wheelEvent(ev)
            camera.sync_from(self)

        def paintGL(self) -> None:
            super().paintGL()
            from OpenGL import GL

            # An item's GL options stay set after it (the differences are drawn with face culling on):
            # QPainter strokes lines as triangles, which culling drops. Its engine resets the rest.
            GL.glDisable(GL.GL_CULL_FACE)
            with QtGui.QPainter(self) as painter:
                draw_axis_gizmo(painter, self.viewMatrix(), self.height())

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
        self.header = ViewHeader(self.title, self.subtitle, self)
        self.header.restyle(self.palette())
        self.status_label = self.header.status_label
        lay.addWidget(self.header)
        self.pane = make_pane(camera, self)
        self.pane.owner = self
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
            # the items only: the drawing data just prepared stays (forgetting it made every worker's result
            # send the other objects back to their workers, each refresh in turn, without end)
            self._remove(obj.id, forget=False)
            items = self.make_items(obj, data)
            for it in items:
                self.pane.addItem(it)
            self._items[obj.id] = (data, items)
        if errors:
            self.header.show_status(errors[0], "\n".join(errors), error=True)
        elif self._waiting:
            self.header.show_status("computing…")
        else:
            factor = self.coarsest_level()
            text, tip = self.level_note(factor) if factor > 1 else ("", "")
            notes = [f"{o.name}: {n}" for o in shown.values() if (n := self.object_note(o)) is not None]
            if notes:  # before the level: the note says what the object is, the level only how it is drawn
                text = " · ".join(t for t in (self.NOTE_TEXT, text) if t)
                tip = "\n".join(t for t in (*notes, tip) if t)
            self.header.show_status(text, tip)
        self.refreshed.emit()

    #: The header's text when an object's :meth:`object_note` says something (the notes go in its tool tip).
    NOTE_TEXT = ""

    def object_note(self, obj: DocObject) -> str | None:
        """What the header's tool tip says of a drawn object beyond its drawing (None: nothing)."""
        return None

    def level_note(self, factor: int) -> tuple[str, str]:
        """The header's text and tool tip when a coarser level (``factor`` > 1) is drawn."""
        return (
            f"coarser level: blocks of {factor}³ voxels",
            f"An object has more than its share of the view's {self.SURFEL_BUDGET:,} surfels: each block of "
            f"{factor}×{factor}×"
            f"{factor} voxels holding one is drawn as one voxel.",
        )

    def coarsest_level(self) -> int:
        """The largest pooling factor among the drawn objects (1: every object drawn at full detail)."""
        return max((int(d.get("factor", 1)) for d, _items in self._items.values()), default=1)

    def _remove(self, obj_id: int, *, forget: bool = True) -> None:
        _data, items = self._items.pop(obj_id, (None, []))
        for it in items:
            self.pane.removeItem(it)
        if forget:
            self.forget_prepared(obj_id)

    def bounds(self) -> Box3 | None:
        """The box holding every drawn vertex (None when nothing is drawn)."""
        return joint_box3(d.get("box") for d, _items in self._items.values())

    # ------------------------------------------------------------------ mouse and keys (editing views)
    def pane_press(self, ev: QtGui.QMouseEvent) -> bool:
        """Handle a press in the pane before the camera does (True: handled)."""
        return False

    def pane_move(self, ev: QtGui.QMouseEvent) -> bool:
        return False

    def pane_release(self, ev: QtGui.QMouseEvent) -> bool:
        return False

    def pane_key(self, ev: QtGui.QKeyEvent) -> bool:
        return False

    def context_menu(self) -> QtWidgets.QMenu | None:
        """The pane's context menu (None: none)."""
        return None

    def target(self) -> DocObject | None:
        """The voxel object the view's edits apply to: the selected one, else the topmost."""
        voxels = [o for o in self.objects() if o.kind != "labels"]
        selected = set(self.scene.doc.selection)
        chosen = [o for o in voxels if o.id in selected] or voxels
        return chosen[-1] if chosen else None

    def replace_voxels(self, obj_id: int, voxels: Any, label: str) -> None:
        """Replace an object's voxels in one undo step; a refusal (a limit) is one line in the header."""
        from mrm.core.errors import MRMError
        from mrm.document.commands import SetSource

        try:
            self.scene.doc.push(SetSource(obj_id, voxels, label=label))
        except MRMError as e:  # the document stays as it was
            self.header.show_status(str(e), error=True)

    def ray_at(self, pos: QtCore.QPointF) -> tuple[np.ndarray, np.ndarray]:
        """The ray from the camera through the pane's point ``pos`` (widget pixels): origin and direction."""
        w, h = max(self.pane.width(), 1), max(self.pane.height(), 1)
        proj = self.pane.projectionMatrix((0, 0, w, h), (0, 0, w, h))
        m = np.array((proj * self.pane.viewMatrix()).data(), np.float64).reshape(4, 4).T  # column-major data
        inv = np.linalg.inv(m)
        nx, ny = 2.0 * pos.x() / w - 1.0, 1.0 - 2.0 * pos.y() / h
        ends = []
        for nz in (-1.0, 1.0):
            p = inv @ np.array([nx, ny, nz, 1.0])
            ends.append(p[:3] / p[3])
        return ends[0], ends[1] - ends[0]

    def screen_of(self, point: Any) -> QtCore.QPointF:
        """The pane's widget point where world ``point`` (x, y, z) is drawn (tests aim with it)."""
        w, h = max(self.pane.width(), 1), max(self.pane.height(), 1)
        proj = self.pane.projectionMatrix((0, 0, w, h), (0, 0, w, h))
        m = np.array((proj * self.pane.viewMatrix()).data(), np.float64).reshape(4, 4).T
        c = m @ np.array([*map(float, point), 1.0])
        return QtCore.QPointF((c[0] / c[3] + 1.0) * w / 2, (1.0 - c[1] / c[3]) * h / 2)

    # ------------------------------------------------------------------ tools
    def add_tool_row(self, *widgets: QtWidgets.QWidget) -> None:
        """Put a view's tools in a row of their own under the header.

        Beside the title they left the subtitle and the state no room at all in a quarter of the window.
        """
        strip = QtWidgets.QWidget(self)
        strip.setObjectName("viewTools")
        row = QtWidgets.QHBoxLayout(strip)
        row.setContentsMargins(8, 0, 6, 2)
        row.setSpacing(6)
        for w in widgets:
            row.addWidget(w)
        row.addStretch(1)
        layout = self.layout()
        assert isinstance(layout, QtWidgets.QBoxLayout)
        layout.insertWidget(1, strip)

    def _tool_button(self, name: str, text: str, tip: str) -> QtWidgets.QToolButton:
        b = QtWidgets.QToolButton(self)
        b.setObjectName(name)
        b.setText(text)
        b.setToolTip(tip)
        b.setCheckable(True)
        b.setAutoRaise(True)
        return b

    def _z_spin(self, name: str, prefix: str, tip: str) -> QtWidgets.QSpinBox:
        """A spin box for a plane z = k (the slice, the cut), disabled until its tool is on."""
        spin = QtWidgets.QSpinBox(self)
        spin.setObjectName(name)
        spin.setPrefix(prefix)
        spin.setRange(-(2**30), 2**30)
        spin.setToolTip(tip)
        spin.setEnabled(False)
        return spin

    def _target_voxels(self) -> tuple[DocObject, Any] | None:
        obj = self.target()
        if obj is None:
            return None
        vs = self.scene.get(obj.id, "discrete")
        return None if vs is None else (obj, vs)

    def middle_z(self) -> int:
        """The middle layer of the target voxel object (0 without one): where a slice or a cut starts."""
        tv = self._target_voxels()
        box = tv[1].bbox if tv is not None else None
        return (box[2] + box[5]) // 2 if box is not None else 0

    # ------------------------------------------------------------------ per view
    def drawing_data(self, obj: DocObject) -> dict[str, Any] | None:
        """The mesh of ``obj`` in this view, or None while its representation or mesh is being computed."""
        raise NotImplementedError

    def make_items(self, obj: DocObject, data: dict[str, Any]) -> list[Any]:
        """The GL items drawing ``data``: arrays made on a worker, uploaded as they are.

        ``data`` is :func:`gl_mesh.surfel_arrays`' or :func:`gl_mesh.triangle_arrays`', lines optional.
        """
        gl = _gl()
        items = []
        if data["vertices"].size:
            items.append(ready_mesh_item(data))
        lines = data.get("lines")
        if lines is not None and lines.size:
            colour = gl_mesh.rgba("#202020")
            items.append(
                gl.GLLinePlotItem(pos=lines, color=colour, width=1.5, mode="lines", glOptions="opaque")
            )
        return items

    # ------------------------------------------------------------------ shared drawing data
    #: Surfels a view draws of one object at most: beyond, a coarser level (blocks of f³ voxels pooled into
    #: one, :mod:`mrm.geometry.topology.level_of_detail`) is drawn instead. The four views repaint together
    #: when the camera moves; on Mesa's llvmpipe (2 cores, a 700 × 450 pane) a frame costs about 10 ms plus
    #: 0.25 µs per surfel (306 k surfels: 84 ms, 77 k: 28 ms, 35 k: 16 ms), so 50 k keeps four under 100 ms.
    SURFEL_BUDGET = 50_000

    #: The least budget an object gets when many share a view (a small object is drawn whole anyway).
    SURFEL_BUDGET_MIN = 5_000

    #: Drawing data up to this many elements is made at once on the GUI thread. A 3D element costs far more
    #: than a pixel of the plane views (a surfel is four vertices, their normals and colours; a triangle's
    #: face edges are found by sorting): 84 k triangles took 80 ms, so beyond 20 k the work goes to a worker.
    PREPARE_SYNC = 20_000

    @staticmethod
    def surfel_work(n: int, budget: int, vs: Any) -> int:
        """How much work the surfels of a voxel object take to prepare.

        ``n`` surfels drawn as they are, or every voxel of the mask when a coarser level must be pooled from
        it (a 10⁶-voxel ball's pooling took 100–200 ms with only 50 k surfels: counting surfels kept it on the
        GUI thread).
        """
        return n if n <= budget else max(n, int(vs.mask.size))

    def object_budget(self) -> int:
        """The surfels one object may draw: the view's budget shared by the 3D objects it draws.

        The budget bounds a frame of the four views (llvmpipe paints on the GUI thread), so three big
        objects on screen get a third each, not 50 k each (a frame of three 10⁶-voxel balls took 0.5–0.8 s).
        """
        shown = sum(1 for o in self.objects() if o.kind != "labels")
        return min(self.SURFEL_BUDGET, max(self.SURFEL_BUDGET_MIN, self.SURFEL_BUDGET // max(1, shown)))

    def budgeted(self, obj_id: int, what: str, budget: int, variant: str = "") -> str:
        """The name of ``obj_id``'s drawing data ``what`` at ``budget`` and ``variant`` (a cut's height).

        The data of another budget or variant is dropped.
        """
        name = f"{what}@{budget}{variant}"
        for key in [
            k for k in self._prepared if k[0] == obj_id and k[1].startswith(f"{what}@") and k[1] != name
        ]:
            del self._prepared[key]
        return name

    def surfel_data(self, obj: DocObject, colour_of: Any, cut: int | None = None) -> dict[str, Any] | None:
        """Surfel meshes of a voxel object's surfaces, coloured by ``colour_of(region, surfaces)``.

        ``colour_of`` gives a uint8 RGBA row per surfel. Beyond :attr:`SURFEL_BUDGET` surfels the surfaces
        drawn are those of a coarser level (max-pooled blocks) and the data's ``factor`` says which.
        ``cut``: only the part z ≤ ``cut`` is drawn, with the faces the cut opens (:func:`gl_mesh.cut_away`).
        """
        if obj.kind == "labels":
            return None  # a label volume's surfaces come with its meshes (issue 29, item 5)
        region = self.scene.get(obj.id, "region")
        vs = self.scene.get(obj.id, "discrete")
        if region is None or vs is None:
            return None
        n = int(region.n_surfels)
        budget = self.object_budget()

        def compute() -> dict[str, Any]:
            from mrm.geometry.topology.level_of_detail import coarse_level
            from mrm.reps.region_3d import region_3d_of

            factor, drawn = 1, region
            if n > budget:
                factor, pooled = coarse_level(vs.mask, budget, n)
                drawn = region_3d_of(pooled)
            surfaces = drawn.surfaces
            voxels = np.concatenate([s.voxels for s in surfaces]) if surfaces else np.zeros((0, 3), np.int64)
            dirs = np.concatenate([s.directions for s in surfaces]) if surfaces else np.zeros(0, np.uint8)
            colours = colour_of(drawn, surfaces)
            if cut is not None:
                # the cut's layer in the drawn level's coordinates (a block holds f layers from the origin)
                top = cut if factor == 1 else (cut - int(vs.origin[2])) // factor
                voxels, dirs, colours = gl_mesh.cut_away(
                    voxels, dirs, colours, drawn.labels(), drawn.origin, top
                )
            data = gl_mesh.surfel_arrays(voxels, dirs, colours, *_placement(vs, factor))
            data["factor"] = factor
            return data

        what = self.budgeted(obj.id, "surfels", budget, "" if cut is None else f"/cut{cut}")
        return self.prepared(obj.id, what, region, self.surfel_work(n, budget, vs), compute)


def _placement(vs: Any, factor: int) -> tuple[float, tuple[float, float, float]]:
    """The scale and offset of :func:`gl_mesh.surfel_mesh` for a level of ``vs`` pooled by ``factor``.

    At factor 1 the voxels are in world coordinates already (the region's surfaces); a pooled level's are
    block indices from the voxel set's origin: block I spans voxels x0 + f·I … x0 + f·I + f − 1.
    """
    if factor == 1:
        return 1.0, (0.0, 0.0, 0.0)
    half = (factor - 1) / 2
    x0, y0, z0 = (float(c) for c in vs.origin)
    return float(factor), (x0 + half, y0 + half, z0 + half)


_READY_MESH: list[type] = []


def ready_mesh_item(data: dict[str, Any]) -> Any:
    """A ``GLMeshItem`` drawing arrays made beforehand (:func:`gl_mesh.surfel_arrays`).

    Its first paint uploads them as they are, instead of building per-face copies on the GUI thread.
    """
    if not _READY_MESH:
        from pyqtgraph.opengl.items.GLMeshItem import DirtyFlag

        gl = _gl()

        class ReadyMeshItem(gl.GLMeshItem):  # type: ignore[misc, name-defined]
            def __init__(self, arrays: dict[str, Any]) -> None:
                super().__init__(smooth=True, shader=headlight_shader(), glOptions="opaque")
                self._arrays = arrays
                self._parsed = False

            def meshDataChanged(self) -> None:
                super().meshDataChanged()
                self._parsed = False

            def parseMeshData(self) -> Any:
                if self._parsed:
                    return DirtyFlag(0)
                self._parsed = True
                a = self._arrays
                self.vertexes, self.normals, self.colors, self.faces = (
                    a["vertices"],
                    a["normals"],
                    a["colours"],
                    a["faces"],
                )
                return DirtyFlag.POSITION | DirtyFlag.NORMAL | DirtyFlag.COLOR | DirtyFlag.FACES

        _READY_MESH.append(ReadyMeshItem)
    return _READY_MESH[0](data)


class DiscreteView3D(View3D):
    """The voxels, drawn by their surfels in the object's colour."""

    name = "discrete3d"
    title = "Discrete"
    subtitle = "voxels (their surfaces)"
    rep: Rep = "region"

    def drawing_data(self, obj: DocObject) -> dict[str, Any] | None:
        colour = gl_mesh.rgba8(obj.style.fill)

        def colours(_region: Any, surfaces: Any) -> Any:
            return np.tile(colour, (sum(len(s) for s in surfaces), 1))

        return self.surfel_data(obj, colours)

    # ------------------------------------------------------------------ the slice plane z = k
    def __init__(self, scene: Scene, camera: Camera3D, parent: QtWidgets.QWidget | None = None) -> None:
        #: The slice plane's z (None: no plane shown).
        self.slice_z: int | None = None
        #: "paint", "erase" or None: what a left drag on the slice plane does.
        self.brush: str | None = None
        self._slice_item: Any = None
        self._difference_item: Any = None  # the voxels that differ from the direct result (show_difference)
        self._stroke: dict[str, Any] | None = None
        super().__init__(scene, camera, parent)
        self.slice_button = self._tool_button(
            "sliceButton", "Slice", "Show the slice plane z = k (PgUp/PgDn)"
        )
        self.slice_button.toggled.connect(self._slice_toggled)
        self.slice_spin = self._z_spin("sliceSpin", "z = ", "The slice plane's z (PgUp/PgDn in the view)")
        self.slice_spin.valueChanged.connect(self._slice_spun)
        self.paint_button = self._tool_button(
            "paintVoxels", "Paint", "Left drag on the slice plane adds voxels (one undo step per stroke)"
        )
        self.erase_button = self._tool_button(
            "eraseVoxels", "Erase", "Left drag on the slice plane removes voxels (one undo step per stroke)"
        )
        self.paint_button.toggled.connect(lambda on: self._brush_toggled("paint", on))
        self.erase_button.toggled.connect(lambda on: self._brush_toggled("erase", on))
        self.add_tool_row(self.slice_button, self.slice_spin, self.paint_button, self.erase_button)

    def set_slice(self, z: int | None) -> None:
        """Show the slice plane at ``z`` (None hides it)."""
        self.slice_z = None if z is None else int(z)
        for w, value in ((self.slice_button, z is not None), (self.slice_spin, z is not None)):
            w.blockSignals(True)
            if w is self.slice_button:
                w.setChecked(value)
            else:
                w.setEnabled(value)
                if z is not None:
                    w.setValue(int(z))
            w.blockSignals(False)
        self._draw_slice()

    def _slice_toggled(self, on: bool) -> None:
        if not on:
            self.set_slice(None)
            return
        self.set_slice(self.middle_z())

    def _slice_spun(self, z: int) -> None:
        if self.slice_z is not None:
            self.set_slice(z)

    def _brush_toggled(self, which: str, on: bool) -> None:
        other = self.erase_button if which == "paint" else self.paint_button
        if on:
            other.setChecked(False)
            self.brush = which
            if self.slice_z is None:
                self._slice_toggled(True)
        elif self.brush == which:
            self.brush = None

    def refresh(self) -> None:
        super().refresh()
        if self.slice_z is not None and self._stroke is None:
            self._draw_slice()

    def _draw_slice(self) -> None:
        """The translucent square of the slice plane over the target's box, its voxels highlighted."""
        if self._slice_item is not None:
            self.pane.removeItem(self._slice_item)
            self._slice_item = None
        tv = self._target_voxels()
        if self.slice_z is None or tv is None:
            return
        _obj, vs = tv
        box = vs.bbox
        if box is None:
            return
        x0, y0 = box[0] - 1, box[1] - 1
        nx, ny = box[3] - box[0] + 3, box[4] - box[1] + 3
        inside = np.zeros((ny, nx), bool)
        k = self.slice_z - box[2]
        if 0 <= k < vs.mask.shape[0]:
            inside[1:-1, 1:-1] = vs.mask[k]
        if self._stroke is not None:
            for x, y in self._stroke["voxels"]:
                if 0 <= x - x0 < nx and 0 <= y - y0 < ny:
                    inside[y - y0, x - x0] = self._stroke["value"]
        image = np.empty((nx, ny, 4), np.uint8)  # GLImageItem's first axis is x
        image[...] = SLICE_PLANE_RGBA
        image[inside.T] = SLICE_VOXEL_RGBA
        gl = _gl()
        from OpenGL import GL

        item = gl.GLImageItem(
            image,
            glOptions={
                GL.GL_DEPTH_TEST: False,
                GL.GL_BLEND: True,
                GL.GL_CULL_FACE: False,
                "glBlendFunc": (GL.GL_SRC_ALPHA, GL.GL_ONE_MINUS_SRC_ALPHA),
            },
        )
        item.translate(x0 - 0.5, y0 - 0.5, float(self.slice_z))
        item.setDepthValue(10)  # drawn after the surfaces, over them
        self.pane.addItem(item)
        self._slice_item = item

    def show_difference(self, data: dict[str, Any] | None) -> None:
        """Draw the voxels that differ from the direct result (light and dark grey), or nothing (None).

        ``data`` is :func:`gl_mesh.difference_arrays`' (made on a worker); drawn over the objects' surfaces.
        """
        if self._difference_item is not None:
            self.pane.removeItem(self._difference_item)
            self._difference_item = None
        if data is None or not data["vertices"].size:
            return
        from OpenGL import GL

        item = ready_mesh_item(data)
        # Over the objects' surfaces, which the differing voxels' surfels often coincide with (no z-fight):
        # drawn last, without the depth test, as the slice plane is.
        item.setGLOptions({GL.GL_DEPTH_TEST: False, GL.GL_BLEND: False, GL.GL_CULL_FACE: True})
        item.setDepthValue(20)
        self.pane.addItem(item)
        self._difference_item = item

    def slice_voxel_at(self, pos: QtCore.QPointF) -> tuple[int, int, int] | None:
        """The voxel of the slice plane under the pane's point ``pos`` (ray-plane intersection)."""
        if self.slice_z is None:
            return None
        origin, direction = self.ray_at(pos)
        if abs(direction[2]) < 1e-12:
            return None  # the ray runs along the plane
        t = (self.slice_z - origin[2]) / direction[2]
        if t < 0:
            return None  # the plane is behind the camera
        p = origin + t * direction
        return (int(np.floor(p[0] + 0.5)), int(np.floor(p[1] + 0.5)), self.slice_z)

    def pane_press(self, ev: QtGui.QMouseEvent) -> bool:
        if self.brush is None or ev.button() != QtCore.Qt.MouseButton.LeftButton or self.slice_z is None:
            return False
        tv = self._target_voxels()
        if tv is None:
            return False
        voxel = self.slice_voxel_at(ev.position())
        if voxel is None:
            return True
        self._stroke = {"obj": tv[0].id, "value": self.brush == "paint", "voxels": {voxel[:2]}, "last": voxel}
        self._draw_slice()
        return True

    def pane_move(self, ev: QtGui.QMouseEvent) -> bool:
        if self._stroke is None:
            return False
        voxel = self.slice_voxel_at(ev.position())
        if voxel is not None:
            # every voxel on the segment from the last one: a fast drag leaves no gap
            (ax, ay, _), (bx, by, _) = self._stroke["last"], voxel
            steps = max(abs(bx - ax), abs(by - ay), 1)
            t = np.linspace(0.0, 1.0, steps + 1)
            xs = np.floor(ax + t * (bx - ax) + 0.5).astype(int)
            ys = np.floor(ay + t * (by - ay) + 0.5).astype(int)
            self._stroke["voxels"].update(zip(xs.tolist(), ys.tolist(), strict=True))
            self._stroke["last"] = voxel
            self._draw_slice()
        return True

    def pane_release(self, ev: QtGui.QMouseEvent) -> bool:
        stroke, self._stroke = self._stroke, None
        if stroke is None:
            return False
        from mrm.core.grids import VoxelSet

        vs = self.scene.get(stroke["obj"], "discrete")
        if vs is None or self.slice_z is None:
            self._draw_slice()
            return True
        pts = np.array([(x, y, self.slice_z) for x, y in stroke["voxels"]], np.int64)
        dab = VoxelSet.from_points(pts)
        after = vs | dab if stroke["value"] else vs - dab
        if after != vs:
            self.replace_voxels(stroke["obj"], after, "Paint voxels" if stroke["value"] else "Erase voxels")
        self._draw_slice()
        return True

    def pane_key(self, ev: QtGui.QKeyEvent) -> bool:
        key = ev.key()
        if key not in (QtCore.Qt.Key.Key_PageUp, QtCore.Qt.Key.Key_PageDown):
            return False
        if self.slice_z is None:
            self._slice_toggled(True)
        else:
            self.set_slice(self.slice_z + (1 if key == QtCore.Qt.Key.Key_PageUp else -1))
        return True


#: The slice plane (translucent) and the voxels of the object it cuts (highlighted), RGBA.
SLICE_PLANE_RGBA = (120, 160, 220, 70)
SLICE_VOXEL_RGBA = (255, 140, 0, 230)


class RegionView3D(View3D):
    """The surfaces of the components, one colour per component; cavity surfaces in red.

    **Cut** cuts the objects away above a plane z = k (the spin box; PgUp/PgDn in the view move it): the
    cavities it crosses open and their red walls show, the cut faces in their component's colour, darker.
    """

    name = "region3d"
    title = "Region"
    subtitle = "components and cavities"
    rep: Rep = "region"

    def __init__(self, scene: Scene, camera: Camera3D, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(scene, camera, parent)
        self.cut_button = self._tool_button(
            "cutButton", "Cut", "Cut the objects away above z = k to see their cavities (PgUp/PgDn move it)"
        )
        self.cut_spin = self._z_spin(
            "cutSpin", "z ≤ ", "The highest layer of voxels drawn (PgUp/PgDn in the view)"
        )
        self.cut_button.toggled.connect(self._cut_toggled)
        self.cut_spin.valueChanged.connect(lambda _z: self.mark_dirty(0))
        self.add_tool_row(self.cut_button, self.cut_spin)

    @property
    def cut(self) -> int | None:
        """The highest layer drawn, or None when nothing is cut away."""
        return self.cut_spin.value() if self.cut_button.isChecked() else None

    def _cut_toggled(self, on: bool) -> None:
        if on:
            self.cut_spin.blockSignals(True)
            self.cut_spin.setValue(self.middle_z())  # through the middle
            self.cut_spin.blockSignals(False)
        self.cut_spin.setEnabled(on)
        self.mark_dirty(0)

    def pane_key(self, ev: QtGui.QKeyEvent) -> bool:
        step = {QtCore.Qt.Key.Key_PageUp: 1, QtCore.Qt.Key.Key_PageDown: -1}.get(ev.key())
        if step is None or not self.cut_button.isChecked():
            return super().pane_key(ev)
        self.cut_spin.setValue(self.cut_spin.value() + step)
        return True

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
            return gl_mesh.palette_rgba8(index, (*gl_mesh.COMPONENT_COLOURS_3D, gl_mesh.CAVITY_COLOUR))

        return self.surfel_data(obj, colours, self.cut)

    #: Components and cavities listed in the context menu at most (the biggest first).
    MENU_ITEMS = 20

    def context_menu(self) -> QtWidgets.QMenu | None:
        """Delete a component or fill a cavity of the target voxel object (each one undo step)."""
        obj = self.target()
        if obj is None:
            return None
        region = self.scene.get(obj.id, "region")
        vs = self.scene.get(obj.id, "discrete")
        if region is None or vs is None:
            return None
        menu = QtWidgets.QMenu(self)
        menu.setObjectName("region3dMenu")
        comps = sorted(region.components, key=lambda c: -c.voxels)[: self.MENU_ITEMS]
        for c in sorted(comps, key=lambda c: c.label):
            act = menu.addAction(f"Delete component {c.label} ({c.voxels:,} voxels)")
            act.triggered.connect(lambda _c=False, label=c.label: self.delete_component(obj.id, label))
        cavities = [(c.label, t, cav) for c in region.components for t, cav in enumerate(c.cavities)]
        if cavities:
            menu.addSeparator()
        for label, t, cav in sorted(cavities, key=lambda x: -x[2].voxels)[: self.MENU_ITEMS]:
            act = menu.addAction(f"Fill cavity {t + 1} of component {label} ({cav.voxels:,} voxels)")
            act.triggered.connect(lambda _c=False, a=label, b=t: self.fill_cavity(obj.id, a, b))
        return menu

    def delete_component(self, obj_id: int, label: int) -> None:
        """Remove component ``label`` (1..n, the region's numbering) of an object's voxels."""
        region, vs = self.scene.get(obj_id, "region"), self.scene.get(obj_id, "discrete")
        if region is not None and vs is not None:
            self.replace_voxels(obj_id, vs - region.component_voxels(label), "Delete component")

    def fill_cavity(self, obj_id: int, component: int, cavity: int) -> None:
        """Fill cavity ``cavity`` (0-based) of component ``component`` of an object's voxels."""
        region, vs = self.scene.get(obj_id, "region"), self.scene.get(obj_id, "discrete")
        if region is not None and vs is not None:
            self.replace_voxels(obj_id, vs | region.cavity_voxels(component, cavity), "Fill cavity")


class AnalyticalView3D(View3D):
    """The digital plane segments of the surfaces, neighbouring segments in different colours.

    A normal of each of the biggest segments (from its preimage, :func:`gl_mesh.segment_normals`) is drawn
    as a line from its centre.
    """

    name = "analytical3d"
    title = "Analytical"
    subtitle = "digital plane segments and their normals"
    rep: Rep = "analytical"
    #: The colour of the plane segment chosen in the Segments panel, drawn over the surfaces (as the plane
    #: analytical view highlights its chosen segment).
    CHOSEN_COLOUR = CHOSEN_SEGMENT_COLOUR

    def __init__(self, scene: Scene, camera: Camera3D, parent: QtWidgets.QWidget | None = None) -> None:
        self._chosen_item: Any = None  # the chosen plane segment's surfels (Scene.plane_segment)
        self._chosen_for: tuple[int, int, Any] = (-1, -1, None)  # what it draws: object, segment, segments
        super().__init__(scene, camera, parent)
        scene.planeSegmentSelected.connect(self._segment_chosen)

    def _segment_chosen(self, _obj_id: int, _index: int) -> None:
        self._draw_chosen()

    def refresh(self) -> None:
        super().refresh()
        self._draw_chosen()

    def _draw_chosen(self) -> None:
        """Draw the chosen plane segment's surfels in :attr:`CHOSEN_COLOUR`, over everything (or nothing)."""
        obj_id, k = self.scene.plane_segment
        ana = self.scene.get(obj_id, "analytical") if obj_id in self._items else None
        if ana is None or not 0 <= k < len(ana):
            ana, obj_id, k = None, -1, -1
        was_obj, was_k, was_ana = self._chosen_for
        if (obj_id, k) == (was_obj, was_k) and ana is was_ana:
            return  # drawn already: a refresh (every derivation ready, every edit) does not make it again
        self._chosen_for = (obj_id, k, ana)
        if self._chosen_item is not None:
            self.pane.removeItem(self._chosen_item)
            self._chosen_item = None
        if ana is None:
            return
        from OpenGL import GL

        seg = ana.segmentation
        members = seg.members[seg.member_ptr[k] : seg.member_ptr[k + 1]]
        colours = np.tile(gl_mesh.rgba8(self.CHOSEN_COLOUR), (members.size, 1))
        item = ready_mesh_item(gl_mesh.surfel_arrays(seg.voxel[members], seg.direction[members], colours))
        # Its surfels are the segment's own, drawn already: over them without the depth test (no z-fight),
        # as the differing voxels are in the discrete view; not culled either, so a segment on the far side
        # shows through the solid: the user sees where the chosen row is, whichever way the camera looks.
        item.setGLOptions({GL.GL_DEPTH_TEST: False, GL.GL_BLEND: False, GL.GL_CULL_FACE: False})
        item.setDepthValue(20)
        self.pane.addItem(item)
        self._chosen_item = item

    def drawing_data(self, obj: DocObject) -> dict[str, Any] | None:
        if obj.kind == "labels":
            return None
        ana = self.scene.get(obj.id, "analytical")
        region = self.scene.get(obj.id, "region")
        vs = self.scene.get(obj.id, "discrete")
        if ana is None or region is None or vs is None:
            return None
        seg = ana.segmentation
        n = int(seg.segment_of.size)
        budget = self.object_budget()

        def compute() -> dict[str, Any]:
            # the surfels' neighbours, numbered over all surfaces in the segmentation's order
            offsets = np.cumsum([0, *[len(s) for s in region.surfaces]])
            neighbours = (
                np.concatenate([s.neighbours + o for s, o in zip(region.surfaces, offsets[:-1], strict=True)])
                if region.surfaces
                else None
            )
            index = gl_mesh.segment_colour_indices(seg.segment_of, neighbours)
            colours = gl_mesh.palette_rgba8(index[seg.segment_of], gl_mesh.SEGMENT_COLOURS_3D)
            if n <= budget:
                data = gl_mesh.surfel_arrays(seg.voxel, seg.direction, colours)
                data["factor"] = 1
                data["lines"] = gl_mesh.segment_normals(seg)
                return data
            from mrm.geometry.topology.level_of_detail import boundary_surfels, coarse_level

            factor, pooled = coarse_level(vs.mask, budget, n)
            voxels, dirs = boundary_surfels(pooled)
            fine = (np.asarray(seg.voxel, np.int64) - np.asarray(vs.origin, np.int64)) // factor
            coarse = gl_mesh.colours_by_block(fine, seg.direction, colours, voxels, dirs, pooled.shape)
            data = gl_mesh.surfel_arrays(voxels, dirs, coarse, *_placement(vs, factor))
            data["factor"] = factor
            data["lines"] = gl_mesh.segment_normals(seg)
            return data

        what = self.budgeted(obj.id, "segments", budget)
        return self.prepared(obj.id, what, ana, self.surfel_work(n, budget, vs), compute)


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
        colour = gl_mesh.rgba8(obj.style.fill)
        budget = 2 * self.object_budget()  # triangles: a surfel is two

        def compute() -> dict[str, Any]:
            from mrm.geometry.topology.level_of_detail import coarse_mesh

            cell, vertices, triangles, kept = coarse_mesh(poly.vertices, poly.triangles, budget)
            faces = np.asarray(poly.face_of_triangle)[kept]
            data = gl_mesh.triangle_arrays(vertices, triangles, np.tile(colour, (len(triangles), 1)))
            # a face's outline is drawn at full detail only: clustered, faces break into slivers whose
            # outlines would cover the solid (and cost a wide-line pass over every edge per frame)
            data["lines"] = gl_mesh.face_edges(vertices, triangles, faces) if cell == 0 else None
            data["factor"] = math.ceil(cell) if cell > 0 else 1
            return data

        what = self.budgeted(obj.id, "polyhedron", budget)
        return self.prepared(obj.id, what, poly, int(poly.n_triangles), compute)

    NOTE_TEXT = "R is the safety net (not compact)"

    def object_note(self, obj: DocObject) -> str | None:
        # R(A) of a voxel object that is the safety net (V(A) eroded by ¼): it meets the contract, but its
        # faces are the voxels' squares; the user should know why the polyhedron looks like its voxels.
        return self.scene.r_note(obj.id) if obj.kind == "discrete" else None

    def level_note(self, factor: int) -> tuple[str, str]:
        return (
            f"coarser level: vertices merged in cubes of side {factor}",
            f"A polyhedron has more than its share of {2 * self.SURFEL_BUDGET:,} triangles: its vertices in "
            f"each cube of side {factor} are drawn as one.",
        )


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
        # The first time something is drawn (and after File ▸ Open), frame it; while objects are still being
        # computed, frame again as each is drawn (a big result drawn last would otherwise fill the panes).
        if not self._fitted and self.bounds() is not None:
            self.fit()
            self._fitted = self.is_drawn()

    def bounds(self) -> Box3 | None:
        """The box holding what the four views draw."""
        return joint_box3(v.bounds() for v in self.views)

    def fit(self) -> None:
        """Frame every drawn 3D object in the four views."""
        self.camera.fit(self.bounds())

    def is_drawn(self) -> bool:
        """True when the four views have drawn everything (always, without OpenGL)."""
        return all(v.is_drawn() for v in self.views)

    def show_difference(self, data: dict[str, Any] | None) -> None:
        """Draw a 3D account's differing voxels in the discrete 3D view (None clears them)."""
        for v in self.views:
            if isinstance(v, DiscreteView3D):
                v.show_difference(data)

    def by_name(self, name: str) -> View3D:
        for v in self.views:
            if v.name == name:
                return v
        raise KeyError(name)
