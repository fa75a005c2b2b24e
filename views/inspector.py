"""The error inspector: provenance chain, the bound beside the measured distance, the differing pixels.

Everything shown is the model's account of the result (:func:`mrm.ops.account.account_of`), computed from
the result's pinned provenance — the content its inputs had when it was made — so editing or deleting an input
never changes it; the inspector says when an input changed since and offers to re-run the operation on the
current input as a new result. The pixels that differ from the direct result are drawn in light and dark grey
as in the paper's Figure 12.
"""

from __future__ import annotations

import html
import logging
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets

from mrm.core.errors import MRMError
from mrm.core.grids import VoxelSet, joint_box
from mrm.ops.account import Account, account_of, rerun_request
from mrm.views import gl_mesh
from mrm.views.canvas import Camera, MaskItem, Picture, PlaneView, lod_image, make_picture, qcolor
from mrm.views.failures import failure_message, log_failure
from mrm.views.provenance import bound_text, chain_rows, changes_text, measured_text
from mrm.views.scene import Scene

LIGHT_GREY = (200, 200, 200)
DARK_GREY = (95, 95, 95)
DIFF_LUT = np.array([[0, 0, 0, 0], [*LIGHT_GREY, 255], [*DARK_GREY, 255]])

log = logging.getLogger(__name__)


