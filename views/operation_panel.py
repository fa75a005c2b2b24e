"""Operation panels generated from the operations' parameter specs.

Pick the operation and its inputs, set the parameters with sliders and fields; while a slider moves the
result is previewed in every view (a new request cancels the one still running). Apply runs the operation
with progress and Cancel in the status bar — never on the GUI thread — and adds the results as new objects,
one undo step, each remembering its provenance (operation, parameters, inputs).
"""

from __future__ import annotations

import html
import logging
import math
import time
from collections.abc import Callable
from fractions import Fraction
from typing import Any

from PySide6 import QtCore, QtWidgets

from mrm.core.errors import MRMError, SizeLimitError
from mrm.core.numbers import spell
from mrm.document.apply import held_euclidean
from mrm.document.commands import ApplyResults
from mrm.ops.registry import THREE_D
from mrm.views.failures import failure_message, log_failure
from mrm.views.op_adapter import OpInfo, ParamInfo, operations
from mrm.views.scene import Scene

log = logging.getLogger(__name__)

SLIDER_STEPS = 1000


def readable_name(name: str) -> str:
    """A result's name for people: co-refinement parts as A ∖ B, A ∩ B, B ∖ A instead of identifiers."""
    from mrm.ops.boolean import PART_TITLES

    for key, title in PART_TITLES.items():
        name = name.replace(key, title)
    return name.replace("_", " ")


def unique_name(name: str, taken: set[str]) -> str:
    """``name``, or ``name (2)``, ``name (3)``… : the first not in ``taken``."""
    if name not in taken:
        return name
    k = 2
    while f"{name} ({k})" in taken:
        k += 1
    return f"{name} ({k})"


def size_limit_text(exc: SizeLimitError, setting: str | None = None) -> str:
    """The message of a result refused for its size, from the error's fields.

    ``setting`` says where the user raises the limit (the window passes the preference's place, e.g.
    "File ▸ Preferences ▸ General ▸ Largest operation result"). At the document's own limit no preference
    goes higher (ADR 0010): the message then says so instead of pointing at a setting that cannot help.
    """
    from mrm.core.limits import MAX_OBJECT_PIXELS

    head = f"{exc.what} would cover {exc.estimated:,} pixels, more than the limit of {exc.limit:,}"
    if exc.limit >= MAX_OBJECT_PIXELS:
        return f"{head}, the largest pixel object a document holds; reduce the scale"
    where = f" in {setting}" if setting else ""
    return f"{head}; reduce the scale or raise the limit{where}"


def _is_empty(source: Any) -> bool:
    empty = getattr(source, "is_empty", False)
    return bool(empty() if callable(empty) else empty)


def range_text(spec: Any) -> str:
    """The allowed values of a number parameter in interval notation: ``(0, ∞)``, ``[0, 1]``, any number."""
    lo, hi = getattr(spec, "minimum", None), getattr(spec, "maximum", None)
    if lo is None and hi is None:
        return "any number"
    left = "(−∞" if lo is None else ("[" if spec.min_inclusive else "(") + _num_text(float(lo))
    right = "∞)" if hi is None else _num_text(float(hi)) + ("]" if spec.max_inclusive else ")")
    return f"{left}, {right}"


def _num_text(v: float) -> str:
    return f"{v:g}".replace("-", "−")


