"""The plane canvas shared by the four representation views.

A :class:`PlaneView` is a pyqtgraph PlotWidget whose ViewBox shows the plane with y up and a locked 1:1
aspect. Views are tied together by a :class:`Camera` (centre and screen pixels per plane unit) instead of
pyqtgraph's axis links, which fight the aspect lock when the views have different shapes: panning or zooming
one view moves the camera and every other view follows with its own size.

Pixel p = (x, y) covers the voxel [x−½, x+½]×[y−½, y+½]. :class:`MaskItem` draws a boolean ``mask[row, col]``
with origin (x0, y0) by placing the image at (x0−½, y0−½) with row-major axis order: image row r is drawn at
y0 + r, so a y-up view shows it the right way up without flipping any array.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pyqtgraph as pg
from PySide6 import QtCore, QtGui, QtWidgets

#: Screen pixels per plane unit allowed by zooming.
MIN_SCALE = 1e-3
MAX_SCALE = 400.0


def qcolor(c: str | QtGui.QColor | tuple[int, ...], alpha: int | None = None) -> QtGui.QColor:
    """A QColor from '#rrggbb', a QColor or a tuple, with an optional alpha override."""
    col = QtGui.QColor(c) if not isinstance(c, tuple) else QtGui.QColor(*c)
    if alpha is not None:
        col.setAlpha(alpha)
    return col


def rgba(c: str | QtGui.QColor, alpha: int = 255) -> tuple[int, int, int, int]:
    """(r, g, b, alpha) of a colour."""
    q = qcolor(c)
    return (q.red(), q.green(), q.blue(), alpha)


# ---------------------------------------------------------------------------------------------- camera
class Camera(QtCore.QObject):
    """Centre (plane coordinates) and scale (screen pixels per plane unit) shared by linked views."""

    changed = QtCore.Signal()

    def __init__(self, parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.cx = 0.0
        self.cy = 0.0
        self.scale = 8.0
        self._views: list[PlaneView] = []
        self._applying = False

    def add_view(self, view: PlaneView) -> None:
        self._views.append(view)
        view.vb.sigRangeChangedManually.connect(lambda *_a, v=view: self._from_view(v))
        view.vb.sigResized.connect(lambda *_a, v=view: self._apply_to(v))
        self._apply_to(view)

    def views(self) -> list[PlaneView]:
        return list(self._views)

    def set(self, cx: float, cy: float, scale: float) -> None:
        """Move every view to centre (cx, cy) at ``scale`` screen pixels per unit."""
        if not (math.isfinite(cx) and math.isfinite(cy) and math.isfinite(scale)) or scale <= 0:
            return
        self.cx, self.cy = float(cx), float(cy)
        self.scale = min(MAX_SCALE, max(MIN_SCALE, float(scale)))
        for v in self._views:
            self._apply_to(v)
        self.changed.emit()

    def zoom(self, factor: float, about: tuple[float, float] | None = None) -> None:
        """Multiply the scale by ``factor``, keeping the plane point ``about`` (default the centre) fixed."""
        new = min(MAX_SCALE, max(MIN_SCALE, self.scale * factor))
        if about is None:
            self.set(self.cx, self.cy, new)
            return
        ax, ay = about
        k = self.scale / new
        self.set(ax + (self.cx - ax) * k, ay + (self.cy - ay) * k, new)

    def fit(self, rect: tuple[float, float, float, float], margin: float = 0.06) -> None:
        """Show the plane rectangle (xmin, ymin, xmax, ymax) whole in every view."""
        xmin, ymin, xmax, ymax = rect
        w, h = max(xmax - xmin, 1.0), max(ymax - ymin, 1.0)
        scales = []
        for v in self._views:
            if not v.isVisible() and any(o.isVisible() for o in self._views):
                continue
            vw, vh = v.viewport_size()
            if vw > 4 and vh > 4:
                scales.append(min(vw / w, vh / h))
        scale = min(scales) if scales else 8.0
        self.set((xmin + xmax) / 2, (ymin + ymax) / 2, scale * (1 - 2 * margin))

    def _from_view(self, view: PlaneView) -> None:
        if self._applying:
            return
        r = view.vb.viewRect()
        vw, _vh = view.viewport_size()
        if r.width() <= 0 or vw <= 0:
            return
        self.cx, self.cy = r.center().x(), r.center().y()
        self.scale = min(MAX_SCALE, max(MIN_SCALE, vw / r.width()))
        for v in self._views:
            if v is not view:
                self._apply_to(v)
        self.changed.emit()

    def _apply_to(self, view: PlaneView) -> None:
        vw, vh = view.viewport_size()
        if vw <= 0 or vh <= 0:
            return
        hw, hh = vw / (2 * self.scale), vh / (2 * self.scale)
        self._applying = True
        try:
            view.vb.setRange(
                xRange=(self.cx - hw, self.cx + hw), yRange=(self.cy - hh, self.cy + hh), padding=0
            )
        finally:
            self._applying = False


# ---------------------------------------------------------------------------------------------- items
class PixelGridItem(pg.GraphicsObject):
    """Lines along the pixel sides (half-integers), drawn only when zoomed in far enough."""

    def __init__(self, threshold: float = 8.0) -> None:
        super().__init__()
        self.threshold = threshold
        self.enabled = True
        self._rect = QtCore.QRectF()
        self._colour = QtGui.QColor(128, 128, 128)
        self.setZValue(50)

    def set_colour(self, c: QtGui.QColor) -> None:
        self._colour = QtGui.QColor(c)
        self.update()

    def view_changed(self, rect: QtCore.QRectF) -> None:
        self.prepareGeometryChange()
        self._rect = QtCore.QRectF(rect)
        self.update()

    def boundingRect(self) -> QtCore.QRectF:
        return self._rect

    def screen_scale(self) -> float:
        """Screen pixels per plane unit (not ``scale``: that is QGraphicsItem's own)."""
        vb = self.getViewBox()
        if vb is None or self._rect.width() <= 0:
            return 0.0
        return float(vb.width()) / self._rect.width()

    def is_drawn(self) -> bool:
        """True when the grid is visible at the current zoom."""
        return self.enabled and self.isVisible() and self.screen_scale() >= self.threshold

    def paint(self, p: QtGui.QPainter, *_args: object) -> None:
        s = self.screen_scale()
        if not self.enabled or s < self.threshold:
            return
        r = self._rect
        # Fade in over one doubling of the zoom so the grid does not pop.
        fade = min(1.0, (s - self.threshold) / self.threshold + 0.35)
        col = QtGui.QColor(self._colour)
        col.setAlphaF(col.alphaF() * fade)
        pen = QtGui.QPen(col)
        pen.setCosmetic(True)
        pen.setWidthF(1.0)
        p.setPen(pen)
        p.setRenderHint(QtGui.QPainter.RenderHint.Antialiasing, False)
        x0 = math.floor(r.left() - 0.5) + 0.5
        y0 = math.floor(r.top() - 0.5) + 0.5
        nx = int(r.width()) + 2
        ny = int(r.height()) + 2
        lines = [QtCore.QLineF(x0 + i, r.top(), x0 + i, r.bottom()) for i in range(nx)]
        lines += [QtCore.QLineF(r.left(), y0 + j, r.right(), y0 + j) for j in range(ny)]
        p.drawLines(lines)


def full_lut(lut: np.ndarray) -> np.ndarray:
    """Pad an RGBA lookup table to 256 entries (transparent), so that value k is drawn with ``lut[k]``.

    pyqtgraph spreads a shorter table over the whole uint8 range when no levels are given.
    """
    lut = np.asarray(lut, dtype=np.uint8).reshape(-1, 4)[:256]
    out = np.zeros((256, 4), dtype=np.uint8)
    out[: lut.shape[0]] = lut
    return out


#: Images with more pixels are shown at a coarser level of detail (each shown pixel the union of f × f).
LOD_PIXELS = 4_000_000


def lod_factor(size: int, limit: int = LOD_PIXELS) -> int:
    """The pooling factor f of :func:`lod_image` for an image of ``size`` pixels (1: the image itself)."""
    return 1 if size <= limit else math.ceil(math.sqrt(size / limit))


def lod_image(data: np.ndarray, limit: int = LOD_PIXELS) -> tuple[np.ndarray, int]:
    """``(image, f)``: the image itself (f = 1), or its f × f max-pooled version (≤ ``limit`` pixels).

    Max-pooling keeps every object pixel visible (a thin line stays a line) and a label wins over background.
    Runs on any thread (the views call it on a worker for big objects).
    """
    f = lod_factor(data.size, limit)
    if f == 1:
        return data, 1
    return max_pool(data, f), f


def max_pool(data: np.ndarray, f: int) -> np.ndarray:
    """The f × f max-pooled image of ``data`` (bool or uint8; 0 beyond its edges; any thread).

    One pass of a compiled kernel without the GIL. The numpy version (a padded copy, then strided maxima)
    touched a full-size copy of the image: at 10⁸ pixels that fresh memory cost more than the maxima, on
    the cores the window shares.
    """
    if f == 1:
        return data.view(np.uint8) if data.dtype == np.bool_ else data
    from mrm.geometry.topology.labeling import max_pool as pool  # numba: loaded on first use

    return pool(data, f)


def opaque_lut(lut: np.ndarray) -> tuple[np.ndarray, float]:
    """``(table, opacity)``: a 256-entry lookup table with the one alpha of its visible entries taken out.

    When every visible entry of ``lut`` has the same alpha A (an object's colours at its opacity), the table
    comes back with those entries opaque, and A / 255 as the item's opacity: a picture made from it serves at
    every opacity (selecting an object changes the opacity, not the picture). Otherwise ``lut`` and 1.
    """
    table = full_lut(lut)
    alpha = table[:, 3]
    seen = np.unique(alpha[alpha > 0])
    if len(seen) != 1:
        return table, 1.0
    out = table.copy()
    out[alpha > 0, 3] = 255
    return out, float(seen[0]) / 255.0


@dataclass(frozen=True, eq=False)
class Picture:
    """A label image made ready to draw: ``qimage`` shows ``image`` (as given) through the table ``lut``.

    Made on any thread (:func:`make_picture`), so that a paint only draws it. The QImage wraps ``argb``,
    which this keeps alive.
    """

    image: np.ndarray
    lut: bytes
    argb: np.ndarray
    qimage: QtGui.QImage


#: Pictures of more pixels are made by a compiled lookup (:func:`make_picture`); smaller ones, which may be
#: made on the GUI thread, by numpy (no kernel to load there).
PICTURE_KERNEL_PIXELS = 1_000_000


def make_picture(image: np.ndarray, lut: np.ndarray) -> Picture:
    """The ``ARGB32_Premultiplied`` picture of a label image (bool or uint8) through ``lut`` (any thread).

    Made as :class:`MaskItem` draws it (:func:`opaque_lut`), so the item uses it as it is. It is one
    ``np.take`` from a 256-entry table, which releases the GIL: about 7 ms for 4 M pixels on a worker. Made
    on the GUI thread at paint time instead, the conversion took 6–12 ms per image, with several images in
    the one paint after a big object arrived.
    """
    img = image.view(np.uint8) if image.dtype == np.bool_ else image
    if img.dtype != np.uint8:
        img = img.astype(np.uint8)
    table, _opacity = opaque_lut(lut)
    a = table[:, 3].astype(np.uint32)
    premultiplied = (table[:, :3].astype(np.uint32) * a[:, None] + 127) // 255
    words = (a << 24) | (premultiplied[:, 0] << 16) | (premultiplied[:, 1] << 8) | premultiplied[:, 2]
    if img.size > PICTURE_KERNEL_PIXELS:  # on a worker: a compiled lookup, without an int64 copy of img
        from mrm.geometry.topology.labeling import lookup

        argb = lookup(words, img)
    else:
        argb = np.take(words, np.ascontiguousarray(img))
    h, w = argb.shape
    qimage = QtGui.QImage(argb.data, w, h, 4 * w, QtGui.QImage.Format.Format_ARGB32_Premultiplied)
    return Picture(image, table.tobytes(), argb, qimage)


def detail_picture(full: np.ndarray, box: tuple[int, int, int, int, int], lut: np.ndarray) -> Picture:
    """The picture of ``full[y0:y1, x0:x1]`` max-pooled g × g; ``box`` is (x0, x1, y0, y1, g) (any thread)."""
    x0, x1, y0, y1, g = box
    return make_picture(max_pool(full[y0:y1, x0:x1], g), lut)


def pictured(lod: tuple[np.ndarray, int], lut: np.ndarray) -> tuple[np.ndarray, int, Picture]:
    """A level-of-detail image ``(image, f)`` (:func:`lod_image`) with its picture (:func:`make_picture`)."""
    return lod[0], lod[1], make_picture(lod[0], lut)


class ArgbImageItem(pg.ImageItem):
    """An ImageItem whose picture is kept in the painter's own pixel format, or made beforehand.

    pyqtgraph renders a label image with a colour table as an ``Indexed8`` QImage; Qt then converts the whole
    image at every paint — 7 ms for a 2000² level-of-detail image, against 0.7 ms in
    ``ARGB32_Premultiplied``. Converted once per new image, a pan or zoom step draws it ten times faster.
    A :class:`Picture` made on a worker for the image and table shown is drawn as it is: nothing is
    converted on the GUI thread.
    """

    picture: Picture | None = None
    _pictured: np.ndarray | None = None  # the image array the picture was given for (setImage's own view)

    def render(self) -> None:
        pic = self.picture
        lut = self.lut
        if (
            pic is not None
            and self.image is not None
            and self.image is self._pictured
            and isinstance(lut, np.ndarray)
            and lut.tobytes() == pic.lut
        ):
            self.qimage = pic.qimage
            self._renderRequired = False
            self._unrenderable = False
            return
        super().render()
        q = self.qimage
        if q is not None and q.format() != QtGui.QImage.Format.Format_ARGB32_Premultiplied:
            self.qimage = q.convertToFormat(QtGui.QImage.Format.Format_ARGB32_Premultiplied)


class MaskItem(ArgbImageItem):
    """A label or boolean image placed on the pixel grid; label k is drawn with ``lut[k]`` (RGBA).

    A table whose visible entries share one alpha is drawn opaque at that opacity (:func:`opaque_lut`).
    """

    def __init__(self) -> None:
        super().__init__(axisOrder="row-major")
        self._origin = (0, 0)
        self._lut: np.ndarray = full_lut(np.array([[0, 0, 0, 0], [0, 0, 0, 255]]))
        self._table, self._opacity = opaque_lut(self._lut)
        self.scale_factor = 1
        self._full: np.ndarray | None = None  # the exact image behind a coarse one
        self._detail: ArgbImageItem | None = None  # its visible part, when zoomed in enough
        self._detail_box: tuple[int, int, int, int, int] | None = None  # what the detail shows or will
        # Pixels must stay sharp squares at every zoom.
        self.setAutoDownsample(False)

    def set_pixels(
        self,
        data: np.ndarray | None,
        origin: tuple[int, int],
        lut: np.ndarray | None = None,
        scale: int = 1,
        full: np.ndarray | None = None,
        picture: Picture | None = None,
    ) -> None:
        """Show ``data[row, col]`` (bool or small ints) with pixel (x0 + col, y0 + row) on its voxel.

        With ``scale`` f > 1, ``data`` is a level-of-detail image (:func:`lod_image`): each pixel covers
        f × f pixels of the plane, and ``full`` (the image itself) is shown exactly, cropped to the view, as
        soon as the visible part of it has at most :data:`LOD_PIXELS` pixels: zoomed in, every pixel is true.
        ``picture`` is ``data`` made ready to draw on a worker (:func:`make_picture`): it is drawn when it
        was made with the table shown, and the paint converts ``data`` itself otherwise.
        """
        self.scale_factor = scale
        if full is not self._full:
            self._hide_detail()  # it shows pixels that are no more
        self._full = full if scale > 1 else None
        if lut is not None:
            self._set_table(lut)
        if data is None or data.size == 0:
            self.picture = None
            self.clear()
            self.setVisible(False)
            self.update_detail()  # hides the exact detail of a previous coarse image
            return
        self.setVisible(True)
        img = data.view(np.uint8) if data.dtype == np.bool_ else data
        if img.dtype != np.uint8:
            img = img.astype(np.uint8)
        self._origin = (int(origin[0]), int(origin[1]))
        self.setImage(img, autoLevels=False, levels=None, lut=self._table)
        # A picture of this very array (not of an earlier one) is drawn instead of a conversion.
        self.picture = picture if picture is not None and picture.image is data else None
        self._pictured = self.image if self.picture is not None else None
        h, w = img.shape
        self.setRect(QtCore.QRectF(self._origin[0] - 0.5, self._origin[1] - 0.5, w * scale, h * scale))
        self.update_detail()

    def _set_table(self, lut: np.ndarray) -> None:
        self._lut = full_lut(lut)
        self._table, self._opacity = opaque_lut(self._lut)
        self.setOpacity(self._opacity)
        detail = getattr(self, "_detail", None)
        if detail is not None:
            detail.setOpacity(self._opacity)

    def viewRangeChanged(self) -> None:
        super().viewRangeChanged()
        self.update_detail()

    def update_detail(self) -> None:
        """Show the exact pixels of the visible part of a coarse (level-of-detail) image, as the screen can.

        Needed once a coarse pixel (f × f) covers two screen pixels or more. The detail image is the view's
        part of the exact image widened by a quarter of the view on each side (a pan inside that margin
        costs nothing), max-pooled g × g with the smallest g that covers a screen pixel (so at most 2.25
        times the view's own pixels), and made ready to draw (:func:`detail_picture`) on the view's task
        runner: cropping and converting millions of pixels at every zoom step stalled the window. Until it
        arrives the
        coarse image and the previous detail stay drawn; both are true where they show.
        """
        full = getattr(self, "_full", None)
        vb = self.getViewBox() if full is not None else None
        if full is None or vb is None or not self.isVisible():
            self._hide_detail()
            return
        r = vb.viewRect()
        px = float(vb.width()) / r.width() if r.width() > 0 else 0.0
        # Pooled g × g with g screen pixels at least: a pixel drawn smaller than a screen pixel may be skipped
        # (a one-pixel line would vanish), a pooled one never is.
        g = max(1, math.ceil(1.0 / px - 1e-9)) if px > 0 else self.scale_factor
        if g >= self.scale_factor:
            self._hide_detail()  # the coarse image is as fine as the screen can show
            return
        ox, oy = self._origin[0] - 0.5, self._origin[1] - 0.5
        h, w = full.shape
        left, right = r.left() - ox, r.right() - ox
        bottom, top = min(r.top(), r.bottom()) - oy, max(r.top(), r.bottom()) - oy
        seen = (
            max(0, math.floor(left)),
            min(w, math.ceil(right)),
            max(0, math.floor(bottom)),
            min(h, math.ceil(top)),
        )
        if seen[1] <= seen[0] or seen[3] <= seen[2]:
            return  # the image is out of view: whatever detail there is stays as it is
        shown = self._detail_box
        if (
            shown is not None
            and shown[4] == g
            and shown[0] <= seen[0]
            and seen[1] <= shown[1]
            and shown[2] <= seen[2]
            and seen[3] <= shown[3]
        ):
            return  # a pan inside the margin, or a change of another view's range
        mx, my = (right - left) / 4, (top - bottom) / 4
        box = (
            max(0, math.floor((left - mx) / g) * g),
            min(w, math.ceil(right + mx)),
            max(0, math.floor((bottom - my) / g) * g),
            min(h, math.ceil(top + my)),
            g,
        )
        self._detail_box = box
        table = self._table
        view = self.getViewWidget()
        runner = getattr(view, "runner", None)
        if runner is None:
            self._show_detail(full, box, detail_picture(full, box, table))
            return
        runner.submit(
            f"detail:{getattr(view, 'name', '')}:{id(self)}",
            lambda _p: detail_picture(full, box, table),
            on_result=lambda shown, full=full, box=box: self._show_detail(full, box, shown),
        )

    def _hide_detail(self) -> None:
        self._detail_box = None
        detail = getattr(self, "_detail", None)
        if detail is not None and detail.isVisible():
            detail.setVisible(False)
            self.update()  # the coarse image was clipped around it

    def _show_detail(self, full: np.ndarray, box: tuple[int, int, int, int, int], shown: Picture) -> None:
        """Draw a detail picture made for ``box`` of ``full``, if that is still what is wanted."""
        if full is not self._full or box != self._detail_box:
            return  # a newer image or view asked for another part
        detail = getattr(self, "_detail", None)
        if detail is None:
            detail = self._detail = ArgbImageItem(axisOrder="row-major")
            detail.setAutoDownsample(False)
            detail.setParentItem(self.parentItem())
            detail.setOpacity(self._opacity)
        detail.setZValue(self.zValue() + 0.01)
        detail.setImage(shown.image, autoLevels=False, levels=None, lut=self._table)
        detail.picture = shown
        detail._pictured = detail.image
        x0, _x1, y0, _y1, g = box
        h, w = shown.image.shape
        ox, oy = self._origin[0] - 0.5, self._origin[1] - 0.5
        detail.setRect(QtCore.QRectF(ox + x0, oy + y0, w * g, h * g))
        detail.setVisible(True)
        self.update()

    def paint(self, p: QtGui.QPainter, *args: object) -> None:
        detail = getattr(self, "_detail", None)
        if detail is not None and detail.isVisible():
            # Under the exact pixels nothing of the coarse image may show: a pixel the detail leaves
            # transparent (a thin gap, a hole) is one the coarse image fills.
            inside = self.mapRectFromItem(detail, detail.boundingRect())
            keep = QtGui.QPainterPath()
            keep.addRect(self.boundingRect())
            cut = QtGui.QPainterPath()
            cut.addRect(inside)
            p.setClipPath(keep.subtracted(cut), QtCore.Qt.ClipOperation.IntersectClip)
        super().paint(p, *args)

    def detach(self) -> None:
        """Remove the exact-detail image (a sibling item) from the view: call before removing this item."""
        detail = getattr(self, "_detail", None)
        if detail is not None:
            detail.setParentItem(None)
            if detail.scene() is not None:
                detail.scene().removeItem(detail)
            self._detail = None

    def update_pixels(self, data: np.ndarray) -> None:
        """Replace the image data in place (same shape and origin): the brush's fast path."""
        img = data.view(np.uint8) if data.dtype == np.bool_ else data
        self.updateImage(img)

    def set_lut(self, lut: np.ndarray) -> None:
        new = full_lut(lut)
        if np.array_equal(new, self._lut):
            return
        old_table = self._table
        self._set_table(new)
        if np.array_equal(old_table, self._table):
            return  # only the opacity changed: the picture stays
        if self.image is not None:
            self.setLookupTable(self._table)
        detail = getattr(self, "_detail", None)
        if detail is not None and detail.image is not None:
            detail.setLookupTable(self._table)  # converted by its paint until its new picture arrives
            self._detail_box = None
            self.update_detail()


# ---------------------------------------------------------------------------------------------- view
class PlaneViewBox(pg.ViewBox):
    """A ViewBox with y up, 1:1 aspect, no pyqtgraph context menu, and zoom limits."""

    def __init__(self) -> None:
        super().__init__(invertY=False, lockAspect=True, enableMenu=False)
        self.setMouseMode(pg.ViewBox.PanMode)
        self.setDefaultPadding(0.0)
        self.disableAutoRange()

    def updateViewRange(self, forceX: bool = False, forceY: bool = False) -> None:
        super().updateViewRange(forceX, forceY)
        # pyqtgraph applies a new range to the items' transform lazily, in the next paint (prepareForPaint):
        # the scene then changes while it is being painted, and Qt paints the whole view a second time.
        # Applied now, a zoom or pan step costs one paint per view, not two.
        self.updateMatrix()

    def wheelEvent(self, ev: object, axis: int | None = None) -> None:
        # Zoom about the cursor on both axes only (an axis-only zoom would break the 1:1 aspect).
        super().wheelEvent(ev, None)


def tick_step(span: float, pixels: float, spacing: float = 70.0) -> float:
    """The 1·10ᵏ, 2·10ᵏ or 5·10ᵏ step that puts a tick about every ``spacing`` screen pixels."""
    if not (span > 0 and pixels > 0 and math.isfinite(span)):
        return 1.0
    raw = span * spacing / pixels
    k = math.floor(math.log10(raw))
    for m in (1.0, 2.0, 5.0, 10.0):
        if m * 10.0**k >= raw:
            return m * 10.0**k
    return 10.0 ** (k + 1)


def tick_text(v: float, step: float) -> str:
    """A tick label with as many decimals as the step needs (no ``-0``)."""
    decimals = max(0, -math.floor(math.log10(step))) if step < 1 else 0
    text = f"{v:.{decimals}f}"
    return "0" if text.strip("-0.") == "" else text


class PlaneAxis(pg.AxisItem):
    """A left or bottom axis drawn directly, in a few calls.

    pyqtgraph's axis regenerates a QPicture of its ticks at every range change and plays it back: 11 ms per
    view and per paint, two thirds of a view's paint during a zoom of a 10⁸-pixel object (ADR 0025). This
    one computes one level of round ticks (:func:`tick_step`) and draws lines and labels straight away.
    """

    def paint(self, p: QtGui.QPainter, *_args: object) -> None:
        r0, r1 = (float(v) for v in self.range)
        # The widget's own rectangle (pyqtgraph's bounding one reaches into the plot by the tick length).
        size = self.size()
        rect = QtCore.QRectF(0.0, 0.0, size.width(), size.height())
        horizontal = self.orientation in ("bottom", "top")
        length = rect.width() if horizontal else rect.height()
        if not (r1 > r0) or length <= 0:
            return
        step = tick_step(r1 - r0, length)
        first = math.ceil(r0 / step)
        last = math.floor(r1 / step)
        if last - first > 200:
            return
        scale = length / (r1 - r0)
        tick = 5.0
        p.setPen(self.pen())
        if horizontal:
            p.drawLine(QtCore.QPointF(rect.left(), rect.top()), QtCore.QPointF(rect.right(), rect.top()))
        else:
            p.drawLine(QtCore.QPointF(rect.right(), rect.top()), QtCore.QPointF(rect.right(), rect.bottom()))
        font = self.style.get("tickFont")
        if font is not None:
            p.setFont(font)
        fm = QtGui.QFontMetricsF(p.font())
        lines = []
        labels = []
        for k in range(first, last + 1):
            v = k * step
            if horizontal:
                x = rect.left() + (v - r0) * scale
                lines.append(QtCore.QLineF(x, rect.top(), x, rect.top() + tick))
            else:
                y = rect.bottom() - (v - r0) * scale
                lines.append(QtCore.QLineF(rect.right() - tick, y, rect.right(), y))
            labels.append((v, lines[-1]))
        p.drawLines(lines)
        p.setPen(self.textPen())
        off = float(self.style.get("tickTextOffset", [3, 3])[0 if horizontal else 1] or 3)
        for v, ln in labels:
            text = tick_text(v, step)
            w = fm.horizontalAdvance(text)
            if horizontal:
                x = ln.x1() - w / 2
                if x < rect.left() - 1 or x + w > rect.right() + 1:
                    continue
                p.drawText(QtCore.QPointF(x, rect.top() + tick + off + fm.ascent()), text)
            else:
                y = ln.y1() + fm.ascent() / 2 - 1
                if y - fm.ascent() < rect.top() - 1 or y > rect.bottom() + 1:
                    continue
                p.drawText(QtCore.QPointF(rect.right() - tick - off - w, y), text)


class PlaneView(pg.PlotWidget):
    """One view of the plane; forwards mouse and key events in plane coordinates to the active tool.

    Signals
    -------
    cursorMoved(float, float)
        The cursor's plane coordinates (NaN, NaN when it leaves the view).
    """

    cursorMoved = QtCore.Signal(float, float)

    def __init__(self, name: str, parent: QtWidgets.QWidget | None = None) -> None:
        vb = PlaneViewBox()
        axes = {side: PlaneAxis(side) for side in ("left", "bottom")}
        super().__init__(parent=parent, viewBox=vb, axisItems=axes)
        self.vb = vb
        self.setObjectName(f"view_{name}")
        self.name = name
        #: Where the items of this view prepare pictures off the GUI thread (a TaskRunner; None: at once).
        self.runner: Any = None
        pi = self.getPlotItem()
        pi.hideButtons()
        pi.setMenuEnabled(False)
        for side in ("left", "bottom"):
            ax = pi.getAxis(side)
            # Fixed axis sizes: an axis that widened with its tick labels would shift the plot area, and the
            # whole picture with it, under the cursor.
            ax.setStyle(tickTextOffset=3, autoExpandTextSpace=False, autoReduceTextSpace=False)
        pi.getAxis("left").setWidth(44)
        pi.getAxis("bottom").setHeight(24)
        pi.showAxis("left")
        pi.showAxis("bottom")
        pi.layout.setContentsMargins(2, 2, 6, 2)
        self.grid = PixelGridItem()
        self.vb.addItem(self.grid, ignoreBounds=True)
        self.vb.sigRangeChanged.connect(lambda *_a: self.grid.view_changed(self.vb.viewRect()))
        self.setMouseTracking(True)
        self.viewport().setMouseTracking(True)
        self.viewport().installEventFilter(self)
        self.tool_handler: Callable[[PlaneView, QtCore.QEvent], bool] | None = None
        self.setFocusPolicy(QtCore.Qt.FocusPolicy.StrongFocus)
        self.apply_palette()

    # ------------------------------------------------------------------ geometry
    def viewport_size(self) -> tuple[float, float]:
        """Width and height, in screen pixels, of the ViewBox (the plot area)."""
        return float(self.vb.width()), float(self.vb.height())

    def pixels_per_unit(self) -> float:
        """Screen pixels per plane unit (not ``scale``: that is QGraphicsView's own)."""
        r = self.vb.viewRect()
        return float(self.vb.width()) / r.width() if r.width() > 0 else 0.0

    def map_to_plane(self, pos: QtCore.QPointF | QtCore.QPoint) -> tuple[float, float]:
        """Viewport widget coordinates → plane coordinates."""
        sp = self.mapToScene(pos.toPoint() if isinstance(pos, QtCore.QPointF) else pos)
        p = self.vb.mapSceneToView(QtCore.QPointF(sp))
        return float(p.x()), float(p.y())

    def map_from_plane(self, x: float, y: float) -> QtCore.QPoint:
        """Plane coordinates → viewport widget coordinates (rounded to the nearest pixel)."""
        sp = self.vb.mapViewToScene(QtCore.QPointF(x, y))
        return self.mapFromScene(sp)

    # ------------------------------------------------------------------ appearance
    def apply_palette(self) -> None:
        pal = self.palette()
        base = pal.color(QtGui.QPalette.ColorRole.Base)
        text = pal.color(QtGui.QPalette.ColorRole.Text)
        self.setBackground(base)
        for side in ("left", "bottom"):
            ax = self.getPlotItem().getAxis(side)
            ax.setPen(pg.mkPen(qcolor(text, 110)))
            ax.setTextPen(pg.mkPen(qcolor(text, 170)))
        dark = base.lightness() < 128
        self.grid.set_colour(QtGui.QColor(255, 255, 255, 60) if dark else QtGui.QColor(0, 0, 0, 45))

    def changeEvent(self, ev: QtCore.QEvent) -> None:
        if getattr(self, "grid", None) is not None and ev.type() in (
            QtCore.QEvent.Type.PaletteChange,
            QtCore.QEvent.Type.ApplicationPaletteChange,
        ):
            self.apply_palette()
        super().changeEvent(ev)

    def is_dark(self) -> bool:
        return self.palette().color(QtGui.QPalette.ColorRole.Base).lightness() < 128

    # ------------------------------------------------------------------ events
    def eventFilter(self, obj: QtCore.QObject, ev: QtCore.QEvent) -> bool:
        t = ev.type()
        if t == QtCore.QEvent.Type.MouseMove:
            assert isinstance(ev, QtGui.QMouseEvent)
            x, y = self.map_to_plane(ev.position())
            self.cursorMoved.emit(x, y)
        elif t == QtCore.QEvent.Type.Leave:
            self.cursorMoved.emit(math.nan, math.nan)
        if self.tool_handler is not None and t in (
            QtCore.QEvent.Type.MouseButtonPress,
            QtCore.QEvent.Type.MouseButtonRelease,
            QtCore.QEvent.Type.MouseMove,
            QtCore.QEvent.Type.MouseButtonDblClick,
            QtCore.QEvent.Type.Leave,
        ):
            return self.tool_handler(self, ev)
        return False

    def event(self, ev: QtCore.QEvent) -> bool:
        # Keys a tool is using (Enter, Esc, Backspace, Delete) must reach it before window shortcuts.
        if (
            ev.type() == QtCore.QEvent.Type.ShortcutOverride
            and getattr(self, "tool_handler", None) is not None
        ) and self.tool_handler(self, ev):
            ev.accept()
            return True
        return super().event(ev)

    def keyPressEvent(self, ev: QtGui.QKeyEvent) -> None:
        if self.tool_handler is not None and self.tool_handler(self, ev):
            ev.accept()
            return
        super().keyPressEvent(ev)

    def keyReleaseEvent(self, ev: QtGui.QKeyEvent) -> None:
        if self.tool_handler is not None and self.tool_handler(self, ev):
            ev.accept()
            return
        super().keyReleaseEvent(ev)