class ErrorInspector(QtWidgets.QWidget):
    """Dock content; follows the selected object.

    Parameters
    ----------
    scene : Scene
    runner : TaskRunner
        Runs the measurement: ``runner.call(measure_job, (provenance, compact_limit), progress)`` inside a
        task (``compact_limit``: the document's, for the R of voxel sets computed again).
    measure_job : callable
        ``measure_job(provenance, compact_limit, progress) -> Account``, a module-level function (the
        window's runner may send it to a worker process); the window passes it in, so that this view needs
        nothing of app/.
    """

    measured = QtCore.Signal()
    #: A measurement ended, however: 'measured', 'failed' (its message is shown) or 'cancelled'.
    measureEnded = QtCore.Signal(str)
    #: The picture of the differences is drawn (it is made on a worker after the measurement).
    pictured = QtCore.Signal()
    rerun_done = QtCore.Signal(list)

    def __init__(
        self,
        scene: Scene,
        runner: Any,
        parent: QtWidgets.QWidget | None = None,
        *,
        measure_job: Callable[[Any, Any, Any], Account],
    ) -> None:
        super().__init__(parent)
        self.setObjectName("errorInspector")
        self.scene = scene
        self.runner = runner
        self.measure_job = measure_job
        self.account: Account | None = None
        self.measurement: Account | None = None
        self.picture: DiffPicture | None = None  # the drawing of the measurement, once made
        self.difference3d: dict[str, Any] | None = None  # a 3D account's differing voxels, drawn in 3D
        self.title = QtWidgets.QLabel("", self)
        self.title.setWordWrap(True)
        self.changes_label = QtWidgets.QLabel("", self)
        self.changes_label.setObjectName("inputChanges")
        self.changes_label.setWordWrap(True)
        self.rerun_button = QtWidgets.QPushButton("Re-run on the current input", self)
        self.rerun_button.setObjectName("rerunButton")
        self.rerun_button.setToolTip(
            "Run the same operation with the same parameters on the inputs as they are now: a new result "
            "(this one keeps its account)"
        )
        self.rerun_button.clicked.connect(self.rerun)
        self.chain = QtWidgets.QTreeWidget(self)
        self.chain.setObjectName("provenanceChain")
        self.chain.setHeaderLabels(["step", "object", "size"])
        self.chain.setRootIsDecorated(False)
        self.chain.setUniformRowHeights(True)
        self.chain.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self.chain.setSizePolicy(QtWidgets.QSizePolicy.Policy.Preferred, QtWidgets.QSizePolicy.Policy.Fixed)
        self.chain.itemDoubleClicked.connect(self._go_to)
        self.bound_label = QtWidgets.QLabel("", self)
        self.bound_label.setObjectName("boundLabel")
        self.bound_label.setWordWrap(True)
        self.bound_label.setTextInteractionFlags(QtCore.Qt.TextInteractionFlag.TextSelectableByMouse)
        self.measured_label = QtWidgets.QLabel("", self)
        self.measured_label.setObjectName("measuredLabel")
        self.measured_label.setWordWrap(True)
        self.measure_button = QtWidgets.QPushButton("Measure", self)
        self.measure_button.setObjectName("measureButton")
        self.measure_button.setToolTip("Compute the exact Hausdorff distance and the direct result")
        self.measure_button.clicked.connect(self.start_measure)
        self.plane = PlaneView("inspector", self)
        self.plane.setMinimumHeight(160)
        self.camera = Camera(self)
        self.camera.add_view(self.plane)
        self.result_item = MaskItem()
        self.diff_item = MaskItem()
        self.diff_item.setZValue(1)
        self.plane.vb.addItem(self.result_item)
        self.plane.vb.addItem(self.diff_item)
        self.legend = QtWidgets.QLabel(
            "<span style='background:#c8c8c8'>&nbsp;&nbsp;&nbsp;</span> in the result, not in the direct one "
            "&nbsp; <span style='background:#5f5f5f'>&nbsp;&nbsp;&nbsp;</span> in the direct result, lost",
            self,
        )
        self.legend.setWordWrap(True)
        self.overlay = QtWidgets.QCheckBox("Show the differences in the discrete view", self)
        self.overlay.setObjectName("diffOverlay")
        self.overlay.toggled.connect(self._overlay_changed)
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(6, 6, 6, 6)
        lay.addWidget(self.title)
        changes = QtWidgets.QHBoxLayout()
        changes.addWidget(self.changes_label, 1)
        changes.addWidget(self.rerun_button)
        lay.addLayout(changes)
        lay.addWidget(self.chain)
        lay.addWidget(self.bound_label)
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self.measured_label, 1)
        row.addWidget(self.measure_button)
        lay.addLayout(row)
        lay.addWidget(self.plane, 1)
        lay.addWidget(self.legend)
        lay.addWidget(self.overlay)
        # Texts stay at the top when the picture is hidden: a spacer with no stretch takes the room only then
        # (the plane has stretch 1). Aligning the layout instead shrank the wrapped texts to a narrow column.
        lay.addStretch(0)
        self._overlay_item: MaskItem | None = None
        self._measured_for: Any = None  # the provenance the current measurement belongs to
        self._measured_text = ""  # its paragraph, written on the worker (it counts 10⁸-pixel differences)
        self._timer = QtCore.QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self.refresh)
        scene.documentChanged.connect(lambda _c: self._timer.start())
        self.refresh()

    # ------------------------------------------------------------------ state
    def refresh(self) -> None:
        obj = self.scene.selected()
        prov = obj.provenance if obj is not None else None
        keep = prov is not None and prov is self._measured_for and self.measurement is not None
        if not keep:
            self.runner.cancel("inspect")
            self.runner.cancel("inspect:picture")
            self.measurement = None
            self.picture = None
            self._measured_for = None
        self._show_diff()
        self.chain.clear()
        details = (
            self.chain,
            self.plane,
            self.legend,
            self.overlay,
            self.measure_button,
            self.measured_label,
        )
        for w in details:
            w.setVisible(prov is not None)
        if obj is not None and obj.dimension == 3:  # its differing voxels are drawn in the 3D discrete view
            self.plane.setVisible(False)
        if obj is None or prov is None:
            self.account = None
            self.title.setText(
                "Select an object produced by an operation to see its provenance, the paper's error bound "
                "and the measured error."
                if obj is None
                else f"<b>{obj.name}</b> was drawn or imported: no provenance, no error to account for."
            )
            self.bound_label.setText("")
            self.measured_label.setText("")
            self.changes_label.setText("")
            self.changes_label.setVisible(False)
            self.rerun_button.setVisible(False)
            self.measure_button.setEnabled(False)
            return
        doc = self.scene.doc
        # The fast part of the account (chain and bound, no geometry): the measurement goes to a worker.
        acc = account_of(prov, measure=False)
        self.account = acc
        rows = chain_rows(doc, obj, acc)
        origin = rows[0].name if rows else "?"
        self.title.setText(f"<b>{obj.name}</b> — {len(acc.chain)} operation(s) from <b>{origin}</b>")
        for r in rows:
            item = QtWidgets.QTreeWidgetItem([r.step, r.name, r.pixels])
            item.setData(0, QtCore.Qt.ItemDataRole.UserRole, r.obj_id)
            self.chain.addTopLevelItem(item)
        self._fit_chain()
        changes = changes_text(doc, obj)
        self.changes_label.setText(
            f"<span style='color:#b9770e'>{changes}</span><br><small>The account below is of the "
            "inputs as they were.</small>"
            if changes
            else ""
        )
        self.changes_label.setVisible(bool(changes))
        self.rerun_button.setVisible(bool(changes) and self._can_rerun(obj.id))
        self.bound_label.setText(bound_text(acc))
        can_measure = not acc.error and (acc.bound is not None or bool(acc.parts))
        self.measure_button.setEnabled(can_measure)
        if keep and self.measurement is not None:
            self.measured_label.setText(self._measured_text)
            return
        self.measured_label.setText("<b>Measured</b>: computing…" if can_measure else measured_text(acc))
        if can_measure:
            self.start_measure()

    #: The provenance list shows this many rows at least, and at most (a longer chain scrolls by rows).
    CHAIN_ROWS = (2, 6)

    def _fit_chain(self) -> None:
        """Make the provenance list as tall as its rows (a whole number of them, within CHAIN_ROWS).

        Half a row showing under a fixed height read as a table cut off.
        """
        tree = self.chain
        least, most = self.CHAIN_ROWS
        shown = min(max(tree.topLevelItemCount(), least), most)
        row = tree.sizeHintForRow(0) if tree.topLevelItemCount() else tree.fontMetrics().height() + 4
        header = tree.header().sizeHint().height() if not tree.isHeaderHidden() else 0
        tree.setFixedHeight(header + shown * row + 2 * tree.frameWidth())

    def _can_rerun(self, obj_id: int) -> bool:
        try:
            rerun_request(self.scene.doc, obj_id)
        except MRMError:
            return False
        return True

    def _go_to(self, item: QtWidgets.QTreeWidgetItem, _col: int) -> None:
        obj_id = item.data(0, QtCore.Qt.ItemDataRole.UserRole)
        if obj_id is not None and obj_id in self.scene.doc:
            self.scene.doc.set_selection([int(obj_id)])

    # ------------------------------------------------------------------ measuring
    def start_measure(self) -> None:
        acc = self.account
        obj = self.scene.selected()
        if acc is None or obj is None or obj.provenance is None or acc.error:
            return
        prov = obj.provenance
        self.measured_label.setText("<b>Measured</b>: computing…")

        def done(outcome: tuple[Account, str]) -> None:
            m, text = outcome
            now = self.scene.selected()
            if now is None or now.provenance is not prov:
                return  # another object was selected meanwhile
            self.measurement = m
            self.picture = None
            self._measured_for = prov
            self._measured_text = text
            self.measured_label.setText(text)
            self._show_diff()  # clears the previous picture at once
            self.measured.emit()
            self.measureEnded.emit("measured")
            self._request_picture(m)

        def failed(exc: BaseException) -> None:
            # Whatever failed — the model, the worker process, the pickling of the result — is said here,
            # and ends "computing…"; a bug's traceback goes to the log.
            log_failure(log, f"measuring {obj.name}", exc)
            text = failure_message(exc)
            self.measured_label.setText(
                f"<b>Measured</b>: could not be computed: {html.escape(text, quote=False)}"
            )
            self.measureEnded.emit("failed")

        def cancelled() -> None:
            if self.runner.is_busy("inspect"):
                return  # superseded: a newer measurement runs, and says how it ends
            self.measured_label.setText("<b>Measured</b>: cancelled — <i>Measure</i> computes it")
            self.measureEnded.emit("cancelled")

        # The provenance is an immutable value pinning everything the account reads: safe on a worker. The
        # exact measurement is Python-heavy for minutes at 10⁸ pixels: in a worker process, so that the
        # window's painting never waits for the GIL it would hold (ADR 0025).
        job = self.measure_job
        compact_limit = self.scene.doc.settings.compact_limit  # the R its operations used
        self.runner.submit(
            "inspect",
            lambda progress: _with_text(self.runner.call(job, (prov, compact_limit), progress)),
            on_result=done,
            on_error=failed,
            on_cancel=cancelled,
            label=f"{obj.name}: measuring the error",
            show_progress=True,
            at_par=True,  # its thread only waits for the worker process (ADR 0042)
        )

    def cancel(self) -> None:
        """Stop measuring (and drawing the differences); the account's chain and bound stay shown."""
        self.runner.cancel("inspect")
        self.runner.cancel("inspect:picture")

    # ------------------------------------------------------------------ re-running
    def rerun(self) -> None:
        """Run the result's operation again on the current inputs, as a new result (one undo step)."""
        obj = self.scene.selected()
        if obj is None or obj.provenance is None:
            return
        doc = self.scene.doc
        try:
            request = rerun_request(doc, obj.id)
        except MRMError as e:
            self.changes_label.setText(f"<span style='color:#c0392b'>{e}</span>")
            return
        from mrm.document.apply import push_plan

        inputs = request.inputs

        def done(plan: Any) -> None:
            if any(o.id not in doc or doc.get(o.id) is not o for o in inputs):
                self.changes_label.setText("an input changed again meanwhile; nothing was added")
                return
            ids = push_plan(doc, plan)
            doc.set_selection(ids[:1])
            self.rerun_done.emit(ids)

        def failed(exc: BaseException) -> None:
            if not isinstance(exc, MRMError):
                raise exc
            self.changes_label.setText(f"<span style='color:#c0392b'>{exc}</span>")

        self.runner.submit(
            "rerun",
            request.plan,
            on_result=done,
            on_error=failed,
            label="Re-running on the current input",
        )

    # ------------------------------------------------------------------ pictures
    def _request_picture(self, m: Account) -> None:
        """Make the drawing of ``m`` on a worker: at 10⁸ pixels the union and the masks take seconds."""
        if isinstance(m.result, VoxelSet):  # 3D: the differing voxels are drawn in the 3D discrete view
            self._request_voxel_difference(m)
            return

        def done(pic: DiffPicture | None) -> None:
            if self.measurement is m:
                self.picture = pic
                self._show_diff()
                self.pictured.emit()

        self.picture = None
        lut = self._result_lut()
        self.runner.submit(
            "inspect:picture",
            lambda _p: diff_picture(m, lut),
            on_result=done,
            label="Drawing the differences",
        )

    def _request_voxel_difference(self, m: Account) -> None:
        """The surfels of the voxels that differ from the direct result, made on a worker (3D accounts)."""

        def done(data: dict[str, Any] | None) -> None:
            if self.measurement is m:
                self.difference3d = data
                self._overlay_changed(self.overlay.isChecked())
                self.pictured.emit()

        def work(_p: Any) -> dict[str, Any] | None:
            if m.difference is None:
                return None
            return gl_mesh.difference_arrays(m.difference.light, m.difference.dark, LIGHT_GREY, DARK_GREY)

        self.picture = None
        self.difference3d = None
        self.runner.submit("inspect:picture", work, on_result=done, label="Drawing the differing voxels")

    def _result_lut(self) -> np.ndarray:
        """The table the result is drawn with: the selected object's colour."""
        obj = self.scene.selected()
        colour = qcolor(obj.style.fill) if obj is not None else QtGui.QColor("#4c72b0")
        return np.array([[0, 0, 0, 0], [*colour.getRgb()[:3], 110]])

    def _show_diff(self) -> None:
        m = self.measurement
        pic = self.picture if m is not None else None
        if pic is None:
            self.result_item.set_pixels(None, (0, 0))
            self.diff_item.set_pixels(None, (0, 0))
            self._overlay_changed(self.overlay.isChecked())
            return
        self.result_item.set_pixels(
            pic.result,
            pic.result_origin,
            self._result_lut(),
            pic.result_f,
            pic.result_full,
            pic.result_picture,
        )
        if pic.diff is not None:
            self.diff_item.set_pixels(
                pic.diff, pic.diff_origin, DIFF_LUT, pic.diff_f, pic.diff_full, pic.diff_picture
            )
        else:
            self.diff_item.set_pixels(None, (0, 0))
        box = pic.box
        if box is not None:
            self.camera.fit((box[0] - 1.5, box[1] - 1.5, box[2] + 1.5, box[3] + 1.5), margin=0.02)
        self._overlay_changed(self.overlay.isChecked())

    def _overlay_changed(self, on: bool) -> None:
        """Draw the difference pixels over the main discrete view too."""
        w = self.window()
        views = getattr(w, "views", None)
        if views is None:
            return
        area3d = getattr(views, "area3d", None)
        if area3d is not None:  # the 3D discrete view draws a 3D account's differing voxels
            measured3d = self.measurement is not None and isinstance(self.measurement.result, VoxelSet)
            area3d.show_difference(self.difference3d if on and measured3d else None)
        vb = views.discrete.plane.vb
        if self._overlay_item is not None:
            self._overlay_item.detach()
            vb.removeItem(self._overlay_item)
            self._overlay_item = None
        pic = self.picture if self.measurement is not None else None
        if on and pic is not None and pic.diff is not None:
            item = MaskItem()
            vb.addItem(item)
            item.setZValue(30_000)
            item.set_pixels(pic.diff, pic.diff_origin, DIFF_LUT, pic.diff_f, pic.diff_full, pic.diff_picture)
            self._overlay_item = item

    def is_measuring(self) -> bool:
        return bool(self.runner.is_busy("inspect") or self.runner.is_busy("inspect:picture"))


