"""A watertight subdivision under ``gauss``: all the labels of a label map reconstructed jointly.

:func:`reconstruct_label_map` maps a label map to one polygon (or multipolygon) per non-zero label such that

1. D_gauss(P_L) = pixels of L, exactly, for every label L;
2. neighbouring parts share their boundaries exactly: every edge of every part is, with the same two
   float64 end points, an edge of exactly one other part (traversed the other way) or lies on the outline
   of the whole (next to the background, label 0). The parts have pairwise disjoint interiors and their union
   is the polygon the outline bounds: no gap, no overlap, no sliver;
3. every part is a valid shapely Polygon / MultiPolygon with dyadic float64 coordinates, one polygon per
   4-connected component of the label, one hole per bounded 8-connected component of its complement (a
   component that touches itself at a pixel corner gets a hole touching its shell at that corner);
4. few vertices: never more than the crack staircase, usually far fewer (about one per digital straight
   segment of each boundary);
5. R(lm + t) = R(lm) + t for t ∈ Z², and the same input always gives the same output.

This is the form CAD and GIS users need (a clean coverage), and the form co-refinement returns under ``gauss``
(:func:`watertight_parts`). It needs ``gauss``: under the cover models the discretization of a polygon adds
the pixels its boundary crosses, so two parts sharing an edge would both claim the pixels along it.

How: cells, polylines and parts
-------------------------------
The boundaries of a label map split into 0-cells (pointels where three or more labels meet, or two
diagonally) and 1-cells (maximal chains of linels between the same two labels; :mod:`mrm.reps.cells`).
Each 1-cell c is reconstructed **once**, as an open polyline γ_c between its two 0-cells (which stay where
they are: a pixel corner is never a pixel centre, so it decides nothing under ``gauss``), or as a ring when
it meets no 0-cell. Every part is then assembled from the polylines of its 1-cells, reversed where the label
is on their right: the shared edges are the same floats by construction.

The corridor of each 1-cell and the conditions every polyline meets (checked exactly) are in
:mod:`._cell_polylines`, with how the polylines are chosen and three lemmas: an edge stays in its corridor
(Lemma 1), each polyline is simple and two meet only at common 0-cells (Lemma 2), and every pixel centre
keeps its side (Lemma 3).

**Theorem.** For every label L, D_gauss(P_L) = L and the parts form a subdivision. *Proof.* As cellular
1-chains, ∂V(L) = Σ_{p∈L} ∂V(p) = Σ ±c over the 1-cells of L (interior linels cancel), so every pixel centre
x has winding number w_x(∂V(L)) = [x ∈ L]. Replacing each 1-cell by γ_c is a homotopy in the plane minus
the centres (Lemma 3), so w_x(Γ_L) = [x ∈ L] for Γ_L = Σ ±γ_c. No centre lies on any γ_c, so the
crossing-number test of ``gauss`` (every ring edge counts, tie rule never used) returns the parity of the
winding number: D_gauss(P_L) = L whichever way the edges of Γ_L are grouped into rings. By Lemma 2 the
rings of P_L are simple and meet only at 0-cells, and they are grouped exactly as the crack rings of L (same
cyclic order of the 1-cells at every 0-cell, because each polyline leaves a 0-cell inside the quarter of
the dual square that holds its first linel), so P_L is a valid polygon with the topology of V(L).
Finally Σ_{L≠0} Γ_L = Γ_0-outline (each shared γ_c appears once each way and cancels), the boundary of one
more valid polygon U; for any point z off the polylines, Σ_L w_z(Γ_L) = w_z(∂U) ∈ {0, 1} with every term in
{0, 1}: z lies in at most one part, and in one exactly when z ∈ U — no overlap and no gap. □

The assembled parts are checked once more (exact discretization, validity); a part that fails (none is
known) has all its 1-cells set back to the staircase (:func:`._cell_polylines._Chain.staircase`), which
the proof above covers as well.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import numpy.typing as npt
import shapely
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import ParameterError
from mrm.core.gc_pause import paused_gc
from mrm.core.grids import LabelMap, PixelSet
from mrm.core.limits import check_subdivision
from mrm.core.models import Model
from mrm.geometry.discretize import _discretize_pieces, _take_apart
from mrm.geometry.reconstruct import _subdivision_kernels as K
from mrm.geometry.reconstruct._cell_polylines import _Chain, _polyline, _to_plane
from mrm.geometry.reconstruct._subdivision_kernels import label_boxes
from mrm.geometry.topology.cracks import DX, DY
from mrm.geometry.topology.labeling import LabelRegions, group_by_label, label_regions
from mrm.geometry.topology.labeling import label as label_components
from mrm.reps.cells import Cells, cells_of

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

# the pixel on the left of a linel leaving pointel (i, j) with code k is (i, j) + _LEFT_PIXEL[k]
_LEFT_PIXEL = ((0, 0), (-1, 0), (-1, -1), (0, -1))


@dataclass(frozen=True)
class Subdivision:
    """The joint reconstruction of a label map (:func:`subdivide`).

    Attributes
    ----------
    parts : dict of int to Polygon or MultiPolygon
        One geometry per non-zero label, in increasing label order.
    polylines : tuple of ndarray of float64
        The reconstructed 1-cells, in the order of ``cells.one_cells``: each an (k, 2) array of plane
        coordinates with the larger label on its left, from its first 0-cell to its last (a ring, without
        the closing repeat, for a 1-cell with no 0-cell).
    staircase : tuple of bool
        For each 1-cell, whether its polyline is the crack staircase (the local fallback, or simply no
        worse: a chain of one or two linels is its own best polyline).
    cells : Cells
        The cell decomposition the polylines follow.
    """

    parts: dict[int, Polygon | MultiPolygon]
    polylines: tuple[FloatArray, ...]
    staircase: tuple[bool, ...]
    cells: Cells

    @property
    def n_vertices(self) -> int:
        """Number of distinct vertices of the subdivision: the 0-cells plus the polylines' other vertices."""
        zero = {z.point for z in self.cells.zero_cells}
        total = len(zero)
        for c, pl in zip(self.cells.one_cells, self.polylines, strict=True):
            total += pl.shape[0] if c.chain.start not in zero else pl.shape[0] - 2
        return total


