"""The discrete view: every object's pixels, the selected one outlined along its crack boundary."""

from __future__ import annotations

import numpy as np
from PySide6 import QtGui

from mrm.core.grids import PixelSet
from mrm.document import DocObject
from mrm.views.base_view import Layer, RepresentationView
from mrm.views.canvas import MaskItem, lod_image, pictured, qcolor
from mrm.views.items import LodPathItem, crack_segments, segments_path
from mrm.views.region_view import boundary_levels


class DiscreteLayer(Layer):
    def __init__(self, obj_id: int) -> None:
        super().__init__(obj_id)
        self.mask = MaskItem()
        self.mask.setParentItem(self)
        self.outline = LodPathItem()
        self.outline.setParentItem(self)
        self.outline.setZValue(1)
        self.pixels: PixelSet | None = None
        self.outlined: PixelSet | None = None


class DiscreteView(RepresentationView):
    name = "discrete"
    title = "Discrete"
    subtitle = "pixels"
    rep = "discrete"

    _stroke_item: MaskItem | None = None
    _stroke_obj: int | None = None

    shows_ghosts = True
    legend = (
        "■ pixels in the object's colour · ▭ outline of the selected object · "
        "<span style='color:#9a9a9a'>■</span> grey: operation preview (not an object)"
    )

    def make_layer(self, obj_id: int) -> Layer:
        return DiscreteLayer(obj_id)

    def update_layer(self, layer: Layer, obj: DocObject, selected: bool) -> bool:
        assert isinstance(layer, DiscreteLayer)
        ps = self.get(obj.id, "discrete")
        if ps is None:
            return self.scene.error(obj.id, "discrete") is not None
        alpha = round(255 * (min(1.0, obj.style.opacity + 0.25) if selected else obj.style.opacity))
        lut = np.array([[0, 0, 0, 0], [*list(qcolor(obj.style.fill).getRgb()[:3]), alpha]])
        if ps is not layer.pixels or not np.array_equal(layer.mask._lut[:2], lut):
            shown = self.prepared(
                obj.id, "pixels", ps, ps.mask.size, lambda: pictured(lod_image(ps.mask), lut)
            )
            if shown is None:
                return False  # a coarser image of a big object is being made on a worker
            image, f, picture = shown
            layer.mask.set_pixels(image, ps.origin, lut, f, ps.mask, picture)
            layer.pixels = ps
        if selected:
            if layer.outlined is not ps and not self._outline(layer, obj.id, ps):
                return False
            layer.outline.set_style(None, self.highlight_colour(), 2.0)
            layer.outline.setVisible(True)
        else:
            layer.outline.setVisible(False)
        return True

    def _outline(self, layer: DiscreteLayer, obj_id: int, ps: PixelSet) -> bool:
        """Draw the crack boundary of the selected object's pixels; False while it is being prepared.

        From the region's boundary chains, by component size class with simplified outlines
        (:func:`~mrm.views.region_view.boundary_levels`): at fit-all zoom, specks are dots and a 10⁸-pixel
        outline is stroked with the corners the screen can show. The region is the one the region view
        draws (computed once for both). Without a region (its derivation failed or was cancelled), the
        merged crack pieces are stroked in full.
        """
        region = self.get(obj_id, "region")
        if region is None:
            if self.scene.error(obj_id, "region") is None:
                return False  # being computed: the pixels are shown meanwhile
            path = self.prepared(
                obj_id, "outline", ps, ps.mask.size, lambda: segments_path(crack_segments(ps.mask, ps.origin))
            )
            if path is None:
                return False
            layer.outline.setPath(path)
        else:
            data = self.prepared(obj_id, "outline", region, ps.mask.size, lambda: boundary_levels(region))
            if data is None:
                return False
            layer.outline.set_levels(*data)
        layer.outlined = ps
        return True

    # ------------------------------------------------------------------ brush fast path
    def show_stroke(
        self, obj_id: int | None, canvas: np.ndarray, origin: tuple[int, int], reshaped: bool
    ) -> None:
        """Show a stroke in progress: ``canvas`` replaces the object's pixels until :meth:`end_stroke`.

        The brush calls this on every dab; when the canvas keeps its shape only the image data is swapped,
        which is what keeps a dab on a 2048² object within a frame.
        """
        item = self._stroke_item
        if item is None or item.scene() is None:
            item = self._stroke_item = MaskItem()
            self.plane.vb.addItem(item)
            item.setZValue(10_000)
            reshaped = True
        if reshaped or self._stroke_obj != obj_id or item.image is None:
            colour = "#808080"
            alpha = 200
            if obj_id is not None and obj_id in self.scene.doc:
                o = self.scene.doc.get(obj_id)
                colour = o.style.fill
                alpha = round(255 * min(1.0, o.style.opacity + 0.25))
            lut = np.array([[0, 0, 0, 0], [*list(qcolor(colour).getRgb()[:3]), alpha]])
            item.set_pixels(canvas, origin, lut)
            self._stroke_obj = obj_id
            layer = self.layer(obj_id) if obj_id is not None else None
            if layer is not None:
                layer.setVisible(False)
        else:
            item.update_pixels(canvas)

    def hidden_while_editing(self, obj_id: int) -> bool:
        return obj_id == self._stroke_obj and self._stroke_item is not None

    def end_stroke(self) -> None:
        item = self._stroke_item
        if item is not None:
            self.plane.vb.removeItem(item)
            self._stroke_item = None
        if self._stroke_obj is not None and self._stroke_obj in self.scene.doc:
            self.mark_dirty(self._stroke_obj)
            layer = self.layer(self._stroke_obj)
            if layer is not None:
                layer.setVisible(self.scene.doc.get(self._stroke_obj).style.visible)
        self._stroke_obj = None

    def highlight_colour(self) -> QtGui.QColor:
        return QtGui.QColor("#ffb000") if self.is_dark() else QtGui.QColor("#d35400")
