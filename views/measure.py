"""Measuring: the distance between two clicked points, and the exact Hausdorff distance between two objects.

The measure tool (``M``) takes two clicks; the line and its length stay drawn until the next click. Shift
snaps to pixel centres and Ctrl to pixel corners, and then the squared length is exact (a rational shown as
such). The Measure panel computes ``H(A, B)`` between the *Euclidean* representations of two objects — the
filled polygons, a pixel object's continuation R(A) — with the model's exact algorithm
(:func:`mrm.geometry.hausdorff.directed_hausdorff`, both directions) on a worker: it can take seconds, and
Cancel in the status bar stops it.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from PySide6 import QtCore, QtGui, QtWidgets

from mrm.core.errors import MRMError
from mrm.views import geometry_edit as ge
from mrm.views.canvas import PlaneView
from mrm.views.tool_base import Tool, ToolHost, accent_colour, cosmetic_pen, screen_square, snap_mode

log = logging.getLogger(__name__)
Qt = QtCore.Qt


def num_text(v: float) -> str:
    """A coordinate as typed back: the shortest text that reads as the same float (``repr``)."""
    if v == int(v) and abs(v) < 1e15:
        return str(int(v))
    return repr(float(v))


def fraction_text(q: Fraction) -> str:
    """``3`` or ``13/4``."""
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def sqrt_text(sq: Fraction) -> str:
    """``√sq`` exactly: ``5`` for 25, ``5/2`` for 25/4, ``√2`` for 2, ``√13/2`` for 13/4, else ``√(2/3)``."""
    n, d = sq.numerator, sq.denominator
    rn, rd = math.isqrt(n), math.isqrt(d)
    if rn * rn == n and rd * rd == d:
        return fraction_text(Fraction(rn, rd))
    if d == 1:
        return f"√{n}"
    if rd * rd == d:
        return f"√{n}/{rd}"
    return f"√({fraction_text(sq)})"


@dataclass(frozen=True)
class PointMeasure:
    """Two plane points and their distance (``squared`` exact: the floats are dyadic rationals)."""

    a: tuple[float, float]
    b: tuple[float, float]

    @property
    def dx(self) -> float:
        return self.b[0] - self.a[0]

    @property
    def dy(self) -> float:
        return self.b[1] - self.a[1]

    @property
    def squared(self) -> Fraction:
        dx = Fraction(self.b[0]) - Fraction(self.a[0])
        dy = Fraction(self.b[1]) - Fraction(self.a[1])
        return dx * dx + dy * dy

    @property
    def distance(self) -> float:
        return math.hypot(self.dx, self.dy)

    def text(self) -> str:
        sq = self.squared
        exact = sqrt_text(sq) if sq.denominator <= 1 << 16 else ""
        value = f"{self.distance:.6g}"
        shown = f"{exact} ≈ {value}" if exact and exact != value else value
        return (
            f"distance {shown}  (from ({num_text(self.a[0])}, {num_text(self.a[1])}) "
            f"to ({num_text(self.b[0])}, {num_text(self.b[1])}); Δx {self.dx:.6g}, Δy {self.dy:.6g})"
        )


class MeasureTool(Tool):
    """Click a first point, then a second: the distance is drawn and reported (``host.measured``)."""

    name = "measure"
    cursor = Qt.CursorShape.CrossCursor
    hint = (
        "Click two points to measure the distance between them (Shift: snap to pixel centres, Ctrl: to "
        "pixel corners); the Measure panel gives the Hausdorff distance between two objects"
    )
    busy_keys = (Qt.Key.Key_Escape,)

    def __init__(self, host: ToolHost) -> None:
        super().__init__(host)
        self.start: tuple[float, float] | None = None
        self.result: PointMeasure | None = None

    def in_gesture(self) -> bool:
        return self.start is not None

    def cancel(self) -> None:
        if self.start is not None:
            self.start = None
            self.host.overlayChanged.emit()

    def press(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if ev.button() != Qt.MouseButton.LeftButton:
            return False
        p = ge.snap(x, y, snap_mode(ev.modifiers()))
        if self.start is None:
            self.start = p
            self.result = None
            self.host.message.emit("click the second point (Esc cancels)", 0)
        else:
            self.result = PointMeasure(self.start, p)
            self.start = None
            self.host.message.emit(self.result.text(), 0)
            self.host.measured.emit(self.result)
        self.host.overlayChanged.emit()
        return True

    def move(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        self.hover = ge.snap(x, y, snap_mode(ev.modifiers()))
        if self.start is not None:
            self.host.message.emit(PointMeasure(self.start, self.hover).text(), 0)
        return self.start is not None

    def key(self, view: PlaneView, ev: QtGui.QKeyEvent) -> bool:
        if ev.key() == Qt.Key.Key_Escape and self.start is not None:
            self.cancel()
            return True
        return False

    def paint_overlay(self, p: QtGui.QPainter, view: PlaneView) -> None:
        acc = accent_colour(view)
        if self.start is not None and self.hover is not None:
            a, b = self.start, self.hover
        elif self.result is not None:
            a, b = self.result.a, self.result.b
        else:
            return
        p.setPen(cosmetic_pen(acc, 1.6, Qt.PenStyle.DashLine))
        p.drawLine(QtCore.QPointF(*a), QtCore.QPointF(*b))
        p.setPen(cosmetic_pen(acc, 1.0))
        for pt in (a, b):
            screen_square(p, pt[0], pt[1], 7, QtGui.QColor("#ffffff"))
        # The length beside the line's middle, in screen space (the painter maps plane → screen).
        m = p.transform().map(QtCore.QPointF((a[0] + b[0]) / 2, (a[1] + b[1]) / 2))
        label = f"{PointMeasure(a, b).distance:.4g}"
        p.save()
        p.resetTransform()
        p.setPen(QtGui.QPen(acc))
        p.drawText(m + QtCore.QPointF(6, -6), label)
        p.restore()


# ---------------------------------------------------------------------------------------------- Hausdorff
@dataclass(frozen=True)
class HausdorffResult:
    """Both directed distances between the Euclidean representations of objects A and B."""

    a_name: str
    b_name: str
    ab: Any  # HausdorffDistance h(A, B)
    ba: Any  # HausdorffDistance h(B, A)

    @property
    def full(self) -> Any:
        """H(A, B) = max(h(A, B), h(B, A)), decided exactly."""
        return self.ab if _exact_cmp(self.ab, self.ba) >= 0 else self.ba

    def text(self) -> str:
        return (
            f"H({self.a_name}, {self.b_name}) = {distance_text(self.full)}<br>"
            f"<small>h(A, B) = {distance_text(self.ab)} · h(B, A) = {distance_text(self.ba)}</small>"
        )


def _exact_cmp(x: Any, y: Any) -> int:
    """Sign of x − y for two exact distances (rational enclosures 2⁻²⁰⁰ wide decide every real case)."""
    if x.is_infinite or y.is_infinite:
        return int(x.is_infinite) - int(y.is_infinite)
    xl, xh = x.squared_enclosure()
    yl, yh = y.squared_enclosure()
    if xh < yl:
        return -1
    if xl > yh:
        return 1
    if xl == xh and yl == yh:
        return (xl > yl) - (xl < yl)
    return 0  # equal to within 2⁻²⁰⁰: either one is H


def distance_text(d: Any) -> str:
    """An exact distance: ``√(25/4) = 2.5``, ``√2 ≈ 1.4142135623730951``, with its witness point."""
    if d.is_infinite:
        return "∞ (one of them is empty)"
    sq = d.squared
    value = repr(d.value)
    if sq is None:
        shown = f"{value} (irrational; exact comparison kept)"
    elif sq == 0:
        return "0"
    else:
        ex = sqrt_text(sq)
        shown = f"{ex} = {value}" if not ex.startswith("√") else f"{ex} ≈ {value}"
        shown += f" (d² = {fraction_text(sq)})"
    if d.witness is not None:
        shown += f", reached at ({d.witness[0]:.6g}, {d.witness[1]:.6g})"
    return shown


class MeasurePanel(QtWidgets.QWidget):
    """The Measure dock: the last two-point measure, and the Hausdorff distance between two objects."""

    computed = QtCore.Signal(object)  # HausdorffResult
    stale = QtCore.Signal()  # the measured objects changed: the result no longer holds

    def __init__(self, scene: Any, runner: Any, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("measurePanel")
        self.scene = scene
        self.runner = runner
        self.result: HausdorffResult | None = None
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(6, 6, 6, 6)
        head = QtWidgets.QLabel("<b>Distance</b> — the measure tool (M): click two points.", self)
        head.setWordWrap(True)
        lay.addWidget(head)
        self.points_label = QtWidgets.QLabel("no measure yet", self)
        self.points_label.setObjectName("pointMeasure")
        self.points_label.setWordWrap(True)
        self.points_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        lay.addWidget(self.points_label)
        lay.addSpacing(8)
        head2 = QtWidgets.QLabel(
            "<b>Hausdorff distance</b> between the Euclidean representations (filled polygons; a pixel "
            "object's continuation R), computed exactly.",
            self,
        )
        head2.setWordWrap(True)
        lay.addWidget(head2)
        form = QtWidgets.QFormLayout()
        self.a_combo = QtWidgets.QComboBox(self)
        self.a_combo.setObjectName("measureA")
        self.b_combo = QtWidgets.QComboBox(self)
        self.b_combo.setObjectName("measureB")
        for cb in (self.a_combo, self.b_combo):
            cb.setSizeAdjustPolicy(QtWidgets.QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
            cb.setMinimumContentsLength(8)
        form.addRow("A", self.a_combo)
        form.addRow("B", self.b_combo)
        lay.addLayout(form)
        row = QtWidgets.QHBoxLayout()
        self.compute_button = QtWidgets.QPushButton("Compute", self)
        self.compute_button.setObjectName("computeHausdorff")
        self.compute_button.clicked.connect(self.compute)
        self.cancel_button = QtWidgets.QPushButton("Cancel", self)
        self.cancel_button.setObjectName("cancelHausdorff")
        self.cancel_button.setEnabled(False)
        self.cancel_button.clicked.connect(self.cancel)
        row.addStretch(1)
        row.addWidget(self.cancel_button)
        row.addWidget(self.compute_button)
        lay.addLayout(row)
        self.result_label = QtWidgets.QLabel("", self)
        self.result_label.setObjectName("hausdorffResult")
        self.result_label.setWordWrap(True)
        self.result_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        lay.addWidget(self.result_label)
        lay.addStretch(1)
        scene.documentChanged.connect(self._doc_changed)
        self._fill()

    # ------------------------------------------------------------------ inputs
    def _fill(self) -> None:
        doc = self.scene.doc
        sel = [i for i in doc.selection if i in doc]
        for k, cb in enumerate((self.a_combo, self.b_combo)):
            current = cb.currentData()
            cb.blockSignals(True)
            cb.clear()
            for o in reversed(doc.plane_objects):
                cb.addItem(o.name, o.id)
            want = current if current in doc else (sel[k] if k < len(sel) else None)
            i = cb.findData(want)
            cb.setCurrentIndex(i if i >= 0 else (min(k, cb.count() - 1) if cb.count() else -1))
            cb.blockSignals(False)

    def _doc_changed(self, ch: Any) -> None:
        if ch.inserted or ch.removed or ch.reset or any("name" in w for w in ch.changed.values()):
            self._fill()
        if self.result is not None and (ch.changed or ch.removed or ch.reset or ch.settings):
            ids = {self.a_combo.currentData(), self.b_combo.currentData()}
            reshaped = {i for i, what in ch.changed.items() if "source" in what}
            if ch.reset or ch.settings or ids & (reshaped | set(ch.removed)):
                self.result_label.setText("<i>(an object changed since: compute again)</i>")
                self.result = None
                self.stale.emit()

    def set_objects(self, a: int, b: int) -> None:
        """Measure between objects ``a`` and ``b`` (ids)."""
        self.a_combo.setCurrentIndex(self.a_combo.findData(a))
        self.b_combo.setCurrentIndex(self.b_combo.findData(b))

    def show_points(self, m: PointMeasure) -> None:
        self.points_label.setText(m.text())

    # ------------------------------------------------------------------ computing
    def compute(self) -> None:
        self.stale.emit()  # the former result's marks go at once
        doc = self.scene.doc
        a, b = self.a_combo.currentData(), self.b_combo.currentData()
        if a is None or b is None or a not in doc or b not in doc:
            self.result_label.setText("choose two objects")
            return
        oa, ob = doc.get(a), doc.get(b)
        maps = [o.name for o in (oa, ob) if o.kind == "labels"]
        if maps:  # ADR 0033: a subdivision is many polygons, the distance is between two shapes
            self.result_label.setText(
                f"{maps[0]} is a label map: the Hausdorff distance is measured between two shapes; "
                "Edit ▸ Split into Objects gives one per label"
            )
            return
        # The derived entries are pinned to the objects' current sources: safe to read on a worker.
        ea, eb = doc.derived(a), doc.derived(b)
        self.result_label.setText(f"computing H({oa.name}, {ob.name})…")
        self.compute_button.setEnabled(False)
        self.cancel_button.setEnabled(True)

        def work(progress: Any) -> HausdorffResult:
            from mrm.geometry.hausdorff import directed_hausdorff

            ga, gb = ea.get("euclidean"), eb.get("euclidean")
            progress.update(0.0, f"h({oa.name}, {ob.name})")
            ab = directed_hausdorff(ga, gb, progress=progress)
            progress.update(0.5, f"h({ob.name}, {oa.name})")
            ba = directed_hausdorff(gb, ga, progress=progress)
            return HausdorffResult(oa.name, ob.name, ab, ba)

        def done(r: HausdorffResult) -> None:
            self._finished()
            self.result = r
            self.result_label.setText(r.text())
            self.computed.emit(r)

        def failed(exc: BaseException) -> None:
            self._finished()
            if not isinstance(exc, MRMError):
                raise exc
            self.result_label.setText(f"<span style='color:#c0392b'>{exc}</span>")

        def cancelled() -> None:
            self._finished()
            self.result_label.setText("cancelled")

        self.runner.submit(
            "measure",
            work,
            on_result=done,
            on_error=failed,
            on_cancel=cancelled,
            label=f"Hausdorff distance {oa.name} – {ob.name}",
            show_progress=True,
        )

    def _finished(self) -> None:
        self.compute_button.setEnabled(True)
        self.cancel_button.setEnabled(False)

    def cancel(self) -> None:
        self.runner.cancel("measure")

    def is_running(self) -> bool:
        return bool(self.runner.is_busy("measure"))