def _check_model(model: Model | str) -> None:
    if Model.parse(model).is_cover:
        raise ParameterError(
            f"a watertight subdivision exists only under the gauss model, not {model!r}: under a cover model "
            "two parts sharing an edge would both claim the pixels along it"
        )


def _split(loop: list[tuple[_Directed, tuple[int, int]]]) -> list[list[_Directed]]:
    """Split a closed walk of directed cells (each with its start pointel) where it passes a 0-cell twice."""
    out: list[list[_Directed]] = []
    stack: list[tuple[tuple[int, int], list[_Directed]]] = []
    where: dict[tuple[int, int], int] = {}
    for d, start in loop:
        if start in where:
            k = where[start]
            piece: list[_Directed] = []
            for pt, seq in stack[k:]:
                piece.extend(seq)
                del where[pt]
            del stack[k:]
            out.append(piece)
        where[start] = len(stack)
        stack.append((start, [d]))
    rest = [d for _, seq in stack for d in seq]
    if rest:
        out.append(rest)
    return out


def _point_in_ring(ring: IntArray, x: int, y: int) -> bool:
    """Crossing-number test of an integer point that lies on no edge of the integer ring."""
    a = ring
    b = np.roll(ring, -1, axis=0)
    ay, by = a[:, 1], b[:, 1]
    straddle = (ay > y) != (by > y)
    if not straddle.any():
        return False
    ax, bx = a[straddle, 0], b[straddle, 0]
    ay, by = ay[straddle], by[straddle]
    # x < ax + (y − ay)(bx − ax)/(by − ay), multiplied by (by − ay) with its sign
    lhs = (x - ax) * (by - ay)
    rhs = (y - ay) * (bx - ax)
    hit = np.where(by > ay, lhs < rhs, lhs > rhs)
    return bool(np.count_nonzero(hit) % 2)


def _code_of_step(d: IntArray) -> IntArray:
    """Freeman codes (0 = E, 1 = N, 2 = W, 3 = S) of unit steps, an (n, 2) array."""
    return np.asarray(_CODE_OF_STEP[d[:, 0] + 1, d[:, 1] + 1], dtype=np.int64)


