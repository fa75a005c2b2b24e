"""Snapping to objects: the vertex or edge point of a visible object nearest to the cursor.

The polygon and vertex tools ask :class:`ObjectSnapper` where a clicked or dragged point goes (through
:meth:`mrm.views.tool_base.Tool.snapped`, which also applies the pixel-grid snapping of Shift and Ctrl first).
The targets are the Euclidean representations of the visible objects *as the document holds them* (a
polygon's source, a pixel object's continuation R(A) once computed, the parts of a label map's subdivision),
never the previews of a gesture in progress. A vertex within the radius beats any edge; a snapped vertex is
returned with its stored float64 coordinates, so that a vertex placed on it coincides with it exactly.

Each geometry gets a :class:`~mrm.views.geometry_edit.SnapIndex` the first time the cursor comes near its
bounds; one of more than :data:`SYNC_VERTICES` vertices is indexed on the task runner (it is not a target
until then), so the GUI thread never spends more than a few milliseconds on it.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
import shapely

from mrm.views import geometry_edit as ge

log = logging.getLogger(__name__)

#: Geometries with more vertices are indexed on a worker (about 15 ms per 50,000 vertices).
SYNC_VERTICES = 50_000


@dataclass(frozen=True)
class SnapTarget:
    """Where a point snapped: an object's vertex (its exact coordinates) or the nearest point of an edge."""

    kind: Literal["vertex", "edge"]
    x: float
    y: float
    obj_id: int


@dataclass(frozen=True)
class SnapExclusion:
    """What of an object must not attract the point being moved (its own vertex, the edges it drags along).

    ``moving``: the row (:func:`~mrm.views.geometry_edit.vertex_table`) of the vertex being dragged, whose
    two edges move with it; ``split``: the edge a vertex being inserted splits; ``geom``: the geometry these
    rows refer to (the object's shape when the drag began).
    """

    obj_id: int
    moving: int | None = None
    split: int | None = None
    geom: Any = field(default=None, compare=False)


class ObjectSnapper:
    """Finds snap targets among the visible objects of a :class:`~mrm.views.scene.Scene`."""

    def __init__(self, scene: Any) -> None:
        self.scene = scene
        self._revision = -1
        self._complete = False
        #: (object id, geometry) of every target geometry, and their bounds as one (n, 4) array.
        self._targets: list[tuple[int, shapely.Geometry]] = []
        self._bounds = np.zeros((0, 4))
        #: id(geometry) -> (geometry, its index or None while a worker builds it).
        self._indices: dict[int, tuple[shapely.Geometry, ge.SnapIndex | None]] = {}

    # ------------------------------------------------------------------ targets
    def _refresh(self) -> None:
        doc = self.scene.doc
        if doc.revision == self._revision and self._complete:
            return
        targets: list[tuple[int, shapely.Geometry]] = []
        complete = True
        for o in doc.plane_objects:
            if not o.style.visible:
                continue
            rep = doc.derived(o.id).peek("euclidean")  # never computed here: only what is ready
            if rep is None:
                complete = False  # a continuation still computing: looked for again at the next query
                continue
            parts = rep.parts.values() if hasattr(rep, "parts") else (rep,)  # a label map's subdivision
            targets.extend((o.id, g) for g in parts if g is not None and not g.is_empty)
        self._targets = targets
        self._bounds = shapely.bounds([g for _, g in targets]) if targets else np.zeros((0, 4))
        self._revision, self._complete = doc.revision, complete
        live = {id(g) for _, g in targets}
        self._indices = {k: v for k, v in self._indices.items() if k in live}

    def _index(self, obj_id: int, geom: shapely.Geometry) -> ge.SnapIndex | None:
        entry = self._indices.get(id(geom))
        if entry is not None and entry[0] is geom:
            return entry[1]
        runner = getattr(self.scene, "runner", None)
        if runner is None or int(shapely.get_num_coordinates(geom)) <= SYNC_VERTICES:
            index = ge.SnapIndex(geom)
            self._indices[id(geom)] = (geom, index)
            return index
        self._indices[id(geom)] = (geom, None)

        def done(index: ge.SnapIndex, g: shapely.Geometry = geom) -> None:
            cur = self._indices.get(id(g))
            if cur is not None and cur[0] is g:
                self._indices[id(g)] = (g, index)

        def failed(exc: BaseException, g: shapely.Geometry = geom) -> None:
            log.warning("no snapping to object %d: %s", obj_id, exc)
            self._indices.pop(id(g), None)

        runner.submit(
            f"snap-index:{id(geom)}",
            lambda _progress, g=geom: ge.SnapIndex(g),
            on_result=done,
            on_error=failed,
            label="Preparing to snap to a large object",
        )
        return self._indices[id(geom)][1]  # a synchronous runner has built it already

    # ------------------------------------------------------------------ queries
    def find(
        self, x: float, y: float, radius: float, exclude: SnapExclusion | None = None
    ) -> SnapTarget | None:
        """The vertex nearest to (x, y) within ``radius`` (plane units), else the nearest edge point; or None.

        ``exclude`` leaves out the vertex being dragged and the edges that move with it.
        """
        self._refresh()
        if not self._targets:
            return None
        b = self._bounds
        near = np.flatnonzero(
            (b[:, 0] <= x + radius)
            & (b[:, 2] >= x - radius)
            & (b[:, 1] <= y + radius)
            & (b[:, 3] >= y - radius)
        )
        found: list[tuple[int, ge.SnapIndex, SnapExclusion | None]] = []
        for k in near.tolist():
            obj_id, geom = self._targets[k]
            index = self._index(obj_id, geom)
            if index is not None and len(index):
                mine = exclude if exclude is not None and exclude.obj_id == obj_id else None
                if mine is not None and mine.geom is not None and geom is not mine.geom:
                    mine = None  # not the geometry the rows refer to (it changed since the drag began)
                found.append((obj_id, index, mine))
        best_v: tuple[float, int, float, float] | None = None
        for obj_id, index, mine in found:
            skip = () if mine is None or mine.moving is None else (mine.moving,)
            hit = index.nearest_vertex(x, y, radius, skip)
            if hit is not None and (best_v is None or hit[0] < best_v[0]):
                vx, vy = index.xy[hit[1]]
                best_v = (hit[0], obj_id, float(vx), float(vy))
        if best_v is not None:
            return SnapTarget("vertex", best_v[2], best_v[3], best_v[1])
        best_e: tuple[float, int, tuple[float, float]] | None = None
        for obj_id, index, mine in found:
            skip_e: tuple[int, ...] = ()
            if mine is not None and mine.moving is not None:
                skip_e = (mine.moving, int(index.prev[mine.moving]))
            elif mine is not None and mine.split is not None:
                skip_e = (mine.split,)
            hit_e = index.nearest_edge(x, y, radius, skip_e)
            if hit_e is not None and (best_e is None or hit_e[0] < best_e[0]):
                best_e = (hit_e[0], obj_id, hit_e[2])
        if best_e is not None:
            return SnapTarget("edge", best_e[2][0], best_e[2][1], best_e[1])
        return None
