"""The Euclidean view: every object's polygons; the selected one shows its vertices as handles."""

from __future__ import annotations

import numpy as np
import shapely
from PySide6 import QtCore, QtGui

from mrm.document import DocObject
from mrm.views.base_view import Layer, RepresentationView
from mrm.views.canvas import qcolor
from mrm.views.items import LodPathItem, MarkersItem, geometry_levels, levels_path, polygon_rings
from mrm.views.scene import Phantom


class EuclideanLayer(Layer):
    def __init__(self, obj_id: int) -> None:
        super().__init__(obj_id)
        self.polygon = LodPathItem()
        self.polygon.setParentItem(self)
        self.handles = MarkersItem(7.0, "square")
        self.handles.setParentItem(self)
        self.handles.setZValue(2)
        self.geometry: shapely.Geometry | None = None
        self.vertices = np.zeros((0, 2))


def ring_vertices(geom: shapely.Geometry) -> np.ndarray:
    """Every distinct vertex of the polygon rings (closing points left out), ring after ring."""
    rings = polygon_rings(geom)
    if not rings:
        return np.zeros((0, 2))
    return np.concatenate([r[:-1] if len(r) > 1 and (r[0] == r[-1]).all() else r for r in rings])


def _polygon_drawing(geom: shapely.Geometry) -> tuple[list, QtGui.QPainterPath, np.ndarray]:
    """Size classes of the polygons, their union path and the vertices (any thread)."""
    levels = geometry_levels(geom)
    return levels, levels_path(levels), ring_vertices(geom)


class EuclideanView(RepresentationView):
    name = "euclidean"
    title = "Euclidean"
    subtitle = "polygons"
    rep = "euclidean"

    shows_ghosts = True
    legend = (
        "polygons in the object's colour · □ vertices of the selected object · "
        "<span style='color:#9a9a9a'>╍</span> grey dashed: operation preview (not an object)"
    )

    def make_layer(self, obj_id: int) -> Layer:
        return EuclideanLayer(obj_id)

    def update_layer(self, layer: Layer, obj: DocObject, selected: bool) -> bool:
        assert isinstance(layer, EuclideanLayer)
        geom = self.get(obj.id, "euclidean")
        if geom is None:
            return self.scene.error(obj.id, "euclidean") is not None
        if geom is not layer.geometry:
            n = int(shapely.get_num_coordinates(geom))
            data = self.prepared(obj.id, "polygons", geom, n * 20, lambda: _polygon_drawing(geom))
            if data is None:
                return False  # prepared on a worker
            layer.polygon.set_levels(data[0], data[1])
            layer.geometry = geom
            layer.vertices = data[2]
        fill = qcolor(obj.style.fill)
        fill.setAlphaF(obj.style.opacity * (0.8 if selected else 0.6))
        stroke = (
            qcolor(obj.style.fill).darker(160) if not self.is_dark() else qcolor(obj.style.fill).lighter(140)
        )
        ghost = isinstance(obj, Phantom)
        layer.polygon.set_style(
            fill,
            stroke,
            obj.style.stroke_width + (0.8 if selected else 0.0),
            QtCore.Qt.PenStyle.DashLine if ghost else None,
        )
        if selected:
            layer.handles.set_points(layer.vertices)
            dark = self.is_dark()
            layer.handles.set_colours(
                QtGui.QColor("#f0f0f0") if dark else QtGui.QColor("#202020"),
                QtGui.QColor("#303030") if dark else QtGui.QColor("#ffffff"),
                QtGui.QColor("#ffb000"),
            )
            layer.handles.setVisible(True)
        else:
            layer.handles.setVisible(False)
        return True