#: _CODE_OF_STEP[dx + 1, dy + 1] is the code of the unit step (dx, dy).
_CODE_OF_STEP = np.array([[-1, 2, -1], [3, -1, 1], [-1, 0, -1]], dtype=np.int64)


class _CellPoints(NamedTuple):
    """The pointels of all 1-cells, in one array and per cell, and twice each cell's signed area.

    Cell c is rows ``off[c]`` … ``off[c + 1] − 1`` of ``all``; ``each[c]`` is that view (``chain.points()``);
    ``area2`` is taken in the label map's array coordinates.
    """

    all: IntArray
    off: IntArray
    each: list[IntArray]
    area2: list[int]


#: A directed 1-cell: 2·c for 1-cell c as it runs (its left label on the left), 2·c + 1 for it reversed.
_Directed = int


class _Assembler:
    """Rings of each label from the directed 1-cells, with the (4, 8) rule at 0-cells."""

    def __init__(self, lm: LabelMap, cells: Cells, cp: _CellPoints) -> None:
        zero = {z.point for z in cells.zero_cells}
        ones = cells.one_cells
        self.points = cp.each
        self.area2 = cp.area2
        self.loop = [c.chain.start not in zero for c in ones]  # a ring with no 0-cell on it
        self.by_label: dict[int, list[_Directed]] = {}
        for ci, c in enumerate(ones):
            self.by_label.setdefault(c.left, []).append(2 * ci)
            self.by_label.setdefault(c.right, []).append(2 * ci + 1)
        m = len(ones)
        self.start: list[tuple[int, int]] = []
        self.first_left: list[tuple[int, int]] = []
        self.cell_key: list[int] = []
        self.next: list[_Directed] = [-1] * (2 * m)
        if m == 0:
            return
        head, tail = cp.off[:-1], cp.off[1:] - 1
        first, last = cp.all[head], cp.all[tail]
        c0 = _code_of_step(cp.all[head + 1] - first)
        c1 = _code_of_step(last - cp.all[tail - 1])
        lab = np.fromiter((v for c in ones for v in (c.left, c.right)), dtype=np.int64, count=2 * m)
        # per directed cell (interleaved forward, backward): its start, its end t and the code k entering t
        start = np.stack([first, last], axis=1).reshape(-1, 2)
        end = np.stack([last, first], axis=1).reshape(-1, 2)
        leave = np.stack([c0, (c1 + 2) % 4], axis=1).reshape(-1)
        k = np.stack([c1, (c0 + 2) % 4], axis=1).reshape(-1)
        self.start = [(a, b) for a, b in start.tolist()]
        # the pixel left of each directed cell's first linel (all left pixels of a ring share a 4-component)
        left = np.asarray(_LEFT_PIXEL, dtype=np.int64)
        self.first_left = [(a, b) for a, b in (start + left[leave]).tolist()]
        # the lowest-leftmost pointel of each cell as one integer: a ring's is the least over its cells
        cat = cp.all
        self.key_x0, self.key_y0 = int(cat[:, 0].min()), int(cat[:, 1].min())
        self.key_w = int(cat[:, 0].max()) - self.key_x0 + 1
        key = (cat[:, 1] - self.key_y0) * self.key_w + (cat[:, 0] - self.key_x0)
        self.cell_key = np.minimum.reduceat(key, head).tolist()
        # the (4, 8) rule at t: turn left when the pixel ahead on the left is not the label, right when the
        # one ahead on the right is, else go straight (the labels read from the padded array, 0 outside)
        pad = np.pad(lm.labels, 1)
        x0, y0 = lm.origin[0] - 1, lm.origin[1] - 1

        def label_at(px: IntArray, py: IntArray) -> IntArray:
            r, c = py - y0, px - x0
            inside = (r >= 0) & (r < pad.shape[0]) & (c >= 0) & (c < pad.shape[1])
            out = np.zeros(px.shape, dtype=np.int64)
            out[inside] = pad[r[inside], c[inside]]
            return out

        fl = label_at(end[:, 0] + left[k, 0], end[:, 1] + left[k, 1])
        kr = (k + 3) % 4
        fr = label_at(end[:, 0] + left[kr, 0], end[:, 1] + left[kr, 1])
        k2 = np.where(fl != lab, (k + 1) % 4, np.where(fr == lab, kr, k))
        out: dict[tuple[tuple[int, int], int, int], _Directed] = {}  # (start pointel, code, label)
        rows = [d for d in range(2 * m) if not self.loop[d >> 1]]
        leave_l, lab_l, k2_l, end_l = leave.tolist(), lab.tolist(), k2.tolist(), end.tolist()
        for d in rows:
            out[(self.start[d], leave_l[d], lab_l[d])] = d
        for d in rows:
            t = end_l[d]
            self.next[d] = out[((t[0], t[1]), k2_l[d], lab_l[d])]

    def loops(self, label: int) -> list[list[_Directed]]:
        """The boundary of a label as simple closed walks of directed cells (label on the left)."""
        used: set[_Directed] = set()
        out: list[list[_Directed]] = []
        nxt, start = self.next, self.start
        for d in self.by_label.get(label, []):
            if d in used:
                continue
            if self.loop[d >> 1]:
                used.add(d)
                out.append([d])
                continue
            walk: list[tuple[_Directed, tuple[int, int]]] = []
            cur = d
            while cur not in used:
                used.add(cur)
                walk.append((cur, start[cur]))
                cur = nxt[cur]
            out.extend(_split(walk))
        return out

    def loop_key(self, loop: list[_Directed]) -> int:
        """The ring's lowest-leftmost pointel (least y, then least x) as one integer, ordered alike."""
        return min(self.cell_key[d >> 1] for d in loop)

    def loop_area2(self, loop: list[_Directed]) -> int:
        return sum(-self.area2[d >> 1] if d & 1 else self.area2[d >> 1] for d in loop)

    def loop_points(self, loop: list[_Directed]) -> IntArray:
        parts = [self.points[d >> 1][::-1] if d & 1 else self.points[d >> 1] for d in loop]
        return np.concatenate([p[:-1] for p in parts])


