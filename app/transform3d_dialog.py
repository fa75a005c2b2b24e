"""Edit ▸ Transform 3D Object (Ctrl+T): move, scale and rotate a polyhedron object by numbers, one undo step.

The map is v ↦ R·s·(v − c) + c + d: a scaling by s and a rotation by an angle about the x, y or z axis, both
about c, the centre of the polyhedron's bounding box, then a move by d. The new solid is computed and checked
on a worker (:meth:`mrm.geometry.polyhedra.Polyhedron.affine` validates it again: rounding to float64 can make
nearby sheets touch, and such a result is refused with the reason).
"""

from __future__ import annotations

import math

import numpy as np
from PySide6 import QtWidgets

AXES = ("x", "y", "z")


def rotation_matrix(axis: str, degrees: float) -> np.ndarray:
    """The rotation by ``degrees`` about the ``axis`` (counter-clockwise seen from its positive side).

    Quarter turns are exact (their sines and cosines are 0 and ±1), so a rotation by 90° maps integer
    vertices to integer vertices.
    """
    quarter, rest = divmod(float(degrees), 90.0)
    if rest == 0.0:
        c, s = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(quarter) % 4]
    else:
        r = math.radians(degrees)
        c, s = math.cos(r), math.sin(r)
    i = AXES.index(axis)
    j, k = (i + 1) % 3, (i + 2) % 3
    m = np.eye(3)
    m[j, j], m[j, k], m[k, j], m[k, k] = c, -s, s, c
    return m


class Transform3DDialog(QtWidgets.QDialog):
    """Numbers for a move, a scaling and a rotation about the solid's centre."""

    def __init__(self, name: str, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("transform3dDialog")
        self.setWindowTitle(f"Transform {name}")
        form = QtWidgets.QFormLayout(self)

        def spin(
            object_name: str, lo: float, hi: float, value: float, decimals: int = 4
        ) -> QtWidgets.QDoubleSpinBox:
            box = QtWidgets.QDoubleSpinBox(self)
            box.setObjectName(object_name)
            box.setRange(lo, hi)
            box.setDecimals(decimals)
            box.setValue(value)
            return box

        self.move = [spin(f"move_{a}", -1e9, 1e9, 0.0) for a in AXES]
        row = QtWidgets.QHBoxLayout()
        for box in self.move:
            row.addWidget(box)
        form.addRow("Move by (x, y, z)", row)
        self.scale = spin("scale", 1e-6, 1e6, 1.0, 6)
        form.addRow("Scale by (about the centre)", self.scale)
        self.axis = QtWidgets.QComboBox(self)
        self.axis.setObjectName("axis")
        self.axis.addItems([f"about {a}" for a in AXES])
        self.axis.setCurrentIndex(2)
        self.angle = spin("angle", -360.0, 360.0, 0.0)
        rot = QtWidgets.QHBoxLayout()
        rot.addWidget(self.angle)
        rot.addWidget(self.axis)
        form.addRow("Rotate by degrees", rot)
        buttons = QtWidgets.QDialogButtonBox(
            QtWidgets.QDialogButtonBox.StandardButton.Ok | QtWidgets.QDialogButtonBox.StandardButton.Cancel,
            self,
        )
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def map(self, centre: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The (linear, offset) of v ↦ R·s·(v − c) + c + d for the numbers entered."""
        linear = rotation_matrix(AXES[self.axis.currentIndex()], self.angle.value()) * self.scale.value()
        offset = centre - linear @ centre + np.array([b.value() for b in self.move])
        return linear, offset
