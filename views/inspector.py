"""The error inspector: provenance chain, the bound beside the measured distance, the differing pixels.

The bound is the paper's (DESIGN §8), the measured error the exact Hausdorff distance; the pixels that differ
from the direct result are drawn in light and dark grey as in the paper's Figure 12.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets

from mrm.errors import MRMError
from mrm.views.canvas import Camera, MaskItem, PlaneView, qcolor
from mrm.views.provenance import Account, Measurement, account_of, measure
from mrm.views.scene import Scene

LIGHT_GREY = (200, 200, 200)
DARK_GREY = (95, 95, 95)


class ErrorInspector(QtWidgets.QWidget):
    """Dock content; follows the selected object."""

    measured = QtCore.Signal()

    def __init__(self, scene: Scene, runner: Any, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("errorInspector")
        self.scene = scene
        self.runner = runner
        self.account: Account | None = None
        self.measurement: Measurement | None = None
        self.title = QtWidgets.QLabel("", self)
        self.title.setWordWrap(True)
        self.chain = QtWidgets.QTreeWidget(self)
        self.chain.setObjectName("provenanceChain")
        self.chain.setHeaderLabels(["step", "object", "pixels"])
        self.chain.setRootIsDecorated(False)
        self.chain.setMaximumHeight(130)
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
        lay.addWidget(self.chain)
        lay.addWidget(self.bound_label)
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self.measured_label, 1)
        row.addWidget(self.measure_button)
        lay.addLayout(row)
        lay.addWidget(self.plane, 1)
        lay.addWidget(self.legend)
        lay.addWidget(self.overlay)
        lay.setAlignment(QtCore.Qt.AlignmentFlag.AlignTop)  # texts stay at the top when the picture is hidden
        self._overlay_item: MaskItem | None = None
        self._timer = QtCore.QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self.refresh)
        scene.documentChanged.connect(lambda _c: self._timer.start())
        self.refresh()

    # ------------------------------------------------------------------ state
    def refresh(self) -> None:
        obj = self.scene.primary()
        self.runner.cancel("inspect")
        self.measurement = None
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
            w.setVisible(obj is not None and obj.provenance is not None)
        if obj is None or obj.provenance is None:
            self.account = None
            self.title.setText(
                "Select an object produced by an operation to see its provenance, the paper's error bound "
                "and the measured error."
                if obj is None
                else f"<b>{obj.name}</b> was drawn or imported: no provenance, no error to account for."
            )
            self.bound_label.setText("")
            self.measured_label.setText("")
            self.measure_button.setEnabled(False)
            return
        acc = account_of(self.scene.doc, obj.id)
        self.account = acc
        origin = acc.origin.name if acc.origin is not None else "(deleted object)"
        self.title.setText(f"<b>{obj.name}</b> — {len(acc.links)} operation(s) from <b>{origin}</b>")
        if acc.origin is not None:
            self._add_row("start", acc.origin)
        for link in acc.links:
            self._add_row(link.label(), link.obj)
        if acc.bound is not None:
            b = acc.shown or acc.bound
            value = f"{b.bound:.4g}" if b.bound is not None else f"{b.value:.4g} (one-sided)"
            self.bound_label.setText(
                f"<b>Bound</b> ({b.model}): H ≤ {value}<br><small>{b.formula}<br>{b.guarantee}</small>"
            )
        else:
            self.bound_label.setText(f"<b>Bound</b>: {acc.bound_error or 'none'}")
        self.measure_button.setEnabled(acc.similarity_chain)
        self.measured_label.setText(
            "<b>Measured</b>: computing…"
            if acc.similarity_chain
            else "<b>Measured</b>: not available for this chain"
        )
        if acc.similarity_chain:
            self.start_measure()

    def _add_row(self, label: str, obj: Any) -> None:
        ps = self.scene.doc.derived(obj.id).peek("discrete")
        item = QtWidgets.QTreeWidgetItem([label, obj.name, f"{ps.count:,}" if ps is not None else "…"])
        item.setData(0, QtCore.Qt.ItemDataRole.UserRole, obj.id)
        self.chain.addTopLevelItem(item)

    def _go_to(self, item: QtWidgets.QTreeWidgetItem, _col: int) -> None:
        obj_id = item.data(0, QtCore.Qt.ItemDataRole.UserRole)
        if obj_id is not None and obj_id in self.scene.doc:
            self.scene.doc.set_selection([int(obj_id)])

    # ------------------------------------------------------------------ measuring
    def start_measure(self) -> None:
        acc = self.account
        if acc is None or not acc.similarity_chain:
            return
        doc = self.scene.doc
        self.measured_label.setText("<b>Measured</b>: computing…")

        def done(m: Measurement) -> None:
            self.measurement = m
            b = acc.bound
            verdict = ""
            if m.exceeds_bound is not None and b is not None:
                verdict = (
                    " — <span style='color:#c0392b'><b>exceeds the bound</b></span>"
                    if m.exceeds_bound
                    else " — within the bound ✓"
                )
            self.measured_label.setText(
                f"<b>Measured</b>: H(T(A_first), A_last) = {m.measured:.4g}{verdict}<br>"
                f"<small>{m.light.count:,} pixels only in the result (light grey), "
                f"{m.dark.count:,} only in the direct result D(T(R(A))) (dark grey)</small>"
            )
            self._show_diff()
            self.measured.emit()

        def failed(exc: BaseException) -> None:
            if not isinstance(exc, MRMError):
                raise exc
            self.measured_label.setText(f"<b>Measured</b>: {exc}")

        self.runner.submit(
            "inspect",
            lambda progress: measure(doc, acc, progress),
            on_result=done,
            on_error=failed,
            label="Measuring the error",
            revision=doc.revision,
        )

    # ------------------------------------------------------------------ pictures
    def _diff_image(self, m: Measurement) -> tuple[np.ndarray, tuple[int, int]] | None:
        union = m.result | m.direct
        box = union.bbox
        if box is None:
            return None
        img = np.zeros((box[3] - box[1] + 1, box[2] - box[0] + 1), dtype=np.uint8)
        light = m.light.to_array(box) if not m.light.is_empty() else None
        dark = m.dark.to_array(box) if not m.dark.is_empty() else None
        if light is not None:
            img[light] = 1
        if dark is not None:
            img[dark] = 2
        return img, (box[0], box[1])

    def _show_diff(self) -> None:
        m = self.measurement
        lut = np.array([[0, 0, 0, 0], [*LIGHT_GREY, 255], [*DARK_GREY, 255]])
        if m is None:
            self.result_item.set_pixels(None, (0, 0))
            self.diff_item.set_pixels(None, (0, 0))
            self._overlay_changed(self.overlay.isChecked())
            return
        obj = self.account.obj if self.account is not None else None
        colour = qcolor(obj.style.fill) if obj is not None else QtGui.QColor("#4c72b0")
        self.result_item.set_pixels(
            m.result.mask, m.result.origin, np.array([[0, 0, 0, 0], [*colour.getRgb()[:3], 110]])
        )
        d = self._diff_image(m)
        if d is not None:
            self.diff_item.set_pixels(d[0], d[1], lut)
        box = (m.result | m.direct).bbox
        if box is not None:
            self.camera.fit((box[0] - 1.5, box[1] - 1.5, box[2] + 1.5, box[3] + 1.5), margin=0.02)
        self._overlay_changed(self.overlay.isChecked())

    def _overlay_changed(self, on: bool) -> None:
        """Draw the difference pixels over the main discrete view too."""
        w = self.window()
        views = getattr(w, "views", None)
        if views is None:
            return
        vb = views.discrete.plane.vb
        if self._overlay_item is not None:
            vb.removeItem(self._overlay_item)
            self._overlay_item = None
        m = self.measurement
        if on and m is not None:
            d = self._diff_image(m)
            if d is not None:
                item = MaskItem()
                item.setZValue(30_000)
                lut = np.array([[0, 0, 0, 0], [*LIGHT_GREY, 255], [*DARK_GREY, 255]])
                item.set_pixels(d[0], d[1], lut)
                vb.addItem(item)
                self._overlay_item = item

    def is_measuring(self) -> bool:
        return bool(self.runner.is_busy("inspect"))