def _ring_coords(loop: list[_Directed], polylines: Sequence[FloatArray], loops: Sequence[bool]) -> FloatArray:
    if len(loop) == 1 and loops[loop[0] >> 1]:
        pl = polylines[loop[0] >> 1]
        return pl[::-1] if loop[0] & 1 else pl
    parts = [polylines[d >> 1][::-1] if d & 1 else polylines[d >> 1] for d in loop]
    return np.concatenate([p[:-1] for p in parts])


def _owners_by_rings(shells: Sequence[tuple[int, IntArray]], holes: Sequence[IntArray]) -> list[int]:
    """For each hole ring, the shell of least area that contains it: point-in-ring against every shell.

    The definition, O(holes × shells); :func:`_owners_by_components` gives the same answer from the pixels.
    Shells are (twice their area, pointels), holes their pointels.
    """
    if len(shells) == 1:
        return [0] * len(holes)
    boxes = [(2 * pts.min(axis=0), 2 * pts.max(axis=0)) for _, pts in shells]
    out = []
    for pts in holes:
        # a test point that lies on no other ring: the midpoint of the hole's first linel (doubled)
        px, py = int(pts[0, 0] + pts[1 % len(pts), 0]), int(pts[0, 1] + pts[1 % len(pts), 1])
        inside = [
            k
            for k, (lo, hi) in enumerate(boxes)
            if lo[0] < px < hi[0] and lo[1] < py < hi[1] and _point_in_ring(2 * shells[k][1], px, py)
        ]
        if not inside:
            raise AssertionError("a hole outside every shell")
        out.append(min(inside, key=lambda k: shells[k][0]))
    return out


