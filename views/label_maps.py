"""How the four views draw a label map object (ADR 0033): labels in colours, cells, the subdivision.

A label map is one object holding every label of a label image. The discrete view colours its pixels by
label, the region view shows its cells (the 1-cells, boundaries between two regions, and the 0-cells where
three or more meet), the Euclidean view its watertight gauss subdivision (each label's part filled in the
label's colour, each shared boundary stroked once). It has no segments of its own: the analytical view
says so. The drawing data is made here on any thread, like the other views' (``prepared``).
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

import numpy as np
from PySide6 import QtGui

from mrm.core.grids import LabelMap
from mrm.views.base_view import Layer
from mrm.views.canvas import MaskItem, lod_image, pictured, qcolor
from mrm.views.items import (
    LodPathItem,
    MarkersItem,
    PathItem,
    StrokeLevel,
    levels_path,
    polygon_rings,
    ring_groups,
    rings_path,
    stroke_levels,
)
from mrm.views.palette import COMPONENT_COLOURS
from mrm.views.region_view import chain_xy

#: The colours labels are drawn with (:func:`label_palette` gives each label one).
LABEL_COLOURS = COMPONENT_COLOURS


@lru_cache(maxsize=4)
def label_palette(lm: LabelMap) -> tuple[np.ndarray, np.ndarray]:
    """The labels of a map (increasing) and each one's index in :data:`LABEL_COLOURS` (any thread).

    Label v takes colour ``(v − 1) mod`` the palette, as many as it can; where a touching region (at a side
    or a corner) already has it, the first colour none of its neighbours has (a greedy colouring of the
    labels' adjacency, in increasing label order), so two neighbouring regions never read as one.
    Cached for the last few maps: the three views and the legend ask for the same one.
    """
    lab = lm.labels
    values = np.unique(lab[lab != 0]).astype(np.int64)
    n_col = len(LABEL_COLOURS)
    pairs = []
    for a, b in (
        (lab[:, 1:], lab[:, :-1]),
        (lab[1:, :], lab[:-1, :]),
        (lab[1:, 1:], lab[:-1, :-1]),
        (lab[1:, :-1], lab[:-1, 1:]),
    ):
        touch = (a != b) & (a != 0) & (b != 0)
        lo = np.minimum(a[touch], b[touch]).astype(np.int64)
        hi = np.maximum(a[touch], b[touch]).astype(np.int64)
        pairs.append(np.unique(lo << 32 | hi))
    keys = np.unique(np.concatenate(pairs)) if pairs else np.zeros(0, np.int64)
    lo_i = np.searchsorted(values, keys >> 32)
    hi_i = np.searchsorted(values, keys & 0xFFFFFFFF)
    neighbours: list[list[int]] = [[] for _ in range(values.size)]
    for i, j in zip(lo_i.tolist(), hi_i.tolist(), strict=True):
        neighbours[j].append(i)  # j > i: i is coloured first
    colour = np.empty(values.size, np.int64)
    for j in range(values.size):
        used = {int(colour[i]) for i in neighbours[j]}
        own = (int(values[j]) - 1) % n_col
        free = [k for k in range(n_col) if k not in used]
        colour[j] = own if own not in used or not free else free[0]
    return values, colour


def label_colour(lm: LabelMap, label: int) -> str:
    """The colour label ``label`` (non-zero) of ``lm`` is drawn with in every view (the legend's)."""
    values, colour = label_palette(lm)
    return LABEL_COLOURS[int(colour[np.searchsorted(values, label)])]


def label_lut(alpha: int) -> np.ndarray:
    """The table of a label image made by :func:`label_image`: entry k + 1 is colour k, 0 is transparent."""
    lut = np.zeros((len(LABEL_COLOURS) + 1, 4), dtype=np.uint8)
    for k, c in enumerate(LABEL_COLOURS):
        lut[k + 1] = [*qcolor(c).getRgb()[:3], alpha]
    return lut


def label_image(lm: LabelMap, lut: np.ndarray) -> tuple[np.ndarray, int, Any, np.ndarray]:
    """``(image, f, picture, full)``: the labels as colour indices, at a level of detail (any thread).

    ``full`` is the exact index image, which the views show cropped when zoomed in (:class:`MaskItem`).
    """
    lab = lm.labels
    values, colour = label_palette(lm)
    index = np.searchsorted(values, lab)  # a label's place among the map's labels (0 also lands on 0)
    full = np.where(lab > 0, colour[np.minimum(index, values.size - 1)] + 1, 0).astype(np.uint8)
    img, f, picture = pictured(lod_image(full), lut)
    return img, f, picture, full


def cells_drawing(cells: Any) -> tuple[list[StrokeLevel], QtGui.QPainterPath, np.ndarray]:
    """The 1-cells by size class (each one a component) and the 0-cells' points (any thread)."""
    lines = [chain_xy(c.chain) for c in cells.one_cells]
    levels = stroke_levels(*ring_groups(lines, np.arange(len(lines))))
    zero = np.array([z.point for z in cells.zero_cells], dtype=float).reshape(-1, 2) - 0.5
    return levels, levels_path(levels), zero


def subdivision_drawing(
    sd: Any, palette: tuple[np.ndarray, np.ndarray]
) -> tuple[list[tuple[int, QtGui.QPainterPath]], list[StrokeLevel], QtGui.QPainterPath]:
    """Each colour's parts as one fill path, and the shared polylines by size class (any thread).

    Every boundary between two regions is one polyline of the subdivision: it is stroked once, not once
    per part, so what is drawn is the coverage itself.
    """
    values, colour = palette
    by_colour: dict[int, list[np.ndarray]] = {}
    for label, part in sd.parts.items():
        k = int(colour[np.searchsorted(values, label)])
        by_colour.setdefault(k, []).extend(polygon_rings(part))
    fills = [(k, rings_path(rings)) for k, rings in sorted(by_colour.items())]
    # A 1-cell that meets no 0-cell is a ring, given without its closing point.
    zero = {z.point for z in sd.cells.zero_cells}
    lines = [
        np.vstack([p, p[:1]]) if c.chain.start not in zero else p
        for c, p in zip(sd.cells.one_cells, sd.polylines, strict=True)
    ]
    levels = stroke_levels(*ring_groups(lines, np.arange(len(lines))))
    return fills, levels, levels_path(levels)


class LabelLayer(Layer):
    """The items of a label map object in one view (each view uses those it needs)."""

    def __init__(self, obj_id: int) -> None:
        super().__init__(obj_id)
        self.image = MaskItem()
        self.image.setParentItem(self)
        self.fills = [PathItem() for _ in LABEL_COLOURS]
        for item in self.fills:
            item.setParentItem(self)
        self.lines = LodPathItem()
        self.lines.setParentItem(self)
        self.lines.setZValue(2)
        self.points = MarkersItem(6.0, "circle")
        self.points.setParentItem(self)
        self.points.setZValue(3)
        self.shown: Any = None  # the representation drawn
        self.key: Any = None  # the style it was drawn with


def draw_labels(view: Any, layer: LabelLayer, obj: Any, rep: str, selected: bool) -> bool:
    """Draw representation ``rep`` of a label map object in ``layer``; False while it is being prepared."""
    if rep == "analytical":  # none of its own: the view says so (RepresentationView.label_map_note)
        layer.setVisible(False)
        return True
    value = view.get(obj.id, rep)
    if value is None:
        return view.scene.error(obj.id, rep) is not None
    lm = obj.source
    dark = view.is_dark()
    base = obj.style.opacity + (0.25 if selected else 0.0)
    alpha = round(255 * min(1.0, base * (0.55 if rep == "region" else 1.0)))
    lut = label_lut(alpha)
    if value is not layer.shown:
        size = int(lm.labels.size)
        if rep == "discrete" or rep == "region":
            # Made once per label map; a new alpha (selection, opacity) only changes the table.
            img = view.prepared(obj.id, "labels", lm, size, lambda: label_image(lm, lut))
            if img is None:
                return False
            layer.image.set_pixels(img[0], lm.origin, lut, img[1], img[3], picture=img[2])
        if rep == "region":
            cells = view.prepared(obj.id, "cells", value, size, lambda: cells_drawing(value))
            if cells is None:
                return False
            layer.lines.set_levels(cells[0], cells[1])
            layer.points.set_points(cells[2])
        if rep == "euclidean":
            sub = view.prepared(
                obj.id, "subdivision", value, size, lambda: subdivision_drawing(value, label_palette(lm))
            )
            if sub is None:
                return False
            for item in layer.fills:
                item.setPath(QtGui.QPainterPath())
            for k, path in sub[0]:
                layer.fills[k].setPath(path)
            layer.lines.set_levels(sub[1], sub[2])
        layer.shown = value
    key = (alpha, dark, selected)
    if key != layer.key:
        layer.image.set_lut(lut)
        for k, item in enumerate(layer.fills):
            fill = qcolor(LABEL_COLOURS[k])
            fill.setAlphaF(min(1.0, base) * 0.75)
            item.set_style(fill, None)
        line = QtGui.QColor("#e8e8e8") if dark else QtGui.QColor("#1d1d1d")
        # A hairline, the selection told by colour: a one-pixel cosmetic pen is Qt's fast stroke (50× a
        # wider one), and a map of 10⁴ regions has 10⁶ boundary elements.
        layer.lines.set_style(None, QtGui.QColor("#d35400") if selected else line, 1.0)
        layer.points.set_colours(line, QtGui.QColor("#e15759"))
        layer.key = key
    layer.image.setVisible(rep in ("discrete", "region") and layer.image.image is not None)
    layer.lines.setVisible(rep in ("region", "euclidean"))
    layer.points.setVisible(rep == "region" and selected)
    for item in layer.fills:
        item.setVisible(rep == "euclidean")
    return True


#: What the analytical view says of a selected label map.
NO_SEGMENTS_NOTE = "label map: no segments of its own (Edit ▸ Split into Objects gives them per label)"

#: The legend line of a view showing a label map (with the views' own legends).
LABEL_LEGEND = {
    "discrete": "label map: one colour per label (Properties lists them)",
    "region": "label map: ━ 1-cell (boundary of two regions) · <span style='color:#e15759'>●</span> 0-cell",
    "euclidean": "label map: its gauss subdivision, each shared boundary one polyline",
}


def legend_rows(lm: LabelMap) -> list[tuple[int, str, int]]:
    """``(label, colour, pixels)`` of every label of a label map, by label (the Properties panel's legend)."""
    values, counts = np.unique(lm.labels, return_counts=True)
    return [(int(v), label_colour(lm, int(v)), int(n)) for v, n in zip(values, counts, strict=True) if v != 0]