class NumberField(QtWidgets.QLineEdit):
    """A number typed as text, read exactly by its parameter's declaration and never rewritten.

    The text is read when it is committed (Enter or leaving the field) by :meth:`ParamSpec.read`, the one
    reading every path shares: ``0.2`` is 1/5, ``1/3`` a third, ``−2,5°`` is −5/2. An invalid entry stays as
    typed, marked red with the declaration's reason; the panel refuses to preview or apply until it is
    corrected.
    """

    #: The exact value after a commit (a Fraction or an int), or None when the text is invalid or empty.
    valueChanged = QtCore.Signal(object)
    #: The text was committed: (valid, message).
    validated = QtCore.Signal(bool, str)

    def __init__(self, info: ParamInfo, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.info = info
        self._value: Fraction | int | None = None
        self.error = ""
        self.setObjectName(f"field_{info.name}")
        self.setPlaceholderText("default" if info.optional else "")
        self.editingFinished.connect(self._commit)
        self.setToolTip(f"{info.label}: {range_text(info.spec)}")

    def suffix(self) -> str:
        return f" {self.info.unit}" if self.info.unit else ""

    def value(self) -> Fraction | int | None:
        return self._value

    def is_valid(self) -> bool:
        return not self.error

    def setValue(self, v: object) -> None:
        """Show ``v`` (read exactly: a float is the decimal it prints as) as the field's exact value."""
        self._value = None if v is None else self.info.spec.read(v)
        self.setText("" if self._value is None else spell(Fraction(self._value)))
        self._mark("")

    def _mark(self, error: str) -> None:
        self.error = error
        self.setProperty("invalid", bool(error))
        self.setStyleSheet("QLineEdit { border: 2px solid #c0392b; }" if error else "")
        self.setToolTip(error or f"{self.info.label}: {range_text(self.info.spec)}")

    def _commit(self) -> None:
        text = self.text()
        if not text.strip() and self.info.optional:
            changed = self._value is not None or bool(self.error)
            self._value = None
            self._mark("")
            if changed:
                self.validated.emit(True, "")
                self.valueChanged.emit(None)
            return
        try:
            v = self.info.spec.read(text)
        except MRMError as e:
            message = str(e).replace("parameter ", "", 1)
            if "allowed" not in message:  # say what is allowed, not only what is wrong
                message += f" (allowed: {range_text(self.info.spec)})"
            self._mark(message)
            self.validated.emit(False, self.error)
            self.valueChanged.emit(None)
            return
        was_error = bool(self.error)
        self._mark("")
        if v != self._value or was_error:
            self._value = v
            self.validated.emit(True, "")
            self.valueChanged.emit(v)


class ParamControl(QtWidgets.QWidget):
    """The control of one parameter: a slider with a field for numbers, a box, a choice, a point."""

    changed = QtCore.Signal()
    #: The slider is being dragged (True) or was released (False).
    dragging = QtCore.Signal(bool)
    #: A point parameter's Pick button: the next click in a view gives the point.
    pickRequested = QtCore.Signal()

    def __init__(self, info: ParamInfo, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.info = info
        self.setObjectName(f"param_{info.name}")
        lay = QtWidgets.QHBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        self.slider: QtWidgets.QSlider | None = None
        self.field: Any = None
        tip = info.help + (f" ({info.unit})" if info.unit else "")
        self.setToolTip(tip)
        k = info.kind
        if k in ("number", "int"):
            lo = info.minimum if info.minimum is not None else (0.0 if k == "int" else -1000.0)
            hi = info.maximum if info.maximum is not None else (lo + 100.0)
            self._lo, self._hi = float(lo), float(hi)
            self._log = info.log or (self._lo > 0 and self._hi / self._lo >= 100)
            f = NumberField(info, self)
            self.field = f
            # The allowed range and the unit, always in sight (the slider spans only a useful part of it).
            self.range_label = QtWidgets.QLabel(
                (f"{info.unit} " if info.unit else "") + range_text(info.spec), self
            )
            self.range_label.setObjectName(f"range_{info.name}")
            self.range_label.setStyleSheet("color: palette(placeholder-text);")
            self.range_label.setWordWrap(True)  # a narrow panel wraps the range instead of scrolling
            s = QtWidgets.QSlider(QtCore.Qt.Orientation.Horizontal, self)
            s.setObjectName(f"slider_{info.name}")
            s.setRange(0, SLIDER_STEPS)
            s.setMinimumWidth(40)
            f.setMinimumWidth(48)
            self.slider = s
            lay.addWidget(s, 3)
            lay.addWidget(f, 2)
            lay.addWidget(self.range_label)
            s.valueChanged.connect(self._slider_moved)
            s.sliderPressed.connect(lambda: self.dragging.emit(True))
            s.sliderReleased.connect(lambda: self.dragging.emit(False))
            f.valueChanged.connect(self._field_changed)
        elif k == "bool":
            self.field = QtWidgets.QCheckBox(self)
            self.field.toggled.connect(lambda _v: self.changed.emit())
            lay.addWidget(self.field)
        elif k in ("choice", "model"):
            self.field = QtWidgets.QComboBox(self)
            for c in info.choices:
                self.field.addItem(str(c), c)
            self.field.currentIndexChanged.connect(lambda _i: self.changed.emit())
            lay.addWidget(self.field)
        elif k == "point":
            self.xs = QtWidgets.QDoubleSpinBox(self)
            self.ys = QtWidgets.QDoubleSpinBox(self)
            self.zs = QtWidgets.QDoubleSpinBox(self)  # shown for a 3D point (set_dimension)
            for w, label in ((self.xs, "x "), (self.ys, "y "), (self.zs, "z ")):
                w.setObjectName(f"{info.name}_{label.strip()}")
                w.setRange(-1e9, 1e9)
                w.setDecimals(4)
                w.setPrefix(label)
                w.setKeyboardTracking(False)
                # Narrow enough for a side panel at 1024 px: the spin boxes shrink, the text scrolls.
                w.setMinimumWidth(60)
                w.setSizePolicy(QtWidgets.QSizePolicy.Policy.Ignored, QtWidgets.QSizePolicy.Policy.Fixed)
                w.valueChanged.connect(lambda _v: self.changed.emit())
                lay.addWidget(w, 1)
            self.pick_button = QtWidgets.QToolButton(self)
            self.pick_button.setObjectName(f"pick_{info.name}")
            self.pick_button.setText("Pick")
            self.pick_button.setToolTip(
                f"Pick the {info.label.lower()} by clicking in a view (Ctrl+Shift+C); Shift snaps to a "
                "pixel centre, Ctrl to a corner"
            )
            self.pick_button.clicked.connect(self.pickRequested.emit)
            lay.addWidget(self.pick_button)
            self.zs.setVisible(info.spec.dimension == 3)
        else:
            self.field = QtWidgets.QLineEdit(self)
            self.field.editingFinished.connect(self.changed.emit)
            lay.addWidget(self.field)
        self._syncing = False
        self.set_value(info.default)

    def set_dimension(self, n: int) -> None:
        """Show the z coordinate of a point for 3D inputs (a centre takes the inputs' dimension)."""
        if self.info.kind == "point" and self.info.spec.dimension == 0:
            self.zs.setHidden(n != 3)
            self.pick_button.setHidden(n == 3)  # picking is a click in a plane view

    # ------------------------------------------------------------------ slider ↔ field
    def _to_slider(self, v: float) -> int:
        lo, hi = self._lo, self._hi
        if hi <= lo:
            return 0
        if self._log:
            t = (math.log(max(v, lo)) - math.log(lo)) / (math.log(hi) - math.log(lo))
        else:
            t = (v - lo) / (hi - lo)
        return round(min(1.0, max(0.0, t)) * SLIDER_STEPS)

    def _from_slider(self, i: int) -> float:
        t = i / SLIDER_STEPS
        lo, hi = self._lo, self._hi
        v = math.exp(math.log(lo) + t * (math.log(hi) - math.log(lo))) if self._log else lo + t * (hi - lo)
        # Round to a readable value: the parameter becomes exactly what the field shows.
        digits = max(0, 3 - math.floor(math.log10(abs(v)))) if v else 0
        return round(v, digits) if self.info.kind == "number" else float(round(v))

    def _slider_moved(self, i: int) -> None:
        if self._syncing:
            return
        self._syncing = True
        try:
            self.field.setValue(self._from_slider(i))
        finally:
            self._syncing = False
        self.changed.emit()

    def is_valid(self) -> bool:
        return not isinstance(self.field, NumberField) or self.field.is_valid()

    def error(self) -> str:
        return self.field.error if isinstance(self.field, NumberField) else ""

    def _field_changed(self, v: object) -> None:
        if self._syncing:
            return
        self._syncing = True
        try:
            if self.slider is not None and v is not None:
                self.slider.setValue(self._to_slider(float(v)))  # type: ignore[arg-type]
        finally:
            self._syncing = False
        self.changed.emit()

    # ------------------------------------------------------------------ value
    def value(self) -> Any:
        k = self.info.kind
        if k in ("number", "int"):
            return self.field.value()  # exact: read once, when the text was committed
        if k == "bool":
            return bool(self.field.isChecked())
        if k in ("choice", "model"):
            return self.field.currentData()
        if k == "point":
            p: tuple[float, ...] = (float(self.xs.value()), float(self.ys.value()))
            if not self.zs.isHidden():
                p = (*p, float(self.zs.value()))
            # An optional centre left at the origin is "no centre" (the origin), as the model's default says.
            return None if self.info.optional and self.info.default is None and not any(p) else p
        return self.field.text()

    def set_value(self, v: Any) -> None:
        k = self.info.kind
        self._syncing = True
        try:
            if k == "number" and v is None and self.info.optional:
                self.field.setValue(None)
                if self.slider is not None:
                    self.slider.setValue(0)
            elif k in ("number", "int") and v is not None:
                self.field.setValue(v)
                if self.slider is not None:
                    self.slider.setValue(self._to_slider(float(v)))
            elif k == "bool":
                self.field.setChecked(bool(v))
            elif k in ("choice", "model"):
                i = self.field.findData(v)
                self.field.setCurrentIndex(max(0, i))
            elif k == "point":
                x, y, *z = v if v is not None else (0.0, 0.0, 0.0)
                self.xs.setValue(float(x))
                self.ys.setValue(float(y))
                self.zs.setValue(float(z[0]) if z else 0.0)
            elif k == "text":
                self.field.setText("" if v is None else str(v))
        finally:
            self._syncing = False


def _narrow(combo: QtWidgets.QComboBox) -> None:
    """A combo box that may be narrower than its longest item (it elides; the popup shows them whole)."""
    combo.setSizeAdjustPolicy(QtWidgets.QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
    combo.setMinimumContentsLength(8)


class OperationPanel(QtWidgets.QWidget):
    """The Operations dock."""

    applied = QtCore.Signal(list)  # ids of the new objects
    previewed = QtCore.Signal()
    #: The Pick button of a point parameter (its name) was pressed: the window lets a view click set it.
    pickRequested = QtCore.Signal(str)

    def __init__(
        self,
        scene: Scene,
        runner: Any,
        parent: QtWidgets.QWidget | None = None,
        *,
        plan_job: Callable[..., Any],
        pixel_limit_setting: str | None = None,
    ) -> None:
        """The panel of ``scene``'s document.

        ``plan_job(inputs, op_name, params, limit, held, compact_limit, progress)`` plans an operation (the
        document's compact limit for every R of a voxel set): a module-level
        function that ``runner.call`` may send to a worker process. ``pixel_limit_setting`` names where the
        user raises the pixel limit. The window passes both, so that this view needs nothing of app/.
        """
        super().__init__(parent)
        self.setObjectName("operationPanel")
        self.scene = scene
        self.runner = runner
        self.plan_job = plan_job
        self.pixel_limit_setting = pixel_limit_setting
        self.ops = operations()
        self.op: OpInfo | None = None
        self._cancel_requested = False
        self._project = 0  # counts the document's resets: an outcome of an earlier project is not shown
        self.controls: list[ParamControl] = []
        self.inputs: list[QtWidgets.QComboBox] = []
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(6, 6, 6, 6)
        self.combo = QtWidgets.QComboBox(self)
        self.combo.setObjectName("operationCombo")
        _narrow(self.combo)
        for op in self.ops:
            self.combo.addItem(op.title, op.name)
        lay.addWidget(self.combo)
        self.help = QtWidgets.QLabel("", self)
        self.help.setWordWrap(True)
        self.help.setObjectName("operationHelp")
        lay.addWidget(self.help)
        self.form_box = QtWidgets.QWidget(self)
        self.form = QtWidgets.QFormLayout(self.form_box)
        self.form.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(self.form_box)
        self.live = QtWidgets.QCheckBox("Live preview", self)
        self.live.setObjectName("livePreview")
        self._prefs = getattr(parent, "prefs", None)
        self.live.setChecked(bool(self._prefs.live_preview) if self._prefs is not None else False)
        self.live.setToolTip(
            "Show the result of the current input and parameters as a grey ghost in the discrete and "
            "Euclidean views (not an object: not listed, not saved, not counted by Fit All)"
        )
        self.live.toggled.connect(self._live_toggled)
        self._paused = False  # after Apply: no preview until the user changes the input or a parameter
        lay.addWidget(self.live)
        row = QtWidgets.QHBoxLayout()
        self.apply_button = QtWidgets.QPushButton("Apply", self)
        self.apply_button.setObjectName("applyOperation")
        self.apply_button.setDefault(True)
        self.apply_button.clicked.connect(self.apply)
        self.cancel_button = QtWidgets.QPushButton("Cancel", self)
        self.cancel_button.setObjectName("cancelOperation")
        self.cancel_button.clicked.connect(self.cancel)
        self.cancel_button.setEnabled(False)
        row.addStretch(1)
        row.addWidget(self.cancel_button)
        row.addWidget(self.apply_button)
        lay.addLayout(row)
        self.status = QtWidgets.QLabel("", self)
        self.status.setObjectName("operationStatus")
        self.status.setWordWrap(True)
        lay.addWidget(self.status)
        lay.addStretch(1)
        self._preview_timer = QtCore.QTimer(self)
        self._preview_timer.setSingleShot(True)
        self._preview_timer.setInterval(30)
        self._preview_timer.timeout.connect(self._run_preview)
        self.combo.currentIndexChanged.connect(self._op_changed)
        scene.documentChanged.connect(self._doc_changed)
        if not self.ops:
            self.combo.hide()
            self.live.hide()
            self.apply_button.setEnabled(False)
            self.help.setText("No operations are available in this build (mrm.ops is missing).")
        else:
            self._op_changed(0)

    # ------------------------------------------------------------------ building
    def fill_menu(self, menu: QtWidgets.QMenu) -> None:
        if self.ops:
            menu.addSeparator()
        for k, op in enumerate(self.ops):
            act = menu.addAction(f"{op.title}…")
            act.setObjectName(f"op.{op.name}")
            act.triggered.connect(lambda _c=False, i=k: self.choose(i))

    def choose(self, index: int) -> None:
        self.combo.setCurrentIndex(index)
        w = self.window()
        if hasattr(w, "show_operations"):
            w.show_operations()

    def select_operation(self, name: str) -> None:
        i = self.combo.findData(name)
        if i < 0:
            raise KeyError(f"no operation {name!r}; have {[o.name for o in self.ops]}")
        self.combo.setCurrentIndex(i)

    def _op_changed(self, index: int) -> None:
        self.clear_preview()
        self.op = self.ops[index] if 0 <= index < len(self.ops) else None
        while self.form.rowCount():
            self.form.removeRow(0)
        self.controls = []
        self.inputs = []
        if self.op is None:
            return
        self.help.setText(self.op.help.strip().split("\n\n")[0])
        for k in range(self.op.arity):
            cb = QtWidgets.QComboBox(self.form_box)
            cb.setObjectName(f"input_{k}")
            _narrow(cb)
            cb.activated.connect(lambda _i: self.user_edited())
            cb.currentIndexChanged.connect(lambda _i: self._follow_dimension())
            cb.currentIndexChanged.connect(lambda _i: self.request_preview())
            self.inputs.append(cb)
            self.form.addRow("Input" if self.op.arity == 1 else f"Input {'AB'[k] if k < 2 else k + 1}", cb)
        for p in self.op.params:
            c = ParamControl(p, self.form_box)
            if p.name == "model" and self.scene.doc.model in p.choices:
                # Results keep D(Euclidean) = discrete under the document's model.
                c.set_value(self.scene.doc.model)
            c.changed.connect(self.user_edited)
            if p.kind == "point":
                c.pickRequested.connect(lambda n=p.name: self.pickRequested.emit(n))
            self.controls.append(c)
            label = QtWidgets.QLabel(p.label, self.form_box)
            label.setToolTip(c.toolTip())
            self.form.addRow(label, c)
        self._fill_inputs()
        self.request_preview()

    def _fill_inputs(self) -> None:
        before = self.input_ids()
        self._refill_inputs()
        if self.input_ids() != before:
            self.request_preview()  # a ghost of the former input must not stay on screen

    def _refill_inputs(self) -> None:
        doc = self.scene.doc
        # A label map is no input of the paper's operations (ADR 0033): it is not offered, and selecting
        # one says why.
        sel = [i for i in doc.selection if i in doc and doc.get(i).kind != "labels"]
        if any(i in doc and doc.get(i).kind == "labels" for i in doc.selection):
            self.status.setText(
                "A label map is no input of the operations: Edit ▸ Split into Objects gives one pixel "
                "object per label"
            )
        solids = self.op is not None and self.op.name in THREE_D
        for k, cb in enumerate(self.inputs):
            current = cb.currentData()
            cb.blockSignals(True)
            cb.clear()
            for o in reversed(doc.objects):
                if o.kind != "labels" and (o.dimension == 2 or solids):
                    cb.addItem(o.name, o.id)
            want = sel[k] if k < len(sel) else current
            if want is None and cb.count() > k:
                want = cb.itemData(k)
            i = cb.findData(want)
            cb.setCurrentIndex(i if i >= 0 else (0 if cb.count() else -1))
            cb.blockSignals(False)
        self._follow_dimension()

    def input_dimension(self) -> int:
        """The dimension of the chosen inputs (3 when the first is a 3D object)."""
        doc = self.scene.doc
        ids = [i for i in self.input_ids() if i in doc]
        return 3 if ids and doc.get(ids[0]).dimension == 3 else 2

    def _follow_dimension(self) -> None:
        """A centre gets its z for a 3D input; the rotation axis is shown for 3D inputs only."""
        n = self.input_dimension()
        for c in self.controls:
            c.set_dimension(n)
            if c.info.kind == "point" and c.info.spec.dimension == 3:
                c.setVisible(n == 3)
                label = self.form.labelForField(c)
                if label is not None:
                    label.setVisible(n == 3)

    def _doc_changed(self, ch: Any) -> None:
        if ch.reset:
            # Another project (File ▸ New or Open): nothing of the previous one is said here any more, and an
            # operation on its objects stops (its ids could name objects of the new one).
            self._project += 1
            self.cancel()
            self._finished()
            self._paused = False
            self.status.setText("")
        if (
            ch.inserted
            or ch.removed
            or ch.reset
            or ch.selection
            or any("name" in w for w in ch.changed.values())
        ):
            self._fill_inputs()
        if ch.settings or ch.reset:
            self._follow_model()
        if ch.changed or ch.removed or ch.reset or ch.settings:
            self.request_preview()

    def _follow_model(self) -> None:
        """The panel's model is the document's (Edit ▸ Discretization Model), so results keep D(E) = A."""
        for c in self.controls:
            if c.info.name == "model" and self.scene.doc.model in c.info.choices:
                c.set_value(self.scene.doc.model)

    # ------------------------------------------------------------------ values
    def values(self) -> dict[str, Any]:
        return {c.info.name: c.value() for c in self.controls}

    def control(self, name: str) -> ParamControl:
        for c in self.controls:
            if c.info.name == name:
                return c
        raise KeyError(name)

    def centre_control(self) -> ParamControl | None:
        """The operation's point parameter (a rotation or scaling centre), if it has one."""
        for c in self.controls:
            if c.info.kind == "point":
                return c
        return None

    def set_centre(self, x: float, y: float, name: str | None = None) -> bool:
        """Set the point parameter ``name`` (default: the first one) to (x, y), as if typed; False: none."""
        c = self.centre_control() if name is None else self.control(name)
        if c is None or c.info.kind != "point":
            return False
        c.set_value((x, y))
        self.user_edited()
        return True

    def input_ids(self) -> list[int]:
        return [int(cb.currentData()) for cb in self.inputs if cb.currentData() is not None]

    def _job(self) -> tuple[OpInfo, Any, list[int], list[Any]] | None:
        op = self.op
        if op is None:
            return None
        ids = self.input_ids()
        if len(ids) < op.arity:
            self.status.setText(f"{op.title} needs {op.arity} input object{'s' if op.arity > 1 else ''}.")
            return None
        bad = [c.error() for c in self.controls if not c.is_valid()]
        if bad:
            self.status.setText(f"<span style='color:#c0392b'>{bad[0]}</span>")
            return None
        try:
            params = op.spec.params.read(**self.values())  # checked once more as they become the parameters
        except (MRMError, TypeError, ValueError) as e:
            self.status.setText(f"<span style='color:#c0392b'>{e}</span>")
            return None
        sources = [self.scene.doc.get(i).source for i in ids]
        return op, params, ids, sources

    # ------------------------------------------------------------------ preview
    def _live_toggled(self, on: bool) -> None:
        if self._prefs is not None:
            self._prefs.live_preview = on
        self._paused = False
        if on:
            self.request_preview()
        else:
            self.clear_preview()
            self.status.setText("")

    def user_edited(self) -> None:
        """The user changed the input or a parameter: previews resume (they pause after Apply)."""
        self._paused = False
        self.request_preview()

    def current_key(self) -> tuple[Any, ...]:
        """What a preview is of: operation, inputs (and their revisions), parameters, model."""
        doc = self.scene.doc
        ids = tuple(self.input_ids())
        revs = tuple(doc.object_revision(i) for i in ids if i in doc)
        return (self.op.name if self.op else None, ids, revs, repr(sorted(self.values().items())), doc.model)

    def request_preview(self) -> None:
        """Clear the ghost at once (it would be of other inputs or parameters) and compute the new one."""
        self.clear_preview()
        if self.live.isChecked() and self.op is not None and not self._paused:
            self.status.setText("preview: computing…")
            self._preview_timer.start()

    def _run_preview(self) -> None:
        job = self._job()
        if job is None:
            self.clear_preview()
            return
        if self.input_dimension() == 3:  # the ghosts are drawn in the plane views
            self.status.setText("no live preview for 3D objects: Apply shows the result in the 3D views")
            return
        op, params, _ids, sources = job
        t0 = time.perf_counter()
        key = self.current_key()

        def done(results: list[tuple[str | None, Any]]) -> None:
            if key != self.current_key() or not self.live.isChecked() or self._paused:
                return  # of other inputs or parameters by now: never shown
            items = [(name or f"{op.title} preview", src) for name, src in results]
            self.scene.set_phantoms(items)
            names = ", ".join(self.scene.doc.get(i).name for i in _ids)
            self.status.setText(f"preview of {op.title} on {names} (grey ghost, not an object): "
                                f"{len(items)} result{'s' if len(items) != 1 else ''}, "
                                f"{time.perf_counter() - t0:.2f} s")  # fmt: skip
            self.previewed.emit()

        def failed(exc: BaseException) -> None:
            if not isinstance(exc, MRMError):
                raise exc
            self.scene.set_phantoms([])
            self.status.setText(f"<span style='color:#c0392b'>{exc}</span>")

        held = held_euclidean(self.scene.doc, _ids)  # R(A) the views computed: not again

        compact_limit = self.scene.doc.settings.compact_limit

        def work(progress: Any) -> list[tuple[str, Any]]:
            return op.run(sources, params, progress, held, compact_limit)

        self.runner.submit(
            "preview",
            work,
            on_result=done,
            on_error=failed,
            label=f"Preview {op.title}",
            revision=self.scene.doc.revision,
        )

    def clear_preview(self) -> None:
        self._preview_timer.stop()
        self.runner.cancel("preview")
        self.scene.set_phantoms([])

    # ------------------------------------------------------------------ apply / cancel
    def apply(self) -> None:
        job = self._job()
        if job is None:
            return
        op, params, ids, _sources = job
        self._preview_timer.stop()
        self.runner.cancel("preview")
        doc = self.scene.doc
        inputs = [doc.get(i) for i in ids]  # immutable values read by the worker
        held = held_euclidean(doc, ids)  # R(A) the views computed already: the worker uses it
        limit = self._prefs.pixel_limit if self._prefs is not None else None
        self.apply_button.setEnabled(False)
        self.cancel_button.setEnabled(True)
        self.status.setText(f"running {op.title}…")
        t0 = time.perf_counter()

        self._cancel_requested = False
        project = self._project

        def done(staged: Any) -> None:
            if project != self._project:
                return  # of the previous project
            if self._cancel_requested:
                # Cancel was pressed after the work's last report: the user still gets "nothing changed".
                cancelled()
                return
            self._finished()
            label, results = staged.label, staged.results
            if not results:
                self.status.setText(f"{op.title}: no result")
                return
            if any(i not in doc for i in ids):
                self.status.setText(f"{op.title}: an input was deleted meanwhile; nothing was changed")
                return
            w = self.window()
            taken = {o.name for o in doc.objects}
            kept, empty = [], []
            for r in results:
                name = unique_name(readable_name(r.name), taken)
                if _is_empty(r.source):
                    empty.append(readable_name(r.name))  # reported, never added as a 0-pixel object
                    continue
                taken.add(name)
                kept.append((name, r))
            if not kept:
                self.status.setText(f"{op.title}: the result is empty ({', '.join(empty)}); nothing added")
                return
            objs = [
                doc.make_object(
                    r.source,
                    name=name,
                    style=w.host.new_style(k) if hasattr(w, "host") else None,
                    provenance=r.provenance,
                )
                for k, (name, r) in enumerate(kept)
            ]
            try:
                doc.push(ApplyResults(label, add=objs))  # the one undo step of the plan
            except MRMError as e:
                self.status.setText(f"<span style='color:#c0392b'>{e}</span>")
                return
            self._paused = True  # no ghost of the operation applied again to its own result
            self.clear_preview()
            note = f"; empty, not created: {', '.join(empty)}" if empty else ""
            self.status.setText(f"{op.title}: {len(objs)} object{'s' if len(objs) != 1 else ''} added "
                                f"in {time.perf_counter() - t0:.2f} s{note}")  # fmt: skip
            self.applied.emit([o.id for o in objs])

        def failed(exc: BaseException) -> None:
            log_failure(log, op.title, exc)  # a bug or a broken worker: its traceback
            if project != self._project:
                return
            self._finished()
            if isinstance(exc, SizeLimitError):
                text = size_limit_text(exc, self.pixel_limit_setting)
            else:
                text = failure_message(exc)
            if not text.startswith(op.title):  # the model's message often names the operation already
                text = f"{op.title}: {text}"
            self.status.setText(f"<span style='color:#c0392b'>{html.escape(text, quote=False)}</span>")

        def cancelled() -> None:
            if project != self._project:
                return
            self._finished()
            self.status.setText(f"{op.title} cancelled; nothing was changed")

        self.runner.submit(
            "operation",
            # Operations are Python-heavy (exact rationals): in a worker process, off the GIL (ADR 0025).
            lambda progress: self.runner.call(
                self.plan_job,
                (inputs, op.name, params, limit, held, self.scene.doc.settings.compact_limit),
                progress,
            ),
            on_result=done,
            on_error=failed,
            on_cancel=cancelled,
            label=op.title,
            show_progress=True,
            # Its thread only waits for the worker process (which runs below the window's priority): at par,
            # so that a busy machine does not starve the hand-over the user waits for (ADR 0042).
            at_par=True,
        )

    def _finished(self) -> None:
        self.apply_button.setEnabled(True)
        self.cancel_button.setEnabled(False)

    def cancel(self) -> None:
        self._cancel_requested = self.is_running()
        self.runner.cancel("operation")
        self.runner.cancel("preview")

    def is_running(self) -> bool:
        return bool(self.runner.is_busy("operation"))