def _owners_by_components(
    shells: Sequence[tuple[int, int]], holes: Sequence[tuple[int, int]], ps: PixelSet
) -> list[int] | None:
    """The owners of :func:`_owners_by_rings`, read from the 4-connected components of the label's pixels.

    Every linel of a ring (a closed walk with the label on its left, split at repeated 0-cells) has its
    left pixel 4-adjacent to, or equal to, the left pixel of the next one, so all the left pixels of a ring
    lie in one 4-component C. A shell is the outer ring of its C; a hole ring of C faces a bounded
    component of the complement of C, which C's shell encloses; any other shell enclosing that hole
    encloses C and so is larger. So the owner is the shell of the component left of the hole's first
    linel: O(pixels of the label's box) instead of O(holes × shells). Rings are given by the pixel left of
    their first linel. None when the shells do not map one-to-one onto the components (never seen; the
    caller then uses the definition).
    """
    comp, _ = label_components(ps.mask, 4)
    x0, y0 = ps.origin

    def component(pixel: tuple[int, int]) -> int:
        r, c = pixel[1] - y0, pixel[0] - x0
        if not (0 <= r < comp.shape[0] and 0 <= c < comp.shape[1]):
            return 0
        return int(comp[r, c])

    shell_of: dict[int, int] = {}
    for k, pixel in enumerate(shells):
        cid = component(pixel)
        if cid == 0 or cid in shell_of:
            return None
        shell_of[cid] = k
    owners = [shell_of.get(component(pixel), -1) for pixel in holes]
    return None if -1 in owners else owners


_Shell = tuple[list[_Directed], int, int]  # walk, twice its area, key of its lowest-leftmost pointel
_Hole = tuple[list[_Directed], int]  # walk, key


def _rings(asm: _Assembler, label: int) -> tuple[list[_Shell], list[_Hole]]:
    """The closed walks of a label split into shells (counter-clockwise) and holes, each sorted by key."""
    shells: list[_Shell] = []
    holes: list[_Hole] = []
    for lp in asm.loops(label):
        a2 = asm.loop_area2(lp)
        if a2 > 0:
            shells.append((lp, a2, asm.loop_key(lp)))
        else:
            holes.append((lp, asm.loop_key(lp)))
    shells.sort(key=lambda s: s[2])
    holes.sort(key=lambda h: h[1])
    return shells, holes


def _owners(asm: _Assembler, shells: Sequence[_Shell], holes: Sequence[_Hole], ps: PixelSet) -> list[int]:
    """The shell (index) that owns each hole."""
    if len(shells) == 1 or not holes:
        return [0] * len(holes)
    first = asm.first_left
    owners = _owners_by_components([first[s[0][0]] for s in shells], [first[h[0][0]] for h in holes], ps)
    if owners is None:
        owners = _owners_by_rings(
            [(a2, asm.loop_points(lp)) for lp, a2, _ in shells], [asm.loop_points(lp) for lp, _ in holes]
        )
    return owners


def _assemble_label(
    asm: _Assembler, label: int, polylines: Sequence[FloatArray], ps: PixelSet
) -> Polygon | MultiPolygon:
    shells, holes = _rings(asm, label)
    if not shells:
        return Polygon()
    owned: list[list[list[_Directed]]] = [[] for _ in shells]
    for (lp, _key), owner in zip(holes, _owners(asm, shells, holes, ps), strict=True):
        owned[owner].append(lp)  # in key order, as the holes are
    # every ring's coordinates, each shell followed by its holes, made into polygons in two vectorised calls
    coords: list[FloatArray] = []
    polygon_of: list[int] = []
    for k, ((lp, _a2, _key), hs) in enumerate(zip(shells, owned, strict=True)):
        coords.append(_ring_coords(lp, polylines, asm.loop))
        coords.extend(_ring_coords(h, polylines, asm.loop) for h in hs)
        polygon_of.extend([k] * (len(hs) + 1))
    sizes = [c.shape[0] for c in coords]
    rings = shapely.linearrings(np.concatenate(coords), indices=np.repeat(np.arange(len(coords)), sizes))
    polys = shapely.polygons(rings, indices=polygon_of)
    return polys[0] if len(polys) == 1 else shapely.multipolygons(polys)


#: Build the polylines with the compiled kernels (:mod:`mrm.geometry.reconstruct._subdivision_kernels`); the
#: Python functions of :mod:`._cell_polylines` are their definition, used for the chains the kernels leave
#: (int64 overflow) and by tests that replace a step of the construction.
_KERNEL = True


