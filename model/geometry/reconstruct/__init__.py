"""The reversible continuation R: pixel set → polygons with D(R(A)) = A exactly (docs/design.md §3).

For every finite pixel set A, :func:`reconstruct` returns a valid shapely Polygon or MultiPolygon (an
empty Polygon for ∅) with dyadic float64 coordinates such that

1. its polygons are the 4-connected components of A and its holes the bounded 8-connected components of
   the complement; under ``standard`` and ``supercover`` R(A) ⊂ V(A); under ``gauss`` ∂R(A) separates the
   centres of A from the other centres strictly and stays within the voxels of the border pixels on either
   side (docs/design.md §3 item 2, revised);
2. D(R(A)) = A exactly for the chosen model; under ``standard`` and ``supercover`` the same polygons serve
   both (∂R(A) crosses between pixels only through open sides shared by two pixels of A, crosses every
   border pixel through its open square and keeps every outside centre out); under ``gauss`` every centre
   of A is strictly inside and every other centre strictly outside;
3. no vertex or edge sits where a tie rule of the model decides (pixel corners and sides under the cover
   models, pixel centres under ``gauss``), so a rotation by a multiple of 90° about a pixel centre is exact;
4. R(A + t) = R(A) + t for t ∈ Z² (up to |coordinates| ≤ 2⁴⁰, :data:`COORD_LIMIT`), and the same A always
   gives the same output;
5. few vertices: about one per greedy digital straight segment of the boundary, in every model.

How (docs/algorithms.md §3.5, "V4"): each crack ring gives a corridor of pieces and gates (:mod:`.border`);
the reach of one straight line from every piece is computed exactly (arithmetic standard-DSS recognition on
full pieces, an exact preimage elsewhere) with a central line per window; consecutive chosen lines meet inside
a piece of their overlap, or a two-vertex patch joins them; every vertex is snapped to the coarsest dyadic
grid that keeps all constraints, and every ring is verified exactly. A failing stretch is replaced locally by
the safety net of the corridor, never the whole result.

The cover models use the border pixels' squares as pieces (:mod:`._kernels`). ``gauss`` uses
the *dual* corridor (:mod:`._dual`, ADR 0012): the open unit squares whose corners are the four
pixel centres around each pointel of the crack ring, joined by the open segments between the centres on
either side of each linel. It holds no pixel centre, so a ring that follows it winds once around the
centres of A and never around the others; it is the cover corridor shifted by half a pixel, so the same
pipeline runs on it, and consecutive lines meet across pixel sides where the cover models could not.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from itertools import pairwise
from typing import TYPE_CHECKING, Any, NamedTuple, overload

import numpy as np
import numpy.typing as npt
import shapely
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import ParameterError
from mrm.core.grids import PixelSet, VoxelSet
from mrm.core.limits import check_reconstruct
from mrm.core.models import Model
from mrm.core.progress import ProgressLike
from mrm.geometry._threads import side_pool
from mrm.geometry._threads import threads as _threads
from mrm.geometry.reconstruct import _dual as _dk
from mrm.geometry.reconstruct import _kernels as _k
from mrm.geometry.reconstruct import _twins as _tw
from mrm.geometry.topology.cracks import trace_mask
from mrm.reps.region import CrackChain

if TYPE_CHECKING:
    from mrm.geometry.polyhedra import Polyhedron

logger = logging.getLogger(__name__)

#: How many times the 3D R fell back to the safety net in this process (the tests hold it at 0).
FALLBACKS = [0]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

#: Names of the vertex sources in :class:`RingDetail`.
SOURCE_NAMES = {
    _k.SRC_LINES: "lines",
    _k.SRC_PATCH: "patch",
    _k.SRC_SPLICE: "splice",
    _k.SRC_NET: "net",
    _k.SRC_SINGLE: "single",
}

#: Names of the ring statuses in :class:`RingDetail`.
STATUS_NAMES = {
    _k.RING_V4: "v4",
    _k.RING_PARTIAL: "partial",
    _k.RING_NET: "net",
    _k.RING_SINGLE: "single",
}


@dataclass(frozen=True)
class _Run:
    # Everything the four kernel phases produce for one pixel set (array coordinates, Q-units).
    rings: Any
    corridor: _k.Corridors
    reach: IntArray
    lines: FloatArray
    xy: FloatArray
    roff: IntArray
    status: IntArray
    src: IntArray
    win: IntArray


#: The finest snapping grid: vertices are origin + k / 2^(K+2) with K <= this (twelve fractional bits).
#: It does not depend on where A lies, so R(A + t) = R(A) + t exactly (the kernels work relative to A's
#: own array); on the test images and random sets no vertex needs more (K = 20 gives the same polygons).
KCAP = 10

#: The largest |pixel coordinate| R accepts: every vertex lies within a pixel of A, so with twelve fractional
#: bits it is an exact float64 number (|v| · 2¹² < 2⁵³) up to here.
COORD_LIMIT = 2**40


def _scale_cap(ps: PixelSet) -> int:
    # Refuse, with a message, coordinates where the output could not be written exactly in float64.
    box = ps.bbox
    assert box is not None
    big = int(max(abs(v) for v in box))
    if big > COORD_LIMIT:
        raise ParameterError(
            f"pixel coordinates up to {big:,} are too large for an exact reconstruction in float64 "
            f"(the limit is ±{COORD_LIMIT:,} = ±2^40)"
        )
    return KCAP


#: The largest side of A's array and the most linels R takes: its corridor tables hold Q-units (4 per
#: pixel) and element and piece indices (up to two elements per linel, two pieces per element) as int32.
INT32_SIDE = 2**28
INT32_LINELS = 2**28

#: Pieces (over all rings) from which R splits its rings between threads, and the most threads it uses.
PARALLEL_PIECES = 4000

#: Under gauss the decimation is tried beside a digitally convex set's grown hull only when the hull has at
#: least this many triangles per surfel of A: on smooth shapes the decimation keeps 0.08–0.13 per surfel, so
#: below 0.05 (a lattice polytope's few faces: the octahedron's 8) it cannot win and would cost seconds.
RIVAL_WORTH = 0.05


#: What one ring costs R besides its pieces (its kernels' calls and small arrays), in pieces' worth of work:
#: about 10 µs a ring against 1 µs a piece on the benchmark images.
RING_COST = 10


def _ring_plan(pieces: IntArray) -> list[list[tuple[int, int]]]:
    # The ring ranges each thread works on (``pieces`` per ring, 0 for a twin): consecutive ranges of about
    # 1/n of the work, except that a ring worth more than 1/(2n) of it is a range of its own; the ranges
    # then go, largest first, to the thread with the least work so far. Isolating the large rings is what
    # balances an image with one big object: cut into consecutive halves, camera's big ring and its
    # neighbours were one thread's 6,116 of 9,123 pieces. Measured against that split (same process,
    # alternating): 4096² blobs 165 → 128 ms, camera 7.4 → 7.2 ms (gauss 6.7 → 5.7), the rest within ±2 %.
    # Every range costs a few kernel calls, so sets without a big ring keep one range per thread. One range
    # when the set is small (starting a thread would cost more than it saves).
    nr = pieces.size
    n = _threads()
    if n < 2 or nr < 2 or int(pieces.sum()) < PARALLEL_PIECES:
        return [[(0, nr)]]
    cost = np.where(pieces > 0, pieces + RING_COST, 0)
    total = int(cost.sum())
    share = total / n
    big = np.flatnonzero(cost > share / 2).tolist()
    # with big rings alone, the others in ranges of half a share, for the threads to even out
    unit = share / 2 if big else share
    ranges: list[tuple[int, int, int]] = []  # (first ring, end, cost)
    start = 0
    for k in [*big, nr]:
        # the rings start … k−1 in consecutive ranges of about one unit, then (big) ring k alone
        if k > start:
            cum = np.cumsum(cost[start:k])
            cuts = np.searchsorted(cum, unit * np.arange(1, int(cum[-1] // unit) + 1)) + 1
            bounds = sorted({0, k - start, *[int(c) for c in cuts if c < k - start]})
            for b0, b1 in pairwise(bounds):
                ranges.append((start + b0, start + b1, int(cum[b1 - 1]) - (int(cum[b0 - 1]) if b0 else 0)))
        if k < nr:
            ranges.append((k, k + 1, int(cost[k])))
        start = k + 1
    load = [0] * n
    plan: list[list[tuple[int, int]]] = [[] for _ in range(n)]
    for a, b, c in sorted(ranges, key=lambda r: -r[2]):
        i = load.index(min(load))
        load[i] += c
        plan[i].append((a, b))
    return [p for p in plan if p]


def _in_threads(work: Callable[[int, int], Any], plan: list[list[tuple[int, int]]]) -> list[Any]:
    # Each thread works through its ranges (the kernels release the GIL, mrm.geometry._jit); the results
    # come back in ring order.
    pool = side_pool() if len(plan) > 1 else None
    if pool is None:
        return [work(a, b) for ranges in plan for a, b in ranges]

    def share(ranges: list[tuple[int, int]]) -> list[tuple[int, Any]]:
        return [(a, work(a, b)) for a, b in ranges]

    futures = [pool.submit(share, ranges) for ranges in plan[1:]]
    done = share(plan[0])  # this thread takes a share too
    for f in futures:
        done += f.result()
    return [result for _a, result in sorted(done, key=lambda d: d[0])]


#: Pieces in one batch of rings: its reach table and lines (40 bytes a piece) are all R keeps of them at
#: a time (a ring with more pieces is a batch of its own).
BATCH_PIECES = 1 << 18


def _batches(poff: IntArray, k0: int, k1: int) -> list[tuple[int, int]]:
    # Consecutive ring ranges of k0 … k1−1 with at most BATCH_PIECES pieces each (or one larger ring).
    out = []
    b0 = k0
    while b0 < k1:
        b1 = int(np.searchsorted(poff, poff[b0] + BATCH_PIECES, side="right")) - 1
        b1 = min(max(b1, b0 + 1), k1)
        out.append((b0, b1))
        b0 = b1
    return out


#: Corridors' tables by what their rows are (see :class:`._base.Corridors`), for slicing a batch of rings.
_PER_RING = ("kmax", "special", "full")
_PER_ELEMENT = ("ec", "er", "edin", "edout", "enl", "cnt")
_PER_PIECE = ("rect", "pel", "gp", "gq", "gdir")
_PER_NET_VERTEX = ("r0", "r0t")


def _batch(cor: _k.Corridors, k0: int, k1: int) -> tuple[_k.Corridors, int, int]:
    # Rings k0 … k1−1 as a corridor of their own (offsets from their first element, piece and net vertex),
    # and the range of their pieces in the whole.
    e0, e1 = int(cor.eoff[k0]), int(cor.eoff[k1])
    p0, p1 = int(cor.poff[k0]), int(cor.poff[k1])
    n0, n1 = int(cor.r0off[k0]), int(cor.r0off[k1])
    rows = {f: getattr(cor, f)[k0:k1] for f in _PER_RING}
    rows |= {f: getattr(cor, f)[e0:e1] for f in _PER_ELEMENT}
    rows |= {f: getattr(cor, f)[p0:p1] for f in _PER_PIECE}
    rows |= {f: getattr(cor, f)[n0:n1] for f in _PER_NET_VERTEX}
    part = cor._replace(
        eoff=cor.eoff[k0 : k1 + 1] - e0,
        poff=cor.poff[k0 : k1 + 1] - p0,
        r0off=cor.r0off[k0 : k1 + 1] - n0,
        **rows,
    )
    return part, p0, p1


def _joined(parts: list[_k.Rings]) -> _k.Rings:
    # Rings of consecutive ring ranges, joined in order.
    if len(parts) == 1:
        return parts[0]
    shift = np.cumsum([0] + [o.xy.shape[0] for o in parts[:-1]])
    return _k.Rings(
        np.concatenate([o.xy for o in parts]),
        np.concatenate([parts[0].roff] + [o.roff[1:] + s for o, s in zip(parts[1:], shift[1:], strict=True)]),
        np.concatenate([o.status for o in parts]),
        np.concatenate([o.src for o in parts]),
        np.concatenate([o.win for o in parts]),
    )


def _run(ps: PixelSet, model: str, tables: bool = False) -> _Run:
    m = np.ascontiguousarray(ps.mask.view(np.uint8))
    kcap = _scale_cap(ps)
    rings = trace_mask(m)
    if max(m.shape) > INT32_SIDE or rings.codes.size > INT32_LINELS:
        # the corridor tables are int32 (Q-units up to 4 × side, elements up to 2 × linels: _base.Corridors)
        raise ParameterError(
            f"a {m.shape[1]:,} × {m.shape[0]:,} pixel set with {rings.codes.size:,} linels is too large "
            f"for R (at most {INT32_SIDE:,} pixels a side and {INT32_LINELS:,} linels)"
        )
    x0, y0 = ps.origin
    gauss = model == "gauss"
    h, w = m.shape
    if gauss:
        # the dual corridor (pointels as pixels, :mod:`._dual`); the cover pipeline runs on it
        cor = _dk.dual_corridors_all(rings.codes, rings.off, rings.sx, rings.sy, h, w, kcap)
    else:
        cor = _k.corridors_all(rings.codes, rings.off, rings.sx, rings.sy, h, w, kcap)

    # a ring that translates an earlier one is left to it (ADR 0036): its phases are skipped and its
    # ring, reach and lines are the earlier one's, moved
    rep = _tw.ring_twins(rings.codes, rings.off, cor.eoff, cor.cnt, cor.special)
    twins = rep != np.arange(rep.size)
    if twins.any():
        special = cor.special.copy()
        special[twins] = _tw.TWIN
        cor = cor._replace(special=special)

    # The reach table and the central lines (40 bytes a piece) are needed ring by ring: R keeps them for a
    # batch of rings at a time, unless the caller wants the whole tables (reconstruct_detailed)
    npc = cor.gdir.size
    reach = np.zeros(npc if tables else 0, np.int64)
    lines = np.zeros((npc if tables else 0, 4), np.float64)

    def rings_from(k0: int, k1: int) -> list[_k.Rings]:
        # Phases 2-4 (reach and lines, the V4 greedy under two closing rules, finishing) for rings
        # k0 … k1−1, a batch at a time: each ring depends only on its own corridor.
        done = []
        for b0, b1 in _batches(cor.poff, k0, k1):
            part, p0, p1 = _batch(cor, b0, b1)
            if tables:
                r, ln = reach[p0:p1], lines[p0:p1]  # this batch's rows of the whole tables
            else:
                r, ln = np.zeros(p1 - p0, np.int64), np.zeros((p1 - p0, 4), np.float64)
            _k.reach_all(part, r, ln)
            ga = _k.greedy_all(part, r, ln, True)
            gb = _k.greedy_all(part, r, ln, False)
            # finishing needs the reach table but not the lines: their 32 bytes a piece (320 kB on camera)
            # are freed before its arrays come, which lowered camera's first-call peak under gauss most
            del ln
            done.append(_k.finish_all(part, r, ga, gb, x0, y0))
        return done

    chunks = _in_threads(rings_from, _ring_plan(np.where(twins, 0, np.diff(cor.poff))))
    xy, roff, status, src, win = _joined([batch for chunk in chunks for batch in chunk])
    if twins.any():
        xy, roff, status, src, win = _tw.fill_twins(
            rep, rings.sx, rings.sy, cor.poff, reach, lines, xy, roff, status, src, win
        )
    if gauss:
        xy -= 0.5  # dual frame → plane (exact: |coordinates| < 2⁵⁰)
    return _Run(rings, cor, reach, lines, xy, roff, status, src, win)


def _ring_order(
    comp: npt.NDArray[np.int32], hole: npt.NDArray[np.bool_], sx: IntArray, sy: IntArray
) -> IntArray:
    # Components in label order (canonical), each with its outer ring first, then its holes by start (y, x).
    return np.lexsort((sx, sy, hole, comp)).astype(np.int64)


@overload
def reconstruct(ps: PixelSet, model: str = "standard") -> Polygon | MultiPolygon: ...
@overload
def reconstruct(ps: VoxelSet, model: str = "standard") -> Polyhedron: ...
def reconstruct(ps: PixelSet | VoxelSet, model: str = "standard") -> Polygon | MultiPolygon | Polyhedron:
    """Return R(A), the reversible continuation of a pixel or voxel set (see the module docstring).

    Parameters
    ----------
    ps : PixelSet or VoxelSet
        The pixel set A; a voxel set's R is :func:`reconstruct_voxels`.
    model : {"standard", "supercover", "gauss"}
        The discretization model D that R inverts: D(R(A)) = A exactly.

    Returns
    -------
    Polygon or MultiPolygon
        One polygon per 4-connected component (a Polygon when there is one, an empty Polygon for ∅), in
        the canonical order of the components (by their lowest-leftmost pixel), holes ordered the same way.

    Raises
    ------
    ParameterError
        For an unknown model, or pixel coordinates beyond ±2⁴⁰ (where 2⁻¹² of a pixel is no longer
        exact float64 numbers).
    """
    model = Model.parse(model)
    for known_ps, known_model, geom in _HELD.get():
        if known_ps is ps and known_model == model:
            return geom
    if isinstance(ps, VoxelSet):
        return reconstruct_voxels(ps, model)
    if ps.is_empty():
        return Polygon()
    check_reconstruct(ps)  # its cost is bounded up front (issue 11): the one entry point applies the limit
    run = _run(ps, model)
    rings = run.rings
    return _assemble(run.xy, run.roff, rings.comp, rings.area2 < 0, rings.sx, rings.sy)


class VoxelR(NamedTuple):
    """R(A) of a voxel set and the way it was made (:func:`reconstruct_voxels_detailed`).

    ``way`` is ``"grown hull"`` (gauss, digitally convex A), ``"spiked hull"`` (the covers, a lattice
    polytope), ``"snapped core"`` (the covers, a finer hull), ``"decimation"`` (the safety net simplified by
    checked collapses), ``"safety net"`` (V(A) eroded by ¼: A's safety net is beyond
    ``limits.MAX_COMPACT_R_TRIANGLES``, or the decimation's result failed its final check) or ``"empty"``.
    """

    polyhedron: Polyhedron
    way: str
    #: Why R is the safety net (empty for the other ways): A's safety net beyond the decimation's limit, or
    #: the decimation's result refused by its final check.
    why: str = ""
    #: True when R is the safety net because the net has more triangles than the compact limit: a higher
    #: limit (``--compact-limit``, the document's setting) would give the compact R, at a cost.
    over_limit: bool = False

    @property
    def note(self) -> str | None:
        """What a user is told when R is the safety net (exact, but not compact), else None.

        The command line prints it and the desktop's Euclidean 3D view shows it: one sentence, one place.
        """
        if self.way != "safety net":
            return None
        return (
            f"R is the safety net (V(A) eroded by ¼, {self.polyhedron.n_triangles:,} triangles), not a "
            f"compact R: {self.why}"
        )


def reconstruct_voxels(vs: VoxelSet, model: str = "standard") -> Polyhedron:
    """R(A) of a voxel set: a valid polyhedron P with D(P) = A exactly in the model (docs/design.md §11).

    R starts from the safety net of §11 item 7 — V(A) eroded by ¼ in the max norm
    (:func:`~mrm.geometry.reconstruct.safety_net_3d.safety_net_3d`), which meets the contract in every model
    (ADR 0044) — and removes vertices by half-edge collapses, each proved exactly to keep the surface a
    valid 2-manifold of the same topology and D(R(A)) = A in the model
    (``mrm.geometry.reconstruct.decimate_3d``, ADR 0064). The result is checked again as a
    whole: validated exactly (:class:`~mrm.geometry.polyhedra.Polyhedron`) and discretized exactly; should
    that ever fail, the safety net is returned and the failure logged.

    A digitally convex A (a ball's, an ellipsoid's, the octahedron's voxels) has an exact R from its convex
    hull, found in milliseconds (``mrm.geometry.reconstruct.convex_3d``): under ``gauss`` the hull grown by
    a dyadic homothety (ADR 0068), the octahedron's 8 faces at any size; under the covers, for a lattice
    polytope, the hull's facets moved in with a spike to each voxel they miss (ADR 0069), the octahedron's 8
    faces and four small ones at each tip; for a finer hull (a ball's), its core snapped inward to a dyadic
    grid with a spike to each voxel it misses (``mrm.geometry.reconstruct.snapped_core``, ADR 0070). Up to
    ``limits.MAX_RIVAL_SURFELS`` surfels the decimation is
    tried too, unless the hull is already very small (``RIVAL_WORTH``), and the smaller is R: by faces, then
    vertices, for a lattice polytope; by triangles, then faces, for a finer hull.

    Raises
    ------
    LimitError
        When A has more surfels than :data:`~mrm.core.limits.MAX_SURFELS`, before any work.
    ParameterError
        For an unknown model.
    """
    return reconstruct_voxels_detailed(vs, model).polyhedron


def reconstruct_voxels_detailed(
    vs: VoxelSet,
    model: str = "standard",
    compact_limit: int | None = None,
    progress: ProgressLike | None = None,
) -> VoxelR:
    """:func:`reconstruct_voxels`, with the way R was made (:class:`VoxelR`): the command line reports it.

    ``compact_limit``: the most triangles of a safety net that the decimation takes (default: the one in
    force, :func:`compact_limit_in_force`, else ``limits.MAX_COMPACT_R_TRIANGLES``); beyond, R is the safety
    net. ``mrm reconstruct --compact-limit`` and the document's setting raise it: the decimation takes about
    40–150 µs per triangle of the net.
    ``progress`` is told when the decimation starts, and cancelling it stops the decimation within about
    50 ms with :class:`~mrm.core.errors.Cancelled`.
    """
    # Imported here: 2D work (and the desktop's first paint) never loads the 3D kernels.
    from mrm.geometry.polyhedra import Polyhedron
    from mrm.geometry.reconstruct.convex_3d import FEW_FACETS, convex_reconstruction

    model = Model.parse(model)
    if vs.is_empty():
        return VoxelR(Polyhedron.empty(), "empty")
    if compact_limit is None:
        compact_limit = _COMPACT_LIMIT.get()
    check_reconstruct(vs)
    from mrm.core import limits

    hull = convex_reconstruction(vs, model)
    if hull is not None:
        way = (
            "grown hull"
            if model == "gauss"
            else "spiked hull"
            if hull.facets <= FEW_FACETS
            else "snapped core"
        )
        small = hull.polyhedron.n_triangles < RIVAL_WORTH * hull.surfels
        if small or hull.surfels > limits.MAX_RIVAL_SURFELS:
            return VoxelR(hull.polyhedron, way)
        rival = _decimated(vs, model, compact_limit, progress)
        if _size(hull.polyhedron, hull.facets) <= _size(rival.polyhedron, hull.facets):
            return VoxelR(hull.polyhedron, way)
        return rival
    return _decimated(vs, model, compact_limit, progress)


def _size(p: Polyhedron, facets: int) -> tuple[int, ...]:
    # How R's two candidates for a digitally convex A compare (convex_3d.FEW_FACETS): a lattice polytope by
    # faces, then vertices; a finer hull by triangles, then faces.
    from mrm.geometry.reconstruct.convex_3d import FEW_FACETS

    if facets <= FEW_FACETS:
        return (p.n_faces, p.n_vertices, p.n_triangles)
    return (p.n_triangles, p.n_faces)


def _decimated(
    vs: VoxelSet, model: str, compact_limit: int | None, progress: ProgressLike | None = None
) -> VoxelR:
    # R(A) by the safety net's decimation (ADR 0064), checked as a whole; the safety net when too big.
    from mrm.core import limits
    from mrm.geometry.discretize.voxels import voxelize_solid
    from mrm.geometry.polyhedra import Polyhedron
    from mrm.geometry.reconstruct.decimate_3d import compact_r

    most = limits.MAX_COMPACT_R_TRIANGLES if compact_limit is None else compact_limit
    vertices, triangles, net_vertices, net_triangles = compact_r(vs.mask, vs.origin, model, most, progress)
    if triangles is net_triangles:  # too big for the decimation: the safety net, which meets the contract
        why = f"the decimation takes sets whose safety net has at most {most:,} triangles"
        return VoxelR(_net_polyhedron(net_vertices, net_triangles), "safety net", why, over_limit=True)
    try:
        result = Polyhedron(vertices, triangles)
        mask, origin = voxelize_solid(vertices, triangles, model, limit=None)
        if VoxelSet(mask, origin) == vs:
            return VoxelR(result, "decimation")
        failure = "its discretization differs from A"
    except ValueError as e:  # InvalidGeometryError: a collapse let through that the whole check refuses
        failure = str(e)
    FALLBACKS[0] += 1
    logger.error("3D R fell back to the safety net (%s): %d voxels, model %s", failure, vs.count, model)
    why = f"the decimation's result failed its final check ({failure}), a defect that is logged"
    return VoxelR(_net_polyhedron(net_vertices, net_triangles), "safety net", why)


def _net_polyhedron(vertices: FloatArray, triangles: IntArray) -> Polyhedron:
    """The safety net as a polyhedron, validated without the search for triangles that meet improperly.

    Its surface is the boundary of a union of closed cubes of the doubled grid, cut into rectangles within
    its faces and triangulated without T-junctions (:mod:`.safety_net_3d`), so two of its triangles meet only
    in common vertices and edges: proven by construction, and checked with the full validation on random
    sets by the tests. That search was about 80 % of R's time on a big set that keeps the net (a 256³
    volume of blobs: 24 s, most of its 2 GB); every other check of the validation still runs.
    """
    from mrm.geometry.polyhedra import Polyhedron
    from mrm.geometry.polyhedra.validation import validate

    v = np.ascontiguousarray(vertices, np.float64)
    t = np.ascontiguousarray(triangles, np.int64)
    return Polyhedron._trusted(v, t, validate(v, t, pairs=False))


#: The compact limit in force (:func:`compact_limit_in_force`): None means ``limits.MAX_COMPACT_R_TRIANGLES``.
_COMPACT_LIMIT: ContextVar[int | None] = ContextVar("mrm_compact_limit", default=None)


@contextmanager
def compact_limit_in_force(limit: int | None) -> Iterator[None]:
    """Within the block, R of a voxel set simplifies safety nets of at most ``limit`` triangles.

    A document's setting (``Settings.compact_limit``, ADR 0073) reaches every R its operations and its error
    account compute this way — R of an input, and of an intermediate set (Sp_α's) — without each of them
    taking it as a parameter. None keeps the limit in force. The current thread and context only: a worker
    sets it again (:func:`mrm.ops.registry.run_operation` takes it).
    """
    token = _COMPACT_LIMIT.set(limit if limit is not None else _COMPACT_LIMIT.get())
    try:
        yield
    finally:
        _COMPACT_LIMIT.reset(token)


#: R(A) already known to the caller (:func:`held`): (A, model, R(A)) in the current context.
_HELD: ContextVar[tuple[tuple[PixelSet | VoxelSet, str, Any], ...]] = ContextVar(
    "mrm_held_reconstructions", default=()
)


@contextmanager
def held(known: Iterable[tuple[PixelSet | VoxelSet, str, Any]]) -> Iterator[None]:
    """Within the block, :func:`reconstruct` of one of these very pixel or voxel sets returns the R given.

    For callers that hold R(A) already — a document keeps each object's Euclidean representation — so that
    an operation on the object does not compute it again (R is deterministic: the held geometry is the one
    R would return). Matched by identity of the pixel set and by model; the current thread and context only.

    Parameters
    ----------
    known : iterable of (PixelSet or VoxelSet, str, Polygon, MultiPolygon or Polyhedron)
        Pixel or voxel sets A, the model, and R(A) under that model as :func:`reconstruct` returned it (for a
        voxel set, under the compact limit in force).
    """
    token = _HELD.set(_HELD.get() + tuple(known))
    try:
        yield
    finally:
        _HELD.reset(token)


def _assemble(
    xy: FloatArray,
    roff: IntArray,
    comp: npt.NDArray[np.int32],
    hole: npt.NDArray[np.bool_],
    sx: IntArray,
    sy: IntArray,
) -> Polygon | MultiPolygon:
    order = _ring_order(comp, hole, sx, sy)
    lengths = np.diff(roff)[order]
    starts = roff[:-1][order]
    ring_off = np.zeros(order.size + 1, dtype=np.int64)
    np.cumsum(lengths, out=ring_off[1:])
    # gather the vertex rows ring by ring in the new order
    idx = np.repeat(starts - ring_off[:-1], lengths) + np.arange(ring_off[-1], dtype=np.int64)
    coords = xy[idx]
    # polygon k holds the rings of component k+1: outer ring, then holes
    counts = np.bincount(comp, minlength=int(comp.max()) + 1)[1:]
    poly_off = np.zeros(counts.size + 1, dtype=np.int64)
    np.cumsum(counts, out=poly_off[1:])
    multi_off = np.array([0, counts.size], dtype=np.int64)
    geom = shapely.from_ragged_array(
        shapely.GeometryType.MULTIPOLYGON, coords, (ring_off, poly_off, multi_off)
    )[0]
    if counts.size == 1:
        poly: Polygon = geom.geoms[0]
        return poly
    mp: MultiPolygon = geom
    return mp


# ---------------------------------------------------------------------------------------------- details


@dataclass(frozen=True)
class RingDetail:
    """How one ring of R(A) was built (for the analytical view and the documentation).

    Attributes
    ----------
    component : int
        The label (1..n, canonical order) of the 4-component the ring bounds.
    hole : bool
        True for a hole ring.
    chain : CrackChain
        The crack chain the ring follows.
    vertices : ndarray of float64, shape (k, 2)
        The ring's vertices in plane coordinates (not repeated at the end).
    sources : tuple of str
        Where each vertex comes from: ``"lines"`` (two chosen lines meet), ``"patch"`` (a two-vertex
        patch), ``"splice"`` / ``"net"`` (a stretch replaced by the safety net), ``"single"`` (an isolated
        pixel's triangle or two pixels' triangle).
    status : str
        ``"v4"``, ``"partial"`` (some stretch from the safety net), ``"net"`` (all of it) or ``"single"``.
    pieces : ndarray of float64, shape (n, 4)
        The corridor's pieces [xmin, xmax, ymin, ymax].
    reach : ndarray of int64, shape (n,)
        For each piece i, how many gates one line crosses from it (window i … i + reach[i]).
    lines : ndarray of float64, shape (n, 4)
        The central line of each window: a point (x, y) and a unit direction (dx, dy).
    edge_window : ndarray of int64, shape (k,)
        For each vertex, the window whose line carries the edge leaving it (−1: a patch or net edge, or an
        edge moved onto the simplest line of the pieces it crosses).
    """

    component: int
    hole: bool
    chain: CrackChain
    vertices: FloatArray
    sources: tuple[str, ...]
    status: str
    pieces: FloatArray
    reach: IntArray
    lines: FloatArray
    edge_window: IntArray


@dataclass(frozen=True)
class Reconstruction:
    """R(A) with how each ring was built (:func:`reconstruct_detailed`)."""

    geometry: Polygon | MultiPolygon
    model: str
    rings: tuple[RingDetail, ...]

    @property
    def n_vertices(self) -> int:
        """Total number of vertices of the rings."""
        return sum(r.vertices.shape[0] for r in self.rings)

    @property
    def n_fallback(self) -> int:
        """Number of rings that use the safety net, in part or whole."""
        return sum(r.status in ("partial", "net") for r in self.rings)


def reconstruct_detailed(ps: PixelSet, model: str = "standard") -> Reconstruction:
    """Like :func:`reconstruct`, with per-ring information: chosen lines, windows, vertex sources, fallbacks.

    The geometry is the same as :func:`reconstruct` returns.
    """
    model = Model.parse(model)
    if ps.is_empty():
        return Reconstruction(Polygon(), model, ())
    run = _run(ps, model, tables=True)
    rings = run.rings
    x0, y0 = ps.origin
    poff = run.corridor.poff
    rect = run.corridor.rect
    text = (rings.codes + np.uint8(48)).tobytes().decode("ascii")
    # gauss works in the dual frame, half a pixel up and right of the plane
    d = 2 if model == "gauss" else 0
    shift = np.array([4 * x0 - d, 4 * x0 - d, 4 * y0 - d, 4 * y0 - d], dtype=np.int64)
    details: list[RingDetail] = []
    for k in range(rings.off.size - 1):
        a, b = int(poff[k]), int(poff[k + 1])
        r0_, r1_ = int(run.roff[k]), int(run.roff[k + 1]) - 1  # without the closing repeat
        lines = run.lines[a:b].copy()
        lines[:, 0] = (lines[:, 0] - d) / 4.0 + x0
        lines[:, 1] = (lines[:, 1] - d) / 4.0 + y0
        chain = CrackChain._trusted(
            (int(rings.sx[k]) + x0, int(rings.sy[k]) + y0), text[int(rings.off[k]) : int(rings.off[k + 1])]
        )
        details.append(
            RingDetail(
                component=int(rings.comp[k]),
                hole=bool(rings.area2[k] < 0),
                chain=chain,
                vertices=run.xy[r0_:r1_].copy(),
                sources=tuple(SOURCE_NAMES[int(v)] for v in run.src[r0_:r1_]),
                status=STATUS_NAMES[int(run.status[k])],
                pieces=(rect[a:b] + shift) / 4.0,
                reach=run.reach[a:b].copy(),
                lines=lines,
                edge_window=run.win[r0_:r1_].copy(),
            )
        )
    geom = _assemble(run.xy, run.roff, rings.comp, rings.area2 < 0, rings.sx, rings.sy)
    order = _ring_order(rings.comp, rings.area2 < 0, rings.sx, rings.sy)
    return Reconstruction(geom, model, tuple(details[i] for i in order.tolist()))
