"""The region view: components in distinct colours, holes hatched, crack boundaries, junction pointels.

Outer boundaries are drawn solid and hole boundaries dashed, along the pixel sides (pointel (i, j) is the
Euclidean point (i − ½, j − ½)). Junctions are the pointels a boundary passes twice: where two pixels of the
object, or two pixels of a hole, touch only at a corner — the places where the (4, 8) topology decides.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from PySide6 import QtCore, QtGui

from mrm.document import DocObject
from mrm.views.base_view import Layer, RepresentationView
from mrm.views.canvas import LOD_PIXELS, MaskItem, lod_factor, pictured, qcolor
from mrm.views.items import LodPathItem, MarkersItem, StrokeLevel, levels_path, ring_groups, stroke_levels
from mrm.views.palette import COMPONENT_COLOURS


def hole_mask(mask: np.ndarray) -> np.ndarray:
    """Pixels of the bounded 8-components of the complement of ``mask`` (same shape as ``mask``)."""
    if mask.size == 0:
        return np.zeros_like(mask, dtype=bool)
    from mrm.geometry.topology.labeling import pooled_holes  # numba: loaded on first use, not at start-up

    return pooled_holes(mask.astype(bool, copy=False)).view(bool)


def chain_xy(chain: Any) -> np.ndarray:
    """The plane coordinates of a crack chain's pointels (pointel (i, j) is (i − ½, j − ½))."""
    return np.asarray(chain.points(), dtype=float) - 0.5