def _polylines(
    pts_all: IntArray, off: IntArray, points: Sequence[IntArray], closed: Sequence[bool]
) -> tuple[list[FloatArray], list[bool]]:
    """γ_c for every 1-cell as float64 plane coordinates, and whether each is the staircase."""
    m = len(points)
    if not _KERNEL or m == 0:
        chains = [_Chain(p, c) for p, c in zip(points, closed, strict=True)]
        done = [_polyline(ch) for ch in chains]
        return [_to_plane(ch, v) for ch, (v, _) in zip(chains, done, strict=True)], [s for _, s in done]

    lens = np.diff(off)
    starts = pts_all[off[:-1]]
    loc = pts_all - np.repeat(starts, lens, axis=0)
    status, count, verts = K.polylines_kernel(loc, off, np.asarray(closed, dtype=np.bool_), K.LIMIT)
    rank = np.arange(pts_all.shape[0], dtype=np.int64) - np.repeat(off[:-1], lens)
    used = rank < np.repeat(count, lens)
    x, y, e = verts[used, 0], verts[used, 1], verts[used, 2]
    # X = (Q − 1) / 2 in plane coordinates, Q = v / 2^e + 2·origin: exact in int64 and float64 while
    # |x + (2·ox − 1)·2^e| < 2^53; a chain beyond that goes through _to_plane (which refuses with a message)
    ox = np.repeat(2 * starts[:, 0] - 1, count)
    oy = np.repeat(2 * starts[:, 1] - 1, count)
    scale = np.exp2(e.astype(np.float64))
    far = (np.abs(ox) * scale + np.abs(x) >= 2.0**52) | (np.abs(oy) * scale + np.abs(y) >= 2.0**52)
    plane = np.empty((x.size, 2), dtype=np.float64)
    near = ~far
    sh = e[near]
    plane[near, 0] = np.ldexp((x[near] + (ox[near] << sh)).astype(np.float64), -(sh + 1))
    plane[near, 1] = np.ldexp((y[near] + (oy[near] << sh)).astype(np.float64), -(sh + 1))
    ends = np.zeros(m + 1, dtype=np.int64)
    np.cumsum(count, out=ends[1:])
    bounds = ends.tolist()
    polylines: list[FloatArray] = [plane[a:b] for a, b in itertools.pairwise(bounds)]
    stair = (status == K.STAIRCASE).tolist()
    for i in set(np.repeat(np.arange(m), count)[far].tolist()):  # far from the origin: exact or refused
        ch = _Chain(points[i], closed[i])
        rows = verts[off[i] : off[i] + count[i]].tolist()
        polylines[i] = _to_plane(ch, [(a, b, c) for a, b, c in rows])
    for i in np.flatnonzero(status == K.FALLBACK).tolist():  # left by the kernel: the Python definition
        ch = _Chain(points[i], closed[i])
        vs, stair[i] = _polyline(ch)
        polylines[i] = _to_plane(ch, vs)
    return polylines, stair


def subdivide(
    lm: LabelMap, model: str = "gauss", *, regions: LabelRegions | None = None, what: str | None = None
) -> Subdivision:
    """Reconstruct all the labels of a label map jointly (module docstring), with the 1-cell polylines.

    Parameters
    ----------
    lm : LabelMap
        The label map; label 0 and everything outside the array is the background.
    model : {"gauss"}
        The discretization model; only ``gauss`` admits a watertight subdivision.
    regions : LabelRegions, optional
        The map's :func:`~mrm.geometry.topology.labeling.label_regions`, when the caller has them already
        (polygonize): the cost check counts them instead of labelling the map again.
    what : str, optional
        How a refusal names the map (default "the label map").

    Returns
    -------
    Subdivision
        The parts and how they were built.

    Raises
    ------
    ParameterError
        For any model other than ``gauss``.
    LimitError
        Before any work, when the map has too many labels, boundary edges, or junctions and regions
        (:func:`mrm.core.limits.check_subdivision`; its cost follows from them, not from its pixels).
    """
    _check_model(model)
    check_cost(lm, what, regions=regions)
    with paused_gc():  # tens of thousands of small acyclic tuples and lists: no cycle to collect
        return _subdivide(lm)


