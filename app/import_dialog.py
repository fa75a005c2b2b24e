"""Importing a grey, colour or label image: ask once how to turn it into objects.

A binary image (two values) imports as it is. Any other image opens this dialog: a threshold (Otsu's value
proposed and shown, adjustable with a slider and a field), an Invert box, a preview of the pixels that would
be imported — or, for a grey (PNG or PGM) or indexed image or an NPZ label array, one label map object
(ADR 0033) or one object per label (each non-zero value). The pixels themselves are read by the model
(:func:`mrm.io.pixel_files.read_pixels` with the chosen threshold, :func:`mrm.io.pixel_files.read_label_map`);
the dialog only reads the image's values for the preview.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets

PREVIEW_SIZE = 220


def image_values(path: Path) -> tuple[np.ndarray, bool, bool] | None:
    """``(values, labels_ok, labels_first)`` of an image; None if binary (imported with no question).

    The values are the grey values, rows top first; ``labels_ok`` says whether labels make sense,
    ``labels_first`` whether they are the image's meaning (an indexed PNG, an NPZ ``labels`` array).
    Colour images give their luminance (the model's :func:`~mrm.core.threshold.luminance`); labels are
    offered for grey and indexed images and NPZ label arrays only.
    """
    from PIL import Image

    from mrm.core.threshold import luminance

    suffix = path.suffix.lower()
    if suffix == ".npz":
        return _npz_labels(path)
    if suffix == ".pgm":
        return _netpbm_values(path)
    if suffix != ".png":
        return None  # PBM is binary; a GeoTIFF keeps the model's own rules
    with Image.open(path) as im:
        mode = im.mode
        if mode == "1":
            return None
        labels_ok = mode in ("L", "P", "I", "I;16", "I;16B", "I;16L", "I;16N")
        if mode in ("RGB", "RGBA", "LA", "PA") or (mode == "P" and "transparency" in im.info):
            rgb = np.asarray(im.convert("RGB"), dtype=np.int64)
            grey = luminance(rgb)
        else:
            grey = np.asarray(im, dtype=np.int64)  # grey values, or palette indices
    if _binary(grey):
        return None  # binary: imported as it is, no question
    return grey, labels_ok, mode == "P" and labels_ok


def _binary(values: np.ndarray) -> bool:
    v = np.unique(values)
    return len(v) <= 2 and (len(v) < 2 or v[0] == 0)


def _netpbm_values(path: Path) -> tuple[np.ndarray, bool, bool] | None:
    """A PGM's grey values (labels offered), read by the model's reader; None if binary or unreadable."""
    from mrm.core.errors import FileFormatError
    from mrm.core.limits import DEFAULT_PIXEL_LIMIT
    from mrm.core.threshold import grey_of
    from mrm.io.netpbm import read_netpbm

    try:
        with open(path, "rb") as fh:
            img = read_netpbm(fh, path.name, DEFAULT_PIXEL_LIMIT)  # what read_pixels accepts
    except (OSError, FileFormatError):
        return None  # the model's reader says what is wrong when the file is imported
    if img.samples.dtype == np.bool_:
        return None
    colour = img.samples.ndim == 3
    grey = np.asarray(grey_of(img.samples) if colour else img.samples, dtype=np.int64)
    return None if _binary(grey) else (grey, not colour, False)


def _npz_labels(path: Path) -> tuple[np.ndarray, bool, bool] | None:
    """An NPZ holding a ``labels`` array: its labels (rows top first); None for a pixel set's NPZ."""
    import zipfile

    try:
        with zipfile.ZipFile(path) as z:
            if "labels.npy" not in z.namelist():
                return None
    except (OSError, zipfile.BadZipFile):
        return None  # the model's reader says what is wrong
    from mrm.io.pixel_files import read_label_map

    lm = read_label_map(path)
    return np.asarray(lm.labels[::-1], dtype=np.int64), True, True


def image_kind(path: Path, labels_ok: bool) -> str:
    """What an image holds, for people: ``indexed-colour``, ``colour``, ``grey`` or ``label`` (NPZ labels).

    A PNG says it in its header (read alone: no pixel is decoded); other files go by whether labels make sense
    for them (grey) or not (colour).
    """
    suffix = path.suffix.lower()
    if suffix == ".npz":
        return "label"
    if suffix == ".png":
        from PIL import Image

        try:
            with Image.open(path) as im:
                mode = im.mode
        except OSError:
            mode = ""
        if mode in ("P", "PA"):
            return "indexed-colour"
        if mode in ("RGB", "RGBA"):
            return "colour"
        if mode:
            return "grey"
    return "grey" if labels_ok else "colour"


class ImageImportDialog(QtWidgets.QDialog):
    """Threshold (Otsu shown), invert, preview — or one label map object, or one object per label."""

    def __init__(
        self,
        path: Path,
        grey: np.ndarray,
        labels_ok: bool,
        labels_first: bool = False,
        parent: QtWidgets.QWidget | None = None,
    ) -> None:
        super().__init__(parent)
        from mrm.core.threshold import otsu_threshold

        self.setObjectName("imageImportDialog")
        self.setWindowTitle(f"Import {path.name}")
        self.path = path
        self.grey = grey
        top = int(grey.max())
        hist = np.bincount(grey.ravel().astype(np.int64), minlength=top + 1)
        self.otsu = int(otsu_threshold(hist))
        lay = QtWidgets.QVBoxLayout(self)
        kind = image_kind(path, labels_ok)
        article = "an" if kind[0] in "aeiou" else "a"
        self.description = QtWidgets.QLabel(
            f"{path.name} is {article} {kind} image ({grey.shape[1]} × {grey.shape[0]}, values 0–{top}). "
            "How should it become objects?",
            self,
        )
        self.description.setObjectName("importDescription")
        self.description.setWordWrap(True)
        lay.addWidget(self.description)
        self.threshold_mode = QtWidgets.QRadioButton("Pixels brighter than a threshold", self)
        self.threshold_mode.setObjectName("thresholdMode")
        # An NPZ label array has no brightness to cut; an indexed image's values are labels first.
        self.threshold_mode.setEnabled(path.suffix.lower() != ".npz")
        self.map_mode = QtWidgets.QRadioButton(
            "One label map object: its labels, cells and watertight polygons (gauss)", self
        )
        self.map_mode.setObjectName("labelMapMode")
        self.map_mode.setToolTip(
            "Every non-zero value is a label; regions sharing a boundary share one polyline. "
            "Edit ▸ Split into Objects later gives one object per label"
        )
        self.labels_mode = QtWidgets.QRadioButton("One object per label (each non-zero value)", self)
        self.labels_mode.setObjectName("labelsMode")
        for w in (self.map_mode, self.labels_mode):
            w.setEnabled(labels_ok)
            if not labels_ok:
                w.setToolTip("Labels need a grey or indexed image")
        (self.map_mode if labels_ok and labels_first else self.threshold_mode).setChecked(True)
        lay.addWidget(self.threshold_mode)
        row = QtWidgets.QHBoxLayout()
        self.slider = QtWidgets.QSlider(QtCore.Qt.Orientation.Horizontal, self)
        self.slider.setObjectName("thresholdSlider")
        self.slider.setRange(0, max(top - 1, 0))
        self.spin = QtWidgets.QSpinBox(self)
        self.spin.setObjectName("thresholdField")
        self.spin.setRange(0, max(top - 1, 0))
        self.slider.setValue(self.otsu)
        self.spin.setValue(self.otsu)
        self.slider.valueChanged.connect(self.spin.setValue)
        self.spin.valueChanged.connect(self.slider.setValue)
        self.spin.valueChanged.connect(lambda _v: self.update_preview())
        row.addWidget(self.slider, 1)
        row.addWidget(self.spin)
        self.otsu_button = QtWidgets.QPushButton(f"Otsu: {self.otsu}", self)
        self.otsu_button.setObjectName("otsuButton")
        self.otsu_button.setToolTip(
            "Back to Otsu's threshold (the split with the largest between-class variance)"
        )
        self.otsu_button.clicked.connect(lambda: self.spin.setValue(self.otsu))
        row.addWidget(self.otsu_button)
        lay.addLayout(row)
        self.invert = QtWidgets.QCheckBox("Invert (dark pixels are the object)", self)
        self.invert.setObjectName("invertBox")
        self.invert.toggled.connect(lambda _v: self.update_preview())
        lay.addWidget(self.invert)
        lay.addWidget(self.map_mode)
        lay.addWidget(self.labels_mode)
        self.threshold_mode.toggled.connect(lambda _v: self.update_preview())
        self.map_mode.toggled.connect(lambda _v: self.update_preview())
        self.preview = QtWidgets.QLabel(self)
        self.preview.setObjectName("importPreview")
        self.preview.setAlignment(QtCore.Qt.AlignmentFlag.AlignCenter)
        self.preview.setMinimumSize(PREVIEW_SIZE, PREVIEW_SIZE)
        lay.addWidget(self.preview, 1)
        self.summary = QtWidgets.QLabel("", self)
        self.summary.setObjectName("importSummary")
        lay.addWidget(self.summary)
        std = QtWidgets.QDialogButtonBox.StandardButton
        buttons = QtWidgets.QDialogButtonBox(std.Ok | std.Cancel, self)
        buttons.button(std.Ok).setText("Import")
        buttons.button(std.Ok).setObjectName("importButton")
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        lay.addWidget(buttons)
        self.update_preview()

    def mask(self) -> np.ndarray:
        """The pixels the threshold choice imports (rows top first), as the model's rule: value > t."""
        m = self.grey > self.spin.value()
        return ~m if self.invert.isChecked() else m

    def update_preview(self) -> None:
        on = self.threshold_mode.isChecked()
        for w in (self.slider, self.spin, self.otsu_button, self.invert):
            w.setEnabled(on)
        if on:
            m = self.mask()
            img = np.where(m, 30, 235).astype(np.uint8)
            self.summary.setText(f"{int(m.sum()):,} pixels of {m.size:,} (threshold {self.spin.value()})")
        else:
            vals = np.unique(self.grey)
            n = int((vals != 0).sum())
            img = (255 - (self.grey * 37 % 200)).astype(np.uint8)
            img[self.grey == 0] = 255
            self.summary.setText(
                f"1 label map object: {n} labels"
                if self.map_mode.isChecked()
                else f"{n} objects, one per non-zero value"
            )
        h, w = img.shape
        q = QtGui.QImage(np.ascontiguousarray(img).data, w, h, w, QtGui.QImage.Format.Format_Grayscale8)
        pm = QtGui.QPixmap.fromImage(q.copy()).scaled(
            PREVIEW_SIZE,
            PREVIEW_SIZE,
            QtCore.Qt.AspectRatioMode.KeepAspectRatio,
            QtCore.Qt.TransformationMode.FastTransformation,
        )
        self.preview.setPixmap(pm)

    def reader(self) -> Callable[[], list[tuple[str, Any]]]:
        """The choice made in the dialog, as a function that reads the file's (name, source) pairs.

        It holds the choice's values, not the widgets, so it runs on any thread (the import's worker).
        """
        from mrm.io.pixel_files import read_label_map, read_pixels

        path, stem = self.path, self.path.stem
        as_map, per_label = self.map_mode.isChecked(), self.labels_mode.isChecked()
        t, invert = self.spin.value(), self.invert.isChecked()

        def read() -> list[tuple[str, Any]]:
            if as_map:
                return [(stem, read_label_map(path))]
            if per_label:
                lm = read_label_map(path)
                return [(f"{stem} label {v}", lm.pixel_set(v)) for v in lm.label_values() if v != 0]
            ps = read_pixels(path, threshold=t)
            if invert:
                full = read_pixels(path, threshold=-1)  # every pixel: the image's box at its origin
                ps = full.difference(ps)
            return [(stem, ps)]

        return read