def _with_text(m: Account) -> tuple[Account, str]:
    """A measurement with its paragraph, made on the worker.

    The paragraph counts the differing pixels: 30 ms at 17 M pixels, a stall on the GUI thread.
    """
    return m, measured_text(m)


@dataclass(frozen=True, eq=False)
class DiffPicture:
    """What the inspector draws of a measured account, made off the GUI thread by :func:`diff_picture`.

    Each image is a level-of-detail image (:func:`~mrm.views.canvas.lod_image`) with its factor, the
    exact mask behind it and its picture (:func:`~mrm.views.canvas.make_picture`), as
    :meth:`MaskItem.set_pixels` takes them. Without a picture the first paint converted the image on the
    GUI thread: 80 ms for a 4 M-pixel result.
    """

    result: np.ndarray
    result_f: int
    result_full: np.ndarray
    result_origin: tuple[int, int]
    diff: np.ndarray | None  # 1 = light grey (only in the result), 2 = dark grey (only in the direct one)
    diff_f: int
    diff_full: np.ndarray | None
    diff_origin: tuple[int, int]
    box: tuple[int, int, int, int] | None  # the result and the direct result together
    result_picture: Picture | None = None
    diff_picture: Picture | None = None


def diff_image(m: Account) -> tuple[np.ndarray, tuple[int, int]] | None:
    """The label image of the differing pixels of ``m`` over the box of both results, and its origin."""
    if m.result is None or m.direct is None or m.difference is None:
        return None
    light_ps, dark_ps = m.difference.light, m.difference.dark
    boxes = [ps.bbox for ps in (light_ps, dark_ps) if not ps.is_empty()]
    if not boxes:
        return None
    # The box of the differences only: the union of the two results is never built.
    box = joint_box(boxes)
    assert box is not None
    img = np.zeros((box[3] - box[1] + 1, box[2] - box[0] + 1), dtype=np.uint8)
    for ps, value in ((light_ps, 1), (dark_ps, 2)):
        if not ps.is_empty():
            x0, y0 = ps.origin
            h, w = ps.shape
            sub = img[y0 - box[1] : y0 - box[1] + h, x0 - box[0] : x0 - box[0] + w]
            sub[ps.mask] = value
    return img, (box[0], box[1])


def diff_picture(m: Account, result_lut: np.ndarray | None = None) -> DiffPicture | None:
    """Everything :class:`ErrorInspector` draws for ``m``; runs on a worker (numpy, and QImages).

    With ``result_lut`` (the table the result is drawn with) the pictures are made too.
    """
    if m.result is None or isinstance(m.result, VoxelSet):  # a 3D account is drawn in the 3D views
        return None
    result, rf = lod_image(m.result.mask)
    d = diff_image(m)
    diff, df, full, origin = None, 1, None, (0, 0)
    if d is not None:
        full, origin = d
        diff, df = lod_image(full)
    box = joint_box([m.result.bbox, m.direct.bbox if m.direct is not None else None])
    result_pic = make_picture(result, result_lut) if result_lut is not None else None
    diff_pic = make_picture(diff, DIFF_LUT) if result_lut is not None and diff is not None else None
    return DiffPicture(
        result, rf, m.result.mask, m.result.origin, diff, df, full, origin, box, result_pic, diff_pic
    )
