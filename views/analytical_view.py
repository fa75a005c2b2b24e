"""The analytical view: each boundary chain cut into digital straight segments (DSS), coloured alternately.

A segment is a run of pointels (pixel corners) of a crack chain; its *pixels* are the border pixels on the
left of its linels (inside the object). Both are drawn in alternating colours, with the segments' end
pointels marked. For the segment selected in the Segments table (or clicked here) the view adds its chosen
Euclidean line — the median line a·x − b·y = μ + (ω − 1)/2 — and the lines at the vertices of its preimage,
the extreme lines compatible with the segment.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np
from PySide6 import QtCore, QtGui

from mrm.document import DocObject
from mrm.views.base_view import Layer, RepresentationView
from mrm.views.canvas import LOD_PIXELS, MaskItem, lod_factor, lod_image, pictured, qcolor
from mrm.views.items import (
    LodPathItem,
    MarkersItem,
    PathItem,
    cosmetic_pen,
    levels_path,
    stroke_levels,
)
from mrm.views.palette import CHOSEN_SEGMENT_COLOUR

#: Alternating segment colours (and a third for the odd one out of a closed chain).
SEGMENT_COLOURS = ("#e15759", "#4e79a7", "#59a14f")


def pointel_xy(points: np.ndarray) -> np.ndarray:
    """Plane coordinates of pointels (pointel (i, j) is the point (i − ½, j − ½))."""
    return np.asarray(points, dtype=float) - 0.5


def segment_colour_index(k: int, n: int) -> int:
    """0/1 alternating; the last segment of an odd closed chain gets 2 so that neighbours always differ."""
    if n % 2 == 1 and k == n - 1 and n > 1:
        return 2
    return k % 2


def left_pixels(chain: Any) -> np.ndarray:
    """The pixel on the left of each linel of a chain (code 0 at pointel (i, j) → pixel (i, j), …)."""
    pts = np.asarray(chain.points())[:-1]
    codes = np.frombuffer(chain.codes.encode("ascii"), dtype=np.uint8).astype(np.int64) - 48
    lx = np.array([0, -1, -1, 0])
    ly = np.array([0, 0, -1, -1])
    return np.stack([pts[:, 0] + lx[codes], pts[:, 1] + ly[codes]], axis=1)


def segment_pixel_image(ana: Any, limit: int = LOD_PIXELS) -> tuple[np.ndarray, tuple[int, int], int] | None:
    """A label image of the border pixels: value 1 + colour index of the segment each pixel belongs to.

    ``(image, origin, f)``: at its level of detail (:func:`~mrm.views.canvas.lod_image`), f × f max-pooled
    beyond ``limit`` pixels. The pooled image is made from the border pixels themselves: the full-size image
    of a 10⁸-pixel object was 100 MB of fresh memory for a few million border pixels.
    """
    pix: list[np.ndarray] = []
    lab: list[np.ndarray] = []
    for chain in ana.chains:
        n = len(chain)
        if n == 0:
            continue
        left = left_pixels(chain)
        m = len(left)
        t = chain.table
        for k in range(n):
            first, last = int(t[k, 0]), int(t[k, 1])
            idx = np.arange(first, last) % m  # linels first .. last−1
            pix.append(left[idx])
            lab.append(np.full(len(idx), 1 + segment_colour_index(k, n), dtype=np.uint8))
    if not pix:
        return None
    p = np.concatenate(pix)
    v = np.concatenate(lab)
    x0, y0 = p.min(axis=0)
    x1, y1 = p.max(axis=0)
    h, w = int(y1 - y0 + 1), int(x1 - x0 + 1)
    ys, xs = p[:, 1] - y0, p[:, 0] - x0
    f = lod_factor(h * w, limit)
    if f > 1:
        # What pooling the full image gives: a pixel of two segments has the value written last, a block the
        # largest value of its pixels (written last, in ascending order).
        key = ys * w + xs
        last = len(key) - 1 - np.unique(key[::-1], return_index=True)[1]
        order = last[np.argsort(v[last], kind="stable")]
        ys, xs, v = ys[order] // f, xs[order] // f, v[order]
        h, w = -(-h // f), -(-w // f)
    img = np.zeros((h, w), dtype=np.uint8)
    img[ys, xs] = v
    return img, (int(x0), int(y0)), f


def segment_cracks(ana: Any) -> tuple[list[tuple[np.ndarray, ...]], np.ndarray, np.ndarray]:
    """The segments' crack polylines per colour index, each chain's extent, and every end pointel.

    Per colour, ``(xy, connect, chain)`` as :func:`~mrm.views.items.stroke_levels` takes them: each
    segment one polyline through its pointels, ``chain[i]`` the chain of point i (its component's stroke).
    Per chain, the longer side of its box (plane units, at least 1).
    """
    extents = np.ones(len(ana.chains))
    points: list[list[np.ndarray]] = [[], [], []]
    owner: list[list[np.ndarray]] = [[], [], []]
    ends: list[np.ndarray] = []
    for ci, chain in enumerate(ana.chains):
        n = len(chain)
        if n == 0:
            continue
        pts = pointel_xy(chain.points())
        m = len(pts) - 1
        extents[ci] = max(1.0, float((pts.max(axis=0) - pts.min(axis=0)).max()))
        t = chain.table
        for k in range(n):
            first, last = int(t[k, 0]), int(t[k, 1])
            p = pts[np.arange(first, last + 1) % m]
            colour = segment_colour_index(k, n)
            points[colour].append(p)
            owner[colour].append(np.full(len(p), ci, dtype=np.int64))
            ends.append(p[[0, -1]])
    out = []
    for ps, os in zip(points, owner, strict=True):
        if not ps:
            out.append((np.zeros((0, 2)), np.zeros(0, np.int32), np.zeros(0, np.int64)))
            continue
        lens = np.array([len(p) for p in ps])
        connect = np.ones(int(lens.sum()), dtype=np.int32)
        connect[np.cumsum(lens) - 1] = 0
        out.append((np.concatenate(ps), connect, np.concatenate(os)))
    return out, extents, (np.unique(np.concatenate(ends), axis=0) if ends else np.zeros((0, 2)))


def line_through_box(
    a: Fraction | float, b: Fraction | float, c: Fraction | float, box: tuple[float, float, float, float]
) -> np.ndarray | None:
    """The piece of the line a·x + b·y = c inside ``box`` (xmin, ymin, xmax, ymax): [[x1, y1], [x2, y2]]."""
    a, b, c = float(a), float(b), float(c)
    xmin, ymin, xmax, ymax = box
    pts = []
    if b != 0:
        for x in (xmin, xmax):
            y = (c - a * x) / b
            if ymin <= y <= ymax:
                pts.append((x, y))
    if a != 0:
        for y in (ymin, ymax):
            x = (c - b * y) / a
            if xmin <= x <= xmax:
                pts.append((x, y))
    if len(pts) < 2:
        return None
    pts_arr = np.array(sorted(set(pts)))
    return pts_arr[[0, -1]] if len(pts_arr) >= 2 else None


def preimage_lines(chain: Any, k: int) -> list[tuple[Fraction, Fraction, Fraction]]:
    """The lines (A, B, C) with A·x + B·y = C in plane coordinates at the vertices of segment k's preimage."""
    pre = chain.preimage(k)
    out = []
    for u, w in pre.vertices:
        A, B, C = pre.line(u, w)  # pointel coordinates: A·i + B·j = C, and i = x + ½, j = y + ½
        out.append((A, B, C - (A + B) / 2))
    return out


def border_lut(alpha: int) -> np.ndarray:
    """The table of the segments' border pixels: label 1 + k in segment colour k."""
    lut = np.zeros((4, 4), dtype=np.uint8)
    for k, c in enumerate(SEGMENT_COLOURS):
        lut[k + 1] = [*qcolor(c).getRgb()[:3], alpha]
    return lut


def analytical_drawing(ana: Any, lut: np.ndarray) -> tuple[Any, list[Any], np.ndarray]:
    """What the analytical view draws of an analytical representation (any thread).

    The border pixels come as a level-of-detail image with its picture through ``lut``. The cracks of each
    colour come by component size class (:func:`stroke_levels`): at fit-all zoom the thousands of tiny
    chains of a speckled object are dots, not a black field of strokes.
    """
    img = segment_pixel_image(ana)
    if img is not None:
        coarse, f, picture = pictured((img[0], img[2]), lut)
        img = (coarse, img[1], f, picture)
    polylines, extents, ends = segment_cracks(ana)
    # A chain's colours are split across the three items: its size class comes from all its points, so
    # the chain's segments switch between dots and strokes at the same zoom in every item.
    levels = []
    for xy, connect, owner in polylines:
        lv = stroke_levels(xy, connect, owner, extents=extents)
        levels.append((lv, levels_path(lv)))
    return img, levels, ends


class AnalyticalLayer(Layer):
    def __init__(self, obj_id: int) -> None:
        super().__init__(obj_id)
        self.body = MaskItem()
        self.body.setParentItem(self)
        self.border = MaskItem()
        self.border.setParentItem(self)
        self.cracks = [LodPathItem() for _ in SEGMENT_COLOURS]
        for c in self.cracks:
            c.setParentItem(self)
            c.setZValue(2)
        self.ends = MarkersItem(5.0, "square")
        self.ends.setParentItem(self)
        self.ends.setZValue(3)
        self.key: Any = None
        self.analytical: Any = None


class AnalyticalView(RepresentationView):
    name = "analytical"
    title = "Analytical"
    subtitle = "straight segments"
    rep = "analytical"

    def __init__(self, scene: Any, parent: Any = None) -> None:
        super().__init__(scene, parent)
        self.chosen = PathItem()
        self.extremes = PathItem()
        self.highlight = PathItem()
        for z, it in ((20_000, self.extremes), (20_001, self.chosen), (19_999, self.highlight)):
            it.setZValue(z)
            self.plane.vb.addItem(it, ignoreBounds=True)
        scene.segmentSelected.connect(lambda *_a: self.after_refresh())

    legend = (
        "<span style='color:#4e79a7'>━</span><span style='color:#e15759'>━</span> consecutive segments "
        "alternate colours · □ segment ends (selected object) · "
        f"<span style='color:{CHOSEN_SEGMENT_COLOUR}'>━</span> chosen segment · ━ its line · "
        "<span style='color:#9467bd'>╍</span> preimage bounds"
    )

    def make_layer(self, obj_id: int) -> Layer:
        return AnalyticalLayer(obj_id)

    def update_layer(self, layer: Layer, obj: DocObject, selected: bool) -> bool:
        assert isinstance(layer, AnalyticalLayer)
        ana = self.get(obj.id, "analytical")
        ps = self.get(obj.id, "discrete")
        if ana is None or ps is None:
            return (
                self.scene.error(obj.id, "analytical") or self.scene.error(obj.id, "discrete")
            ) is not None
        dark = self.is_dark()
        key = (ana, ps, obj.style.fill, dark, selected)
        if key == layer.key:
            return True
        lut = border_lut(150 if selected else 110)
        if ana is not layer.analytical:
            data = self.prepared(obj.id, "segments", ana, ps.mask.size, lambda: analytical_drawing(ana, lut))
            if data is None:
                return False  # prepared on a worker
            img, paths, ends = data
            if img is None:
                layer.border.set_pixels(None, (0, 0))
            else:
                layer.border.set_pixels(img[0], img[1], lut, img[2], picture=img[3])
            for item, (levels, path) in zip(layer.cracks, paths, strict=True):
                item.set_levels(levels, path)
            layer.ends.set_points(ends)
            layer.analytical = ana
        body = qcolor(obj.style.fill)
        body_lut = np.array([[0, 0, 0, 0], [*body.getRgb()[:3], 70 if selected else 45]])
        shown = self.prepared(
            obj.id, "body", ps, ps.mask.size, lambda: pictured(lod_image(ps.mask), body_lut)
        )
        if shown is None:
            return False
        layer.body.set_pixels(shown[0], ps.origin, body_lut, shown[1], picture=shown[2])
        layer.border.set_lut(lut)
        for item, c in zip(layer.cracks, SEGMENT_COLOURS, strict=True):
            item.set_style(
                None, qcolor(c).darker(115) if not dark else qcolor(c).lighter(120), 2.2 if selected else 1.6
            )
        line = QtGui.QColor("#f0f0f0") if dark else QtGui.QColor("#202020")
        layer.ends.set_colours(line, QtGui.QColor("#ffffff") if not dark else QtGui.QColor("#303030"))
        layer.ends.setVisible(selected)  # segment ends of the selected object only (not a black mass)
        layer.key = key
        return True

    def label_map_note(self) -> str | None:
        obj = self.scene.primary()
        if obj is None or obj.kind != "labels":
            return None
        from mrm.views.label_maps import NO_SEGMENTS_NOTE

        return NO_SEGMENTS_NOTE

    # ------------------------------------------------------------------ selected segment
    def after_refresh(self) -> None:
        obj_id, ci, k = self.scene.segment
        self.chosen.setPath(QtGui.QPainterPath())
        self.extremes.setPath(QtGui.QPainterPath())
        self.highlight.setPath(QtGui.QPainterPath())
        if obj_id < 0 or obj_id not in self.scene.doc:
            return
        ana = self.scene.entry(obj_id).peek("analytical")
        if ana is None or not (0 <= ci < len(ana.chains)) or not (0 <= k < len(ana.chains[ci])):
            return
        chain = ana.chains[ci]
        pts = pointel_xy(chain.segment_points(k))
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        pad = max(2.0, 0.25 * float(max(hi - lo)))
        box = (lo[0] - pad, lo[1] - pad, hi[0] + pad, hi[1] + pad)
        dark = self.is_dark()
        hl = QtGui.QPainterPath()
        hl.addPolygon(QtGui.QPolygonF([QtCore.QPointF(float(x), float(y)) for x, y in pts]))
        self.highlight.setPath(hl)
        self.highlight.setPen(cosmetic_pen(QtGui.QColor(CHOSEN_SEGMENT_COLOUR), 5.0))
        seg = chain.segments[k]
        if seg.a == 0 and seg.b == 0:
            return
        a, b, c = chain.euclidean_line(k)  # a·x − b·y = c
        piece = line_through_box(a, -b, c, box)
        path = QtGui.QPainterPath()
        if piece is not None:
            path.moveTo(*piece[0])
            path.lineTo(*piece[1])
        self.chosen.setPath(path)
        self.chosen.setPen(cosmetic_pen(QtGui.QColor("#ffffff") if dark else QtGui.QColor("#000000"), 1.8))
        ext = QtGui.QPainterPath()
        for A, B, C in preimage_lines(chain, k):
            piece = line_through_box(A, B, C, box)
            if piece is not None:
                ext.moveTo(*piece[0])
                ext.lineTo(*piece[1])
        self.extremes.setPath(ext)
        self.extremes.setPen(cosmetic_pen(QtGui.QColor("#9467bd"), 1.2, QtCore.Qt.PenStyle.DashLine))

    def segment_near(self, obj_id: int, x: float, y: float, radius: float) -> tuple[int, int] | None:
        """(chain, segment) whose cracks pass nearest to (x, y) within ``radius``, if any."""
        ana = self.scene.entry(obj_id).peek("analytical")
        if ana is None:
            return None
        best: tuple[float, int, int] | None = None
        for ci, chain in enumerate(ana.chains):
            pts = pointel_xy(chain.points())
            mid = (pts[:-1] + pts[1:]) / 2  # linel midpoints
            d = np.hypot(mid[:, 0] - x, mid[:, 1] - y)
            j = int(np.argmin(d))
            if d[j] > radius or (best is not None and d[j] >= best[0]):
                continue
            firsts = chain.table[:, 0]
            # Greedy segments cover the chain in order from first = 0; linel j lies in the last one starting
            # at or before it (for maximal segments, one of the segments holding it).
            k = int(np.searchsorted(firsts, j, side="right")) - 1
            if 0 <= k < len(chain):
                best = (float(d[j]), ci, k)
        return None if best is None else (best[1], best[2])