def check_cost(lm: LabelMap, what: str | None = None, *, regions: LabelRegions | None = None) -> None:
    """Refuse a label map whose subdivision would cost too much (:func:`mrm.core.limits.check_subdivision`).

    Counts its labels and regions (one linear pass, unless ``regions`` gives them) and its boundary edges
    and junctions, before any work.
    """
    reg = label_regions(lm.labels) if regions is None else regions
    n_labels = int(np.unique(reg.label).size)
    check_subdivision(lm.labels, n_labels, int(reg.label.size), what)


def _subdivide(lm: LabelMap) -> Subdivision:
    cells = cells_of(lm)
    zero = {z.point for z in cells.zero_cells}
    cp = _cell_points(lm, cells)
    points = cp.each
    closed = [c.chain.start not in zero for c in cells.one_cells]
    polylines, stair = _polylines(cp.all, cp.off, points, closed)
    asm = _Assembler(lm, cells, cp)
    pixels = _label_pixel_sets(lm)
    labels = list(pixels)
    touching: dict[int, list[int]] = {v: [] for v in labels}
    for ci, c in enumerate(cells.one_cells):
        for v in (c.left, c.right):
            if v != 0:
                touching[v].append(ci)
    parts: dict[int, Polygon | MultiPolygon] = {}
    todo = list(labels)
    while todo:
        redo: set[int] = set()
        for v in todo:
            geom = _assemble_label(asm, v, polylines, pixels[v])
            parts[v] = geom
            if _part_ok(geom, pixels[v]):
                continue
            if all(stair[ci] for ci in touching[v]):  # the proven safety net: cannot fail
                raise AssertionError(f"the staircase of label {v} does not reconstruct it")
            for ci in touching[v]:
                if not stair[ci]:
                    stair[ci] = True
                    ch = _Chain(points[ci], closed[ci])
                    polylines[ci] = _to_plane(ch, [v_ for v_, _ in ch.staircase()])
                    c = cells.one_cells[ci]
                    redo.update(w for w in (c.left, c.right) if w != 0)
        todo = sorted(redo)
    return Subdivision(dict(sorted(parts.items())), tuple(polylines), tuple(stair), cells)


def _cell_points(lm: LabelMap, cells: Cells) -> _CellPoints:
    """The pointels of every 1-cell (``chain.points()``) and twice its signed area, in one pass.

    Returns all the pointels, the offsets of each cell's rows in them, the per-cell views and the areas.

    The area of a 1-cell is taken in the label map's array coordinates: only its sums around closed walks are
    used, which do not depend on the origin, and the numbers stay small.
    """
    ones = cells.one_cells
    if not ones:
        return _CellPoints(np.zeros((0, 2), dtype=np.int64), np.zeros(1, dtype=np.int64), [], [])
    lens = np.fromiter((len(c.chain.codes) for c in ones), dtype=np.int64, count=len(ones)) + 1
    off = np.zeros(len(ones) + 1, dtype=np.int64)
    np.cumsum(lens, out=off[1:])
    codes = np.frombuffer("".join(c.chain.codes for c in ones).encode("ascii"), dtype=np.uint8) - np.uint8(48)
    steps = np.zeros((int(off[-1]), 2), dtype=np.int64)
    linel = np.ones(int(off[-1]), dtype=bool)
    linel[off[:-1]] = False  # the first point of each cell is its start, not a step
    steps[linel, 0] = DX[codes]
    steps[linel, 1] = DY[codes]
    walk = np.cumsum(steps, axis=0)
    starts = np.array([c.chain.start for c in ones], dtype=np.int64)
    pts = walk + np.repeat(starts - walk[off[:-1]], lens, axis=0)
    rel = pts - np.asarray(lm.origin, dtype=np.int64)
    cross = rel[:-1, 0] * rel[1:, 1] - rel[1:, 0] * rel[:-1, 1]
    cross[off[1:-1] - 1] = 0  # from the last point of one cell to the first of the next
    area2 = np.add.reduceat(cross, off[:-1]) if cross.size else np.zeros(len(ones), dtype=np.int64)
    bounds = off.tolist()
    return _CellPoints(pts, off, [pts[a:b] for a, b in itertools.pairwise(bounds)], area2.tolist())


