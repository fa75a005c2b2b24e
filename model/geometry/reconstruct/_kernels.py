"""Numba kernels of the reversible continuation R (see :mod:`mrm.geometry.reconstruct`).

Everything here works in *array* coordinates (pixel (c, r) is ``mask[r, c]``) and in **Q-units**, a
quarter of a pixel: the centre of pixel (c, r) is (4c, 4r) and pointel (i, j), the lower-left corner of pixel
(i, j), is (4i − 2, 4j − 2). Every corner, side midpoint, centre and safety-net vertex is then an integer.

The pipeline for one crack ring (object on the left):

1. *elements* — the 4-connected border path: one element per maximal run of linels with the same inner
   pixel, plus an *elbow* element at every right turn (docs/algorithms.md §2.5);
2. *pieces* — open axis-parallel rectangles the ring may pass through, in path order, and the *gates* (open
   segments) between consecutive pieces. Cover models: a pixel visited once is one full-square piece; a
   pixel visited several times (one-pixel-wide parts) gets one part per visit, the part on the outer side
   of the centre polyline. ``gauss`` builds the dual corridor instead (:mod:`._dual`, ADR 0012)
   and runs the same later steps on it;
3. *reach* — for each start piece i, the farthest piece j such that one line crosses gates i+1 … j in
   order: arithmetic standard-DSS recognition when every piece is a full pixel, an exact incremental
   preimage (dual polygon, integer orientation tests) otherwise; and a central line of that preimage;
4. *V4 greedy* — consecutive chosen lines meet inside a piece of their overlap, otherwise a patch (two
   vertices in one piece);
5. *snap* — each vertex to the coarsest dyadic grid that keeps every constraint (exact integer checks);
5b. *straighten* — each edge moved onto the simplest line (least |dx| + |dy|, offset centred) that crosses
   the gates of the pieces it covers, where the moved vertices still verify (same vertex count);
6. *verify* — exact: every vertex strictly inside its piece, every edge crossing its gates strictly inside
   and in order, no fold, no crossing between edges meeting in a piece. Pieces of different visits are
   disjoint, so a verified ring is simple and disjoint from the other rings;
7. *repair* — local: the failing stretch is replaced by the safety net R0 (the crack ring offset inward by
   ¼ pixel, which is always a valid ring of the same corridor) spliced in with two vertices at each end;
   the whole ring becomes R0 only if that does not verify.

Where each step lives: elements and pieces in :mod:`._corridor`, the reach in :mod:`._reach`, the
greedy in :mod:`._greedy`, snapping and the exact checks in :mod:`._check`, splicing in :mod:`._splice`,
pruning in :mod:`._prune`, merging in :mod:`._merge`, relinking in :mod:`._relink`, the window bound and the
small-corridor searches in :mod:`._small_search`, straightening in :mod:`._straighten`, the
minimum-link rings (Suri's windows, tried on rings still above their window bound) in :mod:`._minlink`,
shared constants in :mod:`._base`; this module runs them over all rings (the ``*_all`` phases) and
re-exports them, so callers import one module.

Integer checks use coordinates scaled by 2^K with K chosen per ring so that every product of two
coordinate differences stays below 2⁶² (no overflow, no rounding).
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import njit
from mrm.geometry.reconstruct._base import (
    _BIG,
    _DX,
    _DY,
    _EPS,
    _LXD,
    _LYD,
    _RELINK_MAX,
    _SMALL,
    _SMALL_POLY,
    RING_NET,
    RING_PARTIAL,
    RING_SINGLE,
    RING_V4,
    SRC_LINES,
    SRC_NET,
    SRC_PATCH,
    SRC_SINGLE,
    SRC_SPLICE,
    Corridors,
    Greedy,
    Rings,
    _cp1,
    _cp2,
    _grow1,
    _grow2,
)
from mrm.geometry.reconstruct._check import (
    _in_piece,
    _on_seg,
    _orient,
    _sgn,
    edge_ok,
    segments_meet,
    snap_ring,
    verify_ring,
)
from mrm.geometry.reconstruct._corridor import (
    _rect_of,
    build_elements,
    build_pieces,
    element_visits,
    net_pieces,
)
from mrm.geometry.reconstruct._greedy import (
    _chord_point,
    _gate_param,
    _inside_rect,
    _locate,
    _meet,
    _v4_periodic,
    ring_reach,
    v4_greedy,
)
from mrm.geometry.reconstruct._merge import _clip_poly, _merge_pair, merge_ring
from mrm.geometry.reconstruct._minlink import minlink_ring
from mrm.geometry.reconstruct._prune import prune_ring
from mrm.geometry.reconstruct._reach import (
    _QUAD_X,
    _QUAD_Y,
    _best_line,
    _clip,
    _init_poly,
    _vline,
    dss_reach,
    general_reach,
)
from mrm.geometry.reconstruct._relink import _unwrap6, relink_ring
from mrm.geometry.reconstruct._small_search import small_polygon, small_triangle, window_bound
from mrm.geometry.reconstruct._splice import _net_crossing, _seg_point_in_rect, splice_ring
from mrm.geometry.reconstruct._straighten import (
    _edge_line,
    _local_ok,
    _meet_int,
    _place,
    _ring_attempt,
    _simplest_edge_line,
    _vget,
    _window_fit,
    simplest_line,
    straighten_ring,
)
from mrm.geometry.reconstruct._twins import TWIN

# The phases live in the sibling _base, _check, _corridor, … modules; this module runs them and keeps one
# import for callers.
__all__ = [
    "RING_NET",
    "RING_PARTIAL",
    "RING_SINGLE",
    "RING_V4",
    "SRC_LINES",
    "SRC_NET",
    "SRC_PATCH",
    "SRC_SINGLE",
    "SRC_SPLICE",
    "_BIG",
    "_DX",
    "_DY",
    "_EPS",
    "_LXD",
    "_LYD",
    "_QUAD_X",
    "_QUAD_Y",
    "_RELINK_MAX",
    "_SMALL",
    "_SMALL_POLY",
    "Corridors",
    "Greedy",
    "Rings",
    "_best_line",
    "_chord_point",
    "_clip",
    "_clip_poly",
    "_cp1",
    "_cp2",
    "_domino",
    "_edge_line",
    "_gate_param",
    "_grow1",
    "_grow2",
    "_in_piece",
    "_init_poly",
    "_inside_rect",
    "_kmax_for",
    "_local_ok",
    "_locate",
    "_meet",
    "_meet_int",
    "_merge_pair",
    "_net_crossing",
    "_net_ring",
    "_on_seg",
    "_orient",
    "_place",
    "_push",
    "_rect_of",
    "_ring_attempt",
    "_seg_point_in_rect",
    "_sgn",
    "_simplest_edge_line",
    "_unwrap6",
    "_v4_periodic",
    "_vget",
    "_vline",
    "_window_fit",
    "build_elements",
    "build_pieces",
    "check_nets",
    "corridors_all",
    "dss_reach",
    "edge_ok",
    "element_visits",
    "finish_all",
    "general_reach",
    "greedy_all",
    "merge_ring",
    "minlink_ring",
    "net_pieces",
    "prune_ring",
    "reach_all",
    "relink_ring",
    "ring_reach",
    "segments_meet",
    "simplest_line",
    "small_polygon",
    "small_triangle",
    "snap_ring",
    "splice_ring",
    "straighten_ring",
    "v4_greedy",
    "verify_ring",
    "window_bound",
]


# ============================================================================================ driver


@njit(cache=True)
def _domino(
    c0: int, r0_: int, c1: int, r1: int, sc: int
) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover
    # Cover models, two 4-adjacent pixels visited once each: a counter-clockwise triangle with its vertices
    # inside the open squares, crossing the common side twice (scale sc Q-units). (Under gauss the two
    # pixels are split like every element and the greedy handles them.)
    ux = c1 - c0
    uy = r1 - r0_  # from the first pixel to the second
    vx_ = -uy
    vy_ = ux  # to the left of u
    cx = 4 * c0
    cy = 4 * r0_
    # (a, b) in 1/16 pixel along u and v from the first centre
    pa = np.array([-4, 16 + 4, 12], np.int64)
    pb = np.array([-4, -4, 4], np.int64)
    x = np.empty(3, np.int64)
    y = np.empty(3, np.int64)
    for i in range(3):
        x[i] = cx * sc + (pa[i] * ux + pb[i] * vx_) * sc // 4
        y[i] = cy * sc + (pa[i] * uy + pb[i] * vy_) * sc // 4
    return x, y


@njit(cache=True)
def _kmax_for(rect: np.ndarray) -> int:  # pragma: no cover
    xmin = rect[0, 0]
    xmax = rect[0, 1]
    ymin = rect[0, 2]
    ymax = rect[0, 3]
    for i in range(rect.shape[0]):
        xmin = min(xmin, rect[i, 0])
        xmax = max(xmax, rect[i, 1])
        ymin = min(ymin, rect[i, 2])
        ymax = max(ymax, rect[i, 3])
    ext = max(xmax - xmin, ymax - ymin) + 1
    bits = 0
    while (1 << bits) < ext:
        bits += 1
    k = 30 - bits
    if k > 20:
        k = 20
    if k < 2:
        k = 2
    return k


@njit(cache=True)
def _net_ring(
    r0: np.ndarray, r0t: np.ndarray, kmax: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    sc = 1 << kmax
    m = r0t.size
    ox = np.empty(m, np.int64)
    oy = np.empty(m, np.int64)
    ot = np.empty(m, np.int64)
    osrc = np.full(m, SRC_NET, np.int64)
    for i in range(m):
        ox[i] = r0[i, 0] * sc
        oy[i] = r0[i, 1] * sc
        ot[i] = r0t[i]
    return ox, oy, ot, osrc


# The driver runs in four phases, each over all rings at once and each called from Python: numba
# re-optimises a caller together with everything it calls, so one deep driver compiles the whole call tree
# several times over; flat phases compile each part once.


@njit(cache=True)
def corridors_all(
    codes: np.ndarray, off: np.ndarray, sx: np.ndarray, sy: np.ndarray, h: int, w: int, kcap: int
) -> Corridors:  # pragma: no cover
    """Phase 1: border-path elements, visit counts, pieces, gates and net vertices of every ring.

    See :class:`._base.Corridors` for what each array holds.
    """
    eoff, ec, er, edin, edout, enl, r0off, r0, r0e = build_elements(codes, off, sx, sy)
    cnt = element_visits(ec, er, h, w)
    nr = off.size - 1
    cap = 2 * ec.size + 2 * nr + 2
    rect = np.empty((cap, 4), np.int32)
    pel = np.empty(cap, np.int32)
    gp = np.empty((cap, 2), np.int32)
    gq = np.empty((cap, 2), np.int32)
    gdir = np.empty(cap, np.int8)
    poff = np.zeros(nr + 1, np.int64)
    kmax = np.zeros(nr, np.int64)
    special = np.zeros(nr, np.int64)
    full = np.zeros(nr, np.int64)
    r0t = np.full(r0.shape[0], -1, np.int32)
    pos = 0
    for k in range(nr):
        e0 = eoff[k]
        e1 = eoff[k + 1]
        if e1 - e0 == 1 and enl[e0] == 4:
            special[k] = 1
            kmax[k] = 2
            poff[k + 1] = pos
            continue
        rc, pl, p, q, g, fl = build_pieces(e0, e1, ec, er, edin, edout, enl, cnt)
        n = g.size
        _cp2(rect, pos, rc)
        _cp1(pel, pos, pl)
        _cp2(gp, pos, p)
        _cp2(gq, pos, q)
        _cp1(gdir, pos, g)
        full[k] = fl[0]
        if e1 - e0 == 2 and fl[0] == 1:
            special[k] = 2
        kmax[k] = min(_kmax_for(rc), kcap)
        r0l = np.empty(r0off[k + 1] - r0off[k], np.int32)
        for i in range(r0l.size):
            r0l[i] = r0e[r0off[k] + i] - e0
        _cp1(r0t, r0off[k], net_pieces(r0[r0off[k] : r0off[k + 1]], r0l, rc, pl))
        pos += n
        poff[k + 1] = pos
    return Corridors(
        eoff,
        ec,
        er,
        edin,
        edout,
        enl,
        cnt,
        r0off,
        r0,
        r0t,
        poff,
        rect[:pos],
        pel[:pos],
        gp[:pos],
        gq[:pos],
        gdir[:pos],
        kmax,
        special,
        full,
    )


@njit(cache=True)
def reach_all(cor: Corridors, reach: np.ndarray, lines: np.ndarray) -> None:  # pragma: no cover
    """Phase 2: the reach table and the central lines of every ring's pieces, into ``reach``, ``lines``.

    Both have a row per piece of all rings; only the rings of ``cor`` are written (threads share them).
    """
    eoff, ec, er, cnt, poff, pel, rect = cor.eoff, cor.ec, cor.er, cor.cnt, cor.poff, cor.pel, cor.rect
    gp, gq, gdir, special, full = cor.gp, cor.gq, cor.gdir, cor.special, cor.full
    for k in range(eoff.size - 1):
        a = poff[k]
        b = poff[k + 1]
        if special[k] == 1 or special[k] == TWIN or b == a:
            continue
        ring_reach(
            eoff[k],
            eoff[k + 1],
            ec,
            er,
            cnt,
            full[k] == 1,
            pel[a:b],
            rect[a:b],
            gp[a:b],
            gq[a:b],
            gdir[a:b],
            reach[a:b],
            lines[a:b],
        )


@njit(cache=True)
def greedy_all(
    cor: Corridors, reach: np.ndarray, lines: np.ndarray, periodic: bool
) -> Greedy:  # pragma: no cover
    """Phase 3: the V4 greedy on every ring (one closing rule): see :class:`._base.Greedy`."""
    poff, rect, gp, gq, special = cor.poff, cor.rect, cor.gp, cor.gq, cor.special
    nr = poff.size - 1
    cap = 16
    fv = np.empty((cap, 2), np.float64)
    vt = np.empty(cap, np.int64)
    vs = np.empty(cap, np.int64)
    vl = np.empty(cap, np.int64)
    voff = np.zeros(nr + 1, np.int64)
    ok = np.zeros(nr, np.bool_)
    pos = 0
    for k in range(nr):
        a = poff[k]
        b = poff[k + 1]
        if special[k] == 0 and b > a:
            f, t, sr, ln, good = v4_greedy(reach[a:b], lines[a:b], rect[a:b], gp[a:b], gq[a:b], periodic)
            m = t.size
            if good and m >= 3:
                if pos + m > cap:
                    ncap = 2 * cap + m
                    fv = _grow2(fv, pos, ncap)
                    vt = _grow1(vt, pos, ncap)
                    vs = _grow1(vs, pos, ncap)
                    vl = _grow1(vl, pos, ncap)
                    cap = ncap
                _cp2(fv, pos, f)
                _cp1(vt, pos, t)
                _cp1(vs, pos, sr)
                _cp1(vl, pos, ln)
                pos += m
                ok[k] = True
        voff[k + 1] = pos
    return Greedy(fv[:pos], vt[:pos], vs[:pos], vl[:pos], voff, ok)


@njit(cache=True)
def _push(
    xy: np.ndarray,
    src: np.ndarray,
    win: np.ndarray,
    pos: int,
    x: np.ndarray,
    y: np.ndarray,
    s: np.ndarray,
    ln: np.ndarray,
    kk: int,
    x0: int,
    y0: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:  # pragma: no cover
    # Append one closed ring (plane coordinates) to the output buffers, growing them when needed.
    m = x.size
    if pos + m + 1 > xy.shape[0]:
        ncap = 2 * xy.shape[0] + m + 1
        xy = _grow2(xy, pos, ncap)
        src = _grow1(src, pos, ncap)
        win = _grow1(win, pos, ncap)
    f = 1.0 / float(1 << (kk + 2))
    for i in range(m):
        xy[pos + i, 0] = x0 + x[i] * f
        xy[pos + i, 1] = y0 + y[i] * f
        src[pos + i] = s[i]
        win[pos + i] = ln[i]
    xy[pos + m, 0] = xy[pos, 0]
    xy[pos + m, 1] = xy[pos, 1]
    src[pos + m] = -1
    win[pos + m] = -1
    return xy, src, win, pos + m + 1


@njit(cache=True)
def finish_all(
    cor: Corridors, reach: np.ndarray, ga: Greedy, gb: Greedy, x0: int, y0: int
) -> Rings:  # pragma: no cover
    """Phase 4: snap, verify, prune and (locally) repair every ring; emit closed rings in plane coordinates.

    Two greedy results per ring (a: periodic closing, b: closing on the first line): the one with fewer
    vertices is tried first, then the other; if neither verifies, the better one is repaired with the safety
    net. See :class:`._base.Rings` for what it returns.
    """
    eoff, ec, er, poff, rect = cor.eoff, cor.ec, cor.er, cor.poff, cor.rect
    gp, gq, gdir, kmax, special = cor.gp, cor.gq, cor.gdir, cor.kmax, cor.special
    r0off, r0, r0t = cor.r0off, cor.r0, cor.r0t
    fa, ta, sa, la, oa, ka = ga
    fb, tb, sb, lb, ob, kb = gb
    nr = eoff.size - 1
    cap = 4 * r0.shape[0] + 8 * nr + 16
    xy = np.empty((cap, 2), np.float64)
    src = np.empty(cap, np.int64)
    win = np.empty(cap, np.int64)
    roff = np.zeros(nr + 1, np.int64)
    status = np.zeros(nr, np.int64)
    pos = 0
    for k in range(nr):
        e0 = eoff[k]
        a = poff[k]
        b = poff[k + 1]
        kk = kmax[k]
        sc = 1 << kk
        if special[k] == TWIN:
            roff[k + 1] = pos  # its twin's ring, moved, replaces this empty one (._twins.fill_twins)
            continue
        if special[k] == 1:
            cx = 4 * ec[e0]
            cy = 4 * er[e0]
            x = np.empty(3, np.int64)
            y = np.empty(3, np.int64)
            x[0] = (cx - 1) * sc
            x[1] = (cx + 1) * sc
            x[2] = cx * sc
            y[0] = (cy - 1) * sc
            y[1] = (cy - 1) * sc
            y[2] = (cy + 1) * sc
            s3 = np.full(3, SRC_SINGLE, np.int64)
            xy, src, win, pos = _push(xy, src, win, pos, x, y, s3, np.full(3, -1, np.int64), kk, x0, y0)
            status[k] = RING_SINGLE
            roff[k + 1] = pos
            continue
        if special[k] == 2:
            x, y = _domino(ec[e0], er[e0], ec[e0 + 1], er[e0 + 1], sc)
            s3 = np.full(3, SRC_SINGLE, np.int64)
            xy, src, win, pos = _push(xy, src, win, pos, x, y, s3, np.full(3, -1, np.int64), kk, x0, y0)
            status[k] = RING_SINGLE
            roff[k + 1] = pos
            continue
        rc = rect[a:b]
        p = gp[a:b]
        q = gq[a:b]
        g = gdir[a:b]
        rv = r0[r0off[k] : r0off[k + 1]]
        rt = r0t[r0off[k] : r0off[k + 1]]
        done = False
        # candidates in order of vertex count
        na_ = oa[k + 1] - oa[k] if ka[k] else 1 << 60
        nb_ = ob[k + 1] - ob[k] if kb[k] else 1 << 60
        first_b = nb_ < na_
        best_x = np.zeros(0, np.int64)
        best_y = np.zeros(0, np.int64)
        best_t = np.zeros(0, np.int64)
        best_s = np.zeros(0, np.int64)
        best_bad = np.zeros(0, np.bool_)
        for attempt in range(2):
            use_b = first_b if attempt == 0 else not first_b
            if use_b:
                if not kb[k]:
                    continue
                fv = fb[ob[k] : ob[k + 1]]
                vt = tb[ob[k] : ob[k + 1]]
                vs = sb[ob[k] : ob[k + 1]]
                vl = lb[ob[k] : ob[k + 1]]
            else:
                if not ka[k]:
                    continue
                fv = fa[oa[k] : oa[k + 1]]
                vt = ta[oa[k] : oa[k + 1]]
                vs = sa[oa[k] : oa[k + 1]]
                vl = la[oa[k] : oa[k + 1]]
            m = vt.size
            ix = np.empty(m, np.int64)
            iy = np.empty(m, np.int64)
            bad = np.zeros(m, np.bool_)
            fx = np.empty(m, np.float64)
            fy = np.empty(m, np.float64)
            for i in range(m):
                fx[i] = fv[i, 0]
                fy[i] = fv[i, 1]
            snap_ring(fx, fy, vt, rc, p, q, g, kk, ix, iy, bad)
            bad2 = np.zeros(m, np.bool_)
            good = verify_ring(ix, iy, vt, rc, p, q, g, sc, bad2)
            for i in range(m):
                if bad[i]:
                    good = False
                    bad2[i] = True
            if not good:
                # a redundant vertex may be the culprit (three in one piece crossing): prune and re-check
                jx, jy, jt, js, jl = prune_ring(ix, iy, vt, vs, vl, rc, p, q, g, sc, False)
                if jt.size >= 3 and jt.size < m:
                    jbad = np.zeros(jt.size, np.bool_)
                    if verify_ring(jx, jy, jt, rc, p, q, g, sc, jbad):
                        ix, iy, vt, vs, vl = jx, jy, jt, js, jl
                        good = True
            if good:
                px, py, pt, ps, pl = prune_ring(ix, iy, vt, vs, vl, rc, p, q, g, sc)
                px, py, pt, ps, pl = merge_ring(px, py, pt, ps, pl, rc, p, q, g, kk)
                # the window bound depends only on the reach table: computed once per ring, for the three
                # searches below (on large rings it walks the greedy chain from every start of the longest
                # window); each of them needs more than three vertices
                wb = window_bound(reach[a:b]) if px.size > 3 else 0
                if 6 <= px.size <= _RELINK_MAX and px.size > wb:
                    px, py, pt, ps, pl = relink_ring(px, py, pt, ps, pl, rc, p, q, g, reach[a:b], kk)
                if px.size > 3 and b - a <= _SMALL_POLY:
                    # a small corridor: search for the fewest vertices its windows allow (3 or 4)
                    lbv = max(3, wb)
                    for nvv in range(lbv, min(px.size - 1, 4) + 1):
                        tx, ty, tt, okt = small_polygon(rc, p, q, g, reach[a:b], kk, nvv)
                        if okt:
                            px = tx
                            py = ty
                            pt = tt
                            ps = np.full(nvv, SRC_LINES, np.int64)
                            pl = np.full(nvv, -1, np.int64)
                            break
                # ---- minimum-link ring (ADR 0031), only where the ring is still above its window bound
                if px.size > 4 and b - a > _SMALL_POLY and px.size > wb:
                    px, py, pt, ps, pl = minlink_ring(px, py, pt, ps, pl, rc, p, q, g, reach[a:b], kk)
                # ----
                px, py, pt, ps, pl = straighten_ring(px, py, pt, ps, pl, rc, p, q, g, kk)
                xy, src, win, pos = _push(xy, src, win, pos, px, py, ps, pl, kk, x0, y0)
                status[k] = RING_V4
                done = True
                break
            if best_t.size == 0:
                best_x = ix
                best_y = iy
                best_t = vt.copy()
                best_s = vs.copy()
                best_bad = bad2
        if not done and b - a <= _SMALL:
            # no greedy ring verified: a small corridor may still hold a triangle (a 1 x 3 bar under gauss)
            tx, ty, tt, okt = small_triangle(rc, p, q, g, reach[a:b], kk)
            if okt:
                tbad = np.zeros(3, np.bool_)
                if verify_ring(tx, ty, tt, rc, p, q, g, sc, tbad):
                    s3 = np.full(3, SRC_LINES, np.int64)
                    xy, src, win, pos = _push(
                        xy, src, win, pos, tx, ty, s3, np.full(3, -1, np.int64), kk, x0, y0
                    )
                    status[k] = RING_V4
                    done = True
        if not done and best_t.size >= 3:
            # local repair: widen the removed runs until the spliced ring verifies
            m = best_t.size
            remove = best_bad.copy()
            for _attempt in range(6):
                nrm = 0
                for i in range(m):
                    if remove[i]:
                        nrm += 1
                if nrm >= m - 1:
                    break
                sx_, sy_, st_, ss_, oks = splice_ring(
                    best_x, best_y, best_t, best_s, remove, rv, rt, rc, p, g, kk
                )
                if oks and st_.size >= 3:
                    bad3 = np.zeros(st_.size, np.bool_)
                    if verify_ring(sx_, sy_, st_, rc, p, q, g, sc, bad3):
                        sl_ = np.full(st_.size, -1, np.int64)
                        px, py, pt, ps, pl = prune_ring(sx_, sy_, st_, ss_, sl_, rc, p, q, g, sc)
                        px, py, pt, ps, pl = merge_ring(px, py, pt, ps, pl, rc, p, q, g, kk)
                        xy, src, win, pos = _push(xy, src, win, pos, px, py, ps, pl, kk, x0, y0)
                        status[k] = RING_PARTIAL
                        done = True
                        break
                grown = remove.copy()
                for i in range(m):
                    if remove[i]:
                        grown[(i - 1) % m] = True
                        grown[(i + 1) % m] = True
                remove = grown
        if not done:
            ox, oy, ot, osrc = _net_ring(rv, rt, kk)
            xy, src, win, pos = _push(
                xy, src, win, pos, ox, oy, osrc, np.full(ot.size, -1, np.int64), kk, x0, y0
            )
            status[k] = RING_NET
        roff[k + 1] = pos
    return Rings(xy[:pos], roff, status, src[:pos], win[:pos])


@njit(cache=True)
def check_nets(
    poff: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: np.ndarray,
    special: np.ndarray,
    r0off: np.ndarray,
    r0: np.ndarray,
    r0t: np.ndarray,
) -> np.ndarray:  # pragma: no cover
    """Whether each ring's safety net passes the exact corridor check (it always should; tests assert it)."""
    nr = poff.size - 1
    out = np.ones(nr, np.bool_)
    for k in range(nr):
        a = poff[k]
        b = poff[k + 1]
        if special[k] == 1:
            continue
        rt = r0t[r0off[k] : r0off[k + 1]]
        for i in range(rt.size):
            if rt[i] < 0:
                out[k] = False
        if not out[k]:
            continue
        ox, oy, ot, _s = _net_ring(r0[r0off[k] : r0off[k + 1]], rt, kmax[k])
        bad = np.zeros(ot.size, np.bool_)
        out[k] = verify_ring(ox, oy, ot, rect[a:b], gp[a:b], gq[a:b], gdir[a:b], 1 << kmax[k], bad)
    return out