def junctions(chains: list[Any]) -> np.ndarray:
    """Pointels visited more than once by the boundary chains (closing points not counted)."""
    pts = [np.asarray(c.points())[:-1] for c in chains if len(c)]
    if not pts:
        return np.zeros((0, 2))
    allp = np.concatenate(pts).astype(np.int64)
    # One int64 key per pointel, then a 1-D unique: np.unique(axis=0) holds the GIL for its whole sort
    # (0.5 s at 20 M pixels, with the window frozen meanwhile); a plain sort releases it.
    lo = allp.min(axis=0)
    span = int(allp[:, 1].max() - lo[1]) + 1
    keys = (allp[:, 0] - lo[0]) * span + (allp[:, 1] - lo[1])
    uniq, counts = np.unique(keys, return_counts=True)
    rep = uniq[counts > 1]
    return np.stack([rep // span + lo[0], rep % span + lo[1]], axis=1).astype(float) - 0.5


def region_drawing(
    region: Any, component_lut: np.ndarray, hole_lut: np.ndarray, limit: int = LOD_PIXELS
) -> tuple[Any, Any, Any, Any, Any]:
    """What the region view draws of a region (any thread): labels, hole mask, boundary paths, junctions.

    The label and hole images come with their pictures through the given tables (:func:`pictured`).
    """
    from mrm.geometry.topology.labeling import pooled_holes, pooled_labels  # numba: loaded on first use

    data = region.labels.labels
    # Both images straight at their level of detail, in one pass each: at 10⁸ pixels the full-size label
    # arithmetic and the label image of the complement were 2 GB of temporaries, whose fresh memory cost
    # seconds of page faults on the cores the window shares. Labels beyond 255 cycle through the palette:
    # colour, not identity, is what is shown.
    f = lod_factor(data.size, limit)
    img = (pooled_labels(data, f), f) if data.size else (np.zeros((0, 0), np.uint8), 1)
    holes = (pooled_holes(data > 0, f), f) if data.size else (np.zeros((0, 0), np.uint8), 1)
    outer = [chain_xy(c.outer) for c in region.components]
    inner = [chain_xy(h.boundary) for c in region.components for h in c.holes]
    # By component size class (stroke_levels): thousands of tiny components are dots at fit-all zoom.
    outer_levels = stroke_levels(*ring_groups(outer, np.arange(len(outer))))
    inner_levels = stroke_levels(*ring_groups(inner, np.arange(len(inner))))
    return (
        pictured(img, component_lut),
        pictured(holes, hole_lut),
        (outer_levels, levels_path(outer_levels)),
        (inner_levels, levels_path(inner_levels)),
        junctions(list(region.boundary_chains)),
    )


def boundary_levels(region: Any) -> tuple[list[StrokeLevel], QtGui.QPainterPath]:
    """Every crack boundary of a region by component size class (any thread): the selected object's outline.

    A component's outer boundary and its holes' are one group (:func:`stroke_levels`), so a speck is a dot
    at fit-all zoom and a big component's outline is simplified as far as the screen cannot tell.
    """
    rings: list[np.ndarray] = []
    group: list[int] = []
    for k, c in enumerate(region.components):
        rings.append(chain_xy(c.outer))
        rings.extend(chain_xy(h.boundary) for h in c.holes)
        group.extend([k] * (1 + len(c.holes)))
    levels = stroke_levels(*ring_groups(rings, group))
    return levels, levels_path(levels)


def colour_distance(a: str, b: str) -> float:
    """Euclidean distance of two ``#rrggbb`` colours in RGB (0 … 441)."""
    ca, cb = qcolor(a), qcolor(b)
    return float(np.sqrt(sum((x - y) ** 2 for x, y in zip(ca.getRgb()[:3], cb.getRgb()[:3], strict=True))))


class RegionLayer(Layer):
    def __init__(self, obj_id: int) -> None:
        super().__init__(obj_id)
        self.components = MaskItem()
        self.components.setParentItem(self)
        self.holes = MaskItem()
        self.holes.setParentItem(self)
        self.outer = LodPathItem()
        self.outer.setParentItem(self)
        self.outer.setZValue(2)
        self.inner = LodPathItem()
        self.inner.setParentItem(self)
        self.inner.setZValue(2)
        self.junctions = MarkersItem(6.0, "circle")
        self.junctions.setParentItem(self)
        self.junctions.setZValue(3)
        self.region: Any = None
        self.key: Any = None


class RegionView(RepresentationView):
    name = "region"
    title = "Region"
    subtitle = "components, holes, cracks"
    rep = "region"

    def make_layer(self, obj_id: int) -> Layer:
        return RegionLayer(obj_id)

    legend = (
        "<span style='color:#4e79a7'>■</span><span style='color:#f28e2b'>■</span>"
        "<span style='color:#59a14f'>■</span> one colour per component · "
        "<span style='color:#969696'>■</span> hole · ━ outer boundary · ╍ hole boundary · "
        "<span style='color:#e15759'>●</span> junction (selected object)"
    )

    def component_lut(self, fill: str, alpha: int) -> np.ndarray:
        # The object's colour first, then the palette without the colours close to it (a blue object's
        # second component must not be another blue).
        cols = [fill, *[c for c in COMPONENT_COLOURS if colour_distance(c, fill) > 60]]
        lut = np.zeros((256, 4), dtype=np.uint8)
        for k in range(1, 256):
            lut[k] = [*list(qcolor(cols[(k - 1) % len(cols)]).getRgb()[:3]), alpha]
        return lut

    def update_layer(self, layer: Layer, obj: DocObject, selected: bool) -> bool:
        assert isinstance(layer, RegionLayer)
        region = self.get(obj.id, "region")
        if region is None:
            return self.scene.error(obj.id, "region") is not None
        dark = self.is_dark()
        alpha = round(255 * min(1.0, obj.style.opacity + (0.25 if selected else 0.0)))
        key = (region, obj.style.fill, alpha, dark, selected)
        if key == layer.key:
            return True
        if region is not layer.region:
            # The size from the pixels' box: reading region.labels here would paint the labels (seconds on a
            # big object) on the GUI thread.
            ps = self.get(obj.id, "discrete")
            size = ps.mask.size if ps is not None else 0
            lut = self.component_lut(obj.style.fill, alpha)
            hl = np.array([[0, 0, 0, 0], [150, 150, 150, 90] if not dark else [200, 200, 200, 70]])
            data = self.prepared(obj.id, "region", region, size, lambda: region_drawing(region, lut, hl))
            if data is None:
                return False  # prepared on a worker: the view says "computing…" meanwhile
            img, holes, outer, inner, junction_points = data
            lab = region.labels
            layer.components.set_pixels(img[0], lab.origin, lut, img[1], picture=img[2])
            layer.holes.set_pixels(holes[0], lab.origin, hl, holes[1], picture=holes[2])
            layer.outer.set_levels(*outer)
            layer.inner.set_levels(*inner)
            layer.junctions.set_points(junction_points)
            layer.region = region
        layer.components.set_lut(self.component_lut(obj.style.fill, alpha))
        line = QtGui.QColor("#e8e8e8") if dark else QtGui.QColor("#1d1d1d")
        width = 2.0 if selected else 1.2
        layer.outer.set_style(None, line, width)
        layer.inner.set_style(None, line, width, QtCore.Qt.PenStyle.DashLine)
        layer.junctions.set_colours(line, QtGui.QColor("#e15759"))
        layer.junctions.setVisible(selected)  # only the selected object's: many objects' dots are a blur
        layer.key = key
        return True