def _label_pixel_sets(lm: LabelMap) -> dict[int, PixelSet]:
    """The pixels of every non-zero label, each cropped to its own box (one pass over the array).

    Each label's mask is the comparison of its box with the label, unless the boxes together are much
    larger than the array (many nested labels), where the pixels are gathered by label instead.
    """
    lab = lm.labels
    if lab.size == 0:
        return {}

    x0, y0 = lm.origin
    vmax = int(lab.max())
    if vmax <= 4 * lab.size + 1024:
        boxes = label_boxes(lab, vmax)
        present = [v for v in np.flatnonzero(boxes[:, 0]).tolist() if v != 0]
        area = sum(int((boxes[v, 2] - boxes[v, 1] + 1) * (boxes[v, 4] - boxes[v, 3] + 1)) for v in present)
        if area <= 4 * lab.size:
            out: dict[int, PixelSet] = {}
            for v in present:
                _, r0, r1, c0, c1 = boxes[v].tolist()
                out[v] = PixelSet(lab[r0 : r1 + 1, c0 : c1 + 1] == v, (x0 + c0, y0 + r0))
            return out
    w = lab.shape[1]
    out = {}
    for v, idx in zip(*group_by_label(lab), strict=True):
        if v == 0:
            continue
        rows, cols = idx // w, idx % w
        r0, c0 = int(rows[0]), int(cols.min())
        m = np.zeros((int(rows[-1]) - r0 + 1, int(cols.max()) - c0 + 1), dtype=bool)
        m[rows - r0, cols - c0] = True
        out[v] = PixelSet(m, (x0 + c0, y0 + r0))
    return out


def _part_ok(geom: Polygon | MultiPolygon, ps: PixelSet) -> bool:
    """Exactly: a valid geometry whose gauss discretization is ps."""
    if not shapely.is_valid(geom):
        return False
    # a valid (multi)polygon has valid members: discretize without checking them a second time
    return bool(_discretize_pieces(_take_apart(geom, check_validity=False), "gauss", None) == ps)


def reconstruct_label_map(
    lm: LabelMap, model: str = "gauss", *, what: str | None = None
) -> dict[int, Polygon | MultiPolygon]:
    """Reconstruct every label of a label map as a watertight subdivision (module docstring).

    Parameters
    ----------
    lm : LabelMap
        The label map (label 0 is the background).
    model : {"gauss"}
        Only ``gauss``: D_gauss(P_L) equals the pixels of L for every label L.
    what : str, optional
        How a refusal of its cost names the map (:func:`subdivide`).

    Returns
    -------
    dict of int to Polygon or MultiPolygon
        ``{label: P_L}`` for every non-zero label present, in increasing order. Neighbouring parts share
        their boundary edges exactly (same float64 end points), so they have disjoint interiors and no gaps.

    Raises
    ------
    ParameterError
        For a model other than ``gauss``.
    """
    return subdivide(lm, model, what=what).parts


def watertight_parts(parts: Sequence[PixelSet]) -> list[Polygon | MultiPolygon]:
    """Reconstruct disjoint pixel sets (e.g. the three parts of a co-refinement) as a watertight subdivision.

    Parameters
    ----------
    parts : sequence of PixelSet
        Pairwise disjoint pixel sets; part k gets label k + 1.

    Returns
    -------
    list of Polygon or MultiPolygon
        One geometry per part, in order (an empty Polygon for an empty part), with D_gauss(result[k]) ==
        parts[k] exactly and shared boundaries between neighbouring parts.

    Raises
    ------
    ParameterError
        When two parts overlap (from :meth:`LabelMap.from_pixel_sets`).
    """
    parts = list(parts)
    if not parts:
        return []
    try:
        lm = LabelMap.from_pixel_sets(parts)
    except ValueError as e:
        raise ParameterError(f"the parts of a subdivision must be disjoint: {e}") from None
    by_label = reconstruct_label_map(lm, "gauss", what="the parts together")
    return [by_label.get(k + 1, Polygon()) for k in range(len(parts))]
