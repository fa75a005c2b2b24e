"""The status bar: cursor position (plane and pixel), the selected object's figures, progress with Cancel."""

from __future__ import annotations

import math
from typing import Any

from PySide6 import QtCore, QtGui, QtWidgets

from mrm.views.elided_label import ElidedLabel
from mrm.views.geometry_edit import pixel_at, vertex_count
from mrm.views.scene import Scene, pixel_count

#: A count the user cancelled (shown "not computed", never "…" as if it were on its way).
CANCELLED = object()


def _fmt(v: float) -> str:
    return f"{v:.2f}".replace("-", "−")


def _int(v: int) -> str:
    return f"{v:,}".replace(",", "\u2009").replace("-", "−")


def progress_text(label: str, message: str) -> str:
    """What the status bar says of a running task: its label, and what it does now when that adds to it."""
    if not message:
        return label
    if not label or message.startswith(label):
        return message
    return f"{label}: {message}"


class StatusBar(QtWidgets.QStatusBar):
    """Three areas that never overlap: a hint on the left, a task's progress, the permanent fields.

    The hint is the status bar's message (:meth:`showMessage`, a menu's status tip), drawn in its own widget
    and elided at the progress and the figures instead of running into them; a running task's progress text
    has room before the hint (ADR 0042).
    """

    cancelRequested = QtCore.Signal()

    def __init__(self, scene: Scene, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("statusBar")
        self.scene = scene
        self.hint = ElidedLabel(self)
        self.hint.setObjectName("statusHint")
        self.hint.setSizePolicy(QtWidgets.QSizePolicy.Policy.Ignored, QtWidgets.QSizePolicy.Policy.Preferred)
        self.messageChanged.connect(self.hint.setText)
        self.hint.setMinimumWidth(self.HINT_WIDTH)
        # The figures shrink too (elided; a long object name made them push the window wider).
        self.figures = ElidedLabel(self, least=120)
        self.figures.setObjectName("figuresLabel")
        self.cursor_label = QtWidgets.QLabel("", self)
        self.cursor_label.setObjectName("cursorLabel")
        self.cursor_label.setMinimumWidth(
            self.fontMetrics().horizontalAdvance("x −00000.00  y −00000.00 · pixel (−00000, −00000)")
        )
        self.model_label = QtWidgets.QLabel("", self)
        self.model_label.setObjectName("modelLabel")
        self.progress_box = QtWidgets.QWidget(self)
        pl = QtWidgets.QHBoxLayout(self.progress_box)
        pl.setContentsMargins(0, 0, 0, 0)
        pl.setSpacing(4)
        # A task's text ("Discrete smooth scaling DSS_α: continuing R(A)") gets its width before the hint
        # does, up to a cap: a longer one is elided, never allowed to widen the window while it shows.
        self.progress_label = ElidedLabel(self.progress_box, least=100, most=460)
        self.progress_label.setObjectName("progressText")
        self.progress = QtWidgets.QProgressBar(self.progress_box)
        self.progress.setObjectName("taskProgress")
        self.progress.setRange(0, 1000)
        self.progress.setMaximumWidth(120)
        self.progress.setTextVisible(False)
        self.cancel_button = QtWidgets.QPushButton("Cancel", self.progress_box)
        self.cancel_button.setObjectName("cancelTask")
        self.cancel_button.clicked.connect(self.cancelRequested)
        pl.addWidget(self.progress_label, 1)
        pl.addWidget(self.progress)
        pl.addWidget(self.cancel_button)
        self.progress_box.hide()
        # All permanent, so that QStatusBar never hides one for a message: the hint takes the spare width.
        self.addPermanentWidget(self.hint, 1)
        self.addPermanentWidget(self.progress_box)
        self.addPermanentWidget(self.figures)
        self.addPermanentWidget(self.cursor_label)
        self.addPermanentWidget(self.model_label)
        self._vertices: tuple[Any, int] | None = None  # (geometry, its vertex count)
        self._show_timer = QtCore.QTimer(self)
        self._show_timer.setSingleShot(True)
        self._show_timer.setInterval(self.SHOW_AFTER_MS)
        self._show_timer.timeout.connect(lambda: self._show_progress(True))
        self._timer = QtCore.QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self.update_figures)
        scene.documentChanged.connect(lambda _c: self.schedule())
        scene.derivedReady.connect(lambda _i: self.schedule())
        scene.previewChanged.connect(lambda _i: self.schedule())
        self.schedule()

    def schedule(self) -> None:
        self._timer.start()

    # ------------------------------------------------------------------ cursor
    def set_cursor(self, x: float, y: float) -> None:
        if math.isnan(x) or math.isnan(y):
            self.cursor_label.setText("")
            return
        px, py = pixel_at(x, y)
        self.cursor_label.setText(f"x {_fmt(x)}  y {_fmt(y)} · pixel ({_int(px)}, {_int(py)})")

    # ------------------------------------------------------------------ figures
    def figures_of(self, obj_id: int) -> dict[str, Any]:
        """The selected object's counts; None for the ones still being computed."""
        s = self.scene
        out: dict[str, Any] = {
            "pixels": None,
            "components": None,
            "holes": None,
            "segments": None,
            "vertices": None,
        }
        ps = s.get(obj_id, "discrete")
        if ps is not None:
            out["pixels"] = pixel_count(ps)
        region = s.get(obj_id, "region")
        if region is not None:
            out["components"] = region.n_components
            out["holes"] = region.n_holes
        ana = s.get(obj_id, "analytical")
        if ana is not None:
            out["segments"] = segment_count(ana)
        geom = s.get(obj_id, "euclidean")
        if geom is not None:
            # Once per geometry (10⁵ rings take 0.1–0.2 s to count), not at every status update.
            vc = self._vertices
            if vc is None or vc[0] is not geom:
                vc = self._vertices = (geom, vertex_count(geom))
            out["vertices"] = vc[1]
        # A big set is counted with its region (views.scene.pixel_count).
        for key, rep in (("pixels", "region"), ("components", "region"), ("holes", "region"),
                         ("segments", "analytical"), ("vertices", "euclidean")):  # fmt: skip
            if out[key] is None and (s.is_cancelled(obj_id, rep) or s.is_cancelled(obj_id, "discrete")):
                out[key] = CANCELLED
        return out

    def label_map_figures(self, obj_id: int) -> str:
        """A label map's figures (ADR 0033), from what the workers derived: nothing is counted here."""
        s = self.scene
        lm = s.source(obj_id)
        h, w = lm.shape
        out = [f"label map {_int(w)} × {_int(h)}"]
        cells = s.get(obj_id, "region")
        sd = s.get(obj_id, "euclidean")
        out.append(f"{_int(len(sd.parts))} labels" if sd is not None else "… labels")
        out.append(f"{_int(len(cells.one_cells))} 1-cells" if cells is not None else "… 1-cells")
        if sd is not None:
            vc = self._vertices
            if vc is None or vc[0] is not sd:
                vc = self._vertices = (sd, sd.n_vertices)
            out.append(f"{_int(vc[1])} vertices (gauss subdivision)")
        else:
            out.append("… vertices")
        return " · ".join(out)

    def update_figures(self) -> None:
        doc = self.scene.doc
        self.model_label.setText(f"model: {doc.model}")
        obj = self.scene.primary()
        if obj is None:
            n = len(doc)
            self.figures.setText(f"{n} object{'s' if n != 1 else ''}" if n else "")
            return
        if obj.kind == "labels":
            self.figures.set_parts(f"{obj.name}: ", self.label_map_figures(obj.id))
            return
        f = self.figures_of(obj.id)

        def v(key: str, unit: str, plural: str | None = None) -> str:
            val = f[key]
            if val is None:
                return f"… {plural or unit + 's'}"
            if val is CANCELLED:
                return f"{plural or unit + 's'} not computed"
            return f"{_int(val)} {unit if val == 1 else (plural or unit + 's')}"

        self.figures.set_parts(
            f"{obj.name}: ",
            f"{v('pixels', 'pixel')} · {v('components', 'component')} · "
            f"{v('holes', 'hole')} · {v('segments', 'segment')} · {v('vertices', 'vertex', 'vertices')}",
        )

    # ------------------------------------------------------------------ progress
    #: Work shorter than this never shows the progress bar (a derivation of a small object would flicker).
    SHOW_AFTER_MS = 250

    def set_busy(self, busy: bool) -> None:
        if not busy:
            self._show_timer.stop()
            self._show_progress(False)
            return
        if not self.progress_box.isVisible() and not self._show_timer.isActive():
            self.progress.setValue(0)
            self.progress.setRange(0, 0)  # indeterminate until the first report
            self._show_timer.start()

    #: The hint's least width: a tool's hint stays readable on a 1024-pixel window.
    HINT_WIDTH = 100

    def _show_progress(self, on: bool) -> None:
        # While a task runs its text comes first: the hint may shrink to nothing meanwhile.
        self.hint.setMinimumWidth(0 if on else self.HINT_WIDTH)
        self.progress_box.setVisible(on)

    def set_progress(self, label: str, fraction: float, message: str) -> None:
        self.progress.setRange(0, 1000)
        self.progress.setValue(round(1000 * fraction))
        text = progress_text(label, message)
        if text != self.progress_label.text():
            self.progress_label.setText(text)
            self.progress_box.setToolTip(text)
            # The box asks the status bar for the new width itself: a nested label's new size hint does
            # not reach QStatusBar's layout on its own.
            self.progress_box.updateGeometry()

    # ------------------------------------------------------------------ messages
    def show_text(self, text: str, ms: int = 0, *, error: bool = False) -> None:
        """Show ``text`` in the hint area for ``ms`` ms (0: until the next message), red for an error."""
        self.hint.setStyleSheet("color: #c0392b;" if error else "")
        self.showMessage(text, ms)

    def paintEvent(self, ev: QtGui.QPaintEvent) -> None:
        # QStatusBar's own paint draws the message over the area left of the first permanent widget; here
        # the hint widget draws it, elided. The panel and the widgets' frames as Qt draws them.
        # The painter ends with the block (see ElidedLabel.paintEvent: a kept frame crashed the next paint).
        with QtGui.QPainter(self) as p:
            opt = QtWidgets.QStyleOption()
            opt.initFrom(self)
            style = self.style()
            style.drawPrimitive(QtWidgets.QStyle.PrimitiveElement.PE_PanelStatusBar, opt, p, self)
            for w in (self.hint, self.progress_box, self.figures, self.cursor_label, self.model_label):
                if w.isVisible():
                    item = QtWidgets.QStyleOption()
                    item.rect = w.geometry().adjusted(-2, -1, 2, 1)
                    item.palette = self.palette()
                    if ev.rect().intersects(item.rect):
                        style.drawPrimitive(
                            QtWidgets.QStyle.PrimitiveElement.PE_FrameStatusBarItem, item, p, w
                        )


def segment_count(ana: Any) -> int:
    """Number of digital straight segments of an analytical representation (whatever its container)."""
    for attr in ("n_segments", "segment_count"):
        n = getattr(ana, attr, None)
        if n is not None:
            return int(n() if callable(n) else n)
    segs = getattr(ana, "segments", None)
    if segs is not None:
        return len(segs)
    chains = getattr(ana, "chains", ())
    return sum(len(getattr(c, "segments", ())) for c in chains)
