"""Numba kernels of the ``gauss`` corridor: the dual squares of the crack pointels.

Reference: docs/design.md §3, item 2.

Under ``gauss`` a polygon P gives back A when every centre of A is strictly inside P and every other centre
strictly outside. The *dual square* of a pointel is the open unit square whose corners are the four pixel
centres around it; the *dual gate* of a linel is the open segment between the two centres on either side
of it. For one crack ring (object on the left) the corridor is the sequence of the dual squares of its
pointels, in chain order, joined by the dual gates of its linels. This is the corridor of the cover models
shifted by half a pixel, with pointels in the role of pixels:

* it holds no pixel centre (centres are corners of dual squares and ends of gates), so a ring that keeps
  every vertex strictly inside a piece and crosses the gates strictly inside, in order, once around, is
  homotopic to its crack ring in the plane minus the centres: it winds once around the centres of A on its
  left and zero times around the others, and no centre lies on it — so D_gauss(P) = A and no centre is on
  ∂P (ADR 0004 gives the same argument for the label-map subdivision);
* a dual square lies in the four voxels around its pointel, which are border pixels on one side or the
  other (the 2 × 2 block holds pixels of A and of the complement), so ∂P stays within the voxels of the
  border pixels;
* a pointel met twice (two pixels of A touching only at that corner; the (4, 8) tracing turns left there
  to keep its own pixel) gives each visit the quarter of its dual square next to its own pixel's centre:
  the two quarters are disjoint, so rings stay simple and pairwise disjoint and the two pixels end in
  different polygons (the (4, 8) topology).

Everything else (reach, V4 greedy, snapping, exact verification, local repair) is the cover pipeline of
:mod:`._kernels`, run in the *dual frame*: pointel (i, j) plays the pixel (i, j), whose centre
is (4i, 4j) in Q-units; plane coordinates are the dual ones minus half a pixel.

The safety net is the crack ring itself (its turning pointels, centres of their dual squares), with the
corner at a twice-met pointel moved a quarter pixel diagonally into that visit's quarter.
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import njit
from mrm.geometry.reconstruct._base import _DX, _DY, Corridors, _cp1, _cp2
from mrm.geometry.reconstruct._corridor import _rect_of, element_visits, side_gate
from mrm.geometry.reconstruct._kernels import _kmax_for


@njit(cache=True)
def _gates(rect: np.ndarray, gp: np.ndarray, gq: np.ndarray, gdir: np.ndarray) -> None:  # pragma: no cover
    # Gate k between piece k−1 and piece k: the common side of the two rectangles, oriented so that gp is
    # its left end and gq its right end when crossing in direction gdir.
    n = rect.shape[0]
    for k in range(n):
        a = (k - 1) % n
        side_gate(rect, a, k, gp, gq, gdir)


@njit(cache=True)
def dual_elements(
    codes: np.ndarray, off: np.ndarray, sx: np.ndarray, sy: np.ndarray, h: int, w: int
) -> tuple[
    np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray
]:  # pragma: no cover
    """The pointels of every ring as dual elements, and how many times each pointel is met.

    Returns ``eoff`` (ring offsets), ``ec, er`` (pointel, array coordinates), ``edin, edout`` (the codes of
    the linels into and out of it), ``enl`` (1 everywhere: one piece per element) and ``cnt`` (per element:
    how many times its pointel is met over all rings, saturated at 2; pointels are in [0, w] × [0, h]).
    """
    nr = off.size - 1
    lt = codes.size
    ec = np.empty(lt, np.int32)
    er = np.empty(lt, np.int32)
    edin = np.empty(lt, np.int8)
    edout = np.empty(lt, np.int8)
    enl = np.ones(lt, np.int8)
    eoff = np.zeros(nr + 1, np.int64)
    for k in range(nr):
        o0 = off[k]
        n = off[k + 1] - o0
        x = sx[k]
        y = sy[k]
        for i in range(n):
            d = codes[o0 + i]
            ec[o0 + i] = x
            er[o0 + i] = y
            edin[o0 + i] = codes[o0 + (i - 1) % n]
            edout[o0 + i] = d
            x += _DX[d]
            y += _DY[d]
        eoff[k + 1] = o0 + n
    return eoff, ec, er, edin, edout, enl, element_visits(ec, er, h + 1, w + 1)


@njit(cache=True)
def dual_pieces(
    e0: int,
    e1: int,
    ec: np.ndarray,
    er: np.ndarray,
    edin: np.ndarray,
    edout: np.ndarray,
    cnt: np.ndarray,
) -> tuple[
    np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray
]:  # pragma: no cover
    """Pieces, gates and safety-net vertices of the ring whose dual elements are e0 … e1−1 (dual Q-units).

    Returns ``rect`` (n, 4), ``pel`` (element of each piece, local), ``gp``, ``gq``, ``gdir`` (as
    :func:`._kernels.build_pieces`), ``full`` (1 if no pointel is met twice), ``r0`` (net
    vertices, (m, 2)) and ``r0t`` (the local piece of each net vertex).
    """
    n = e1 - e0
    rect = np.empty((n, 4), np.int32)
    pel = np.empty(n, np.int32)
    r0 = np.empty((n, 2), np.int32)
    r0t = np.empty(n, np.int32)
    full = 1
    nv = 0
    for k in range(n):
        e = e0 + k
        c = ec[e]
        r = er[e]
        din = edin[e]
        dout = edout[e]
        pel[k] = k
        if cnt[e] < 2:
            _rect_of(c, r, 0, 0, rect, k)
            if din != dout:
                r0[nv, 0] = 4 * c
                r0[nv, 1] = 4 * r
                r0t[nv] = k
                nv += 1
        else:
            full = 0
            # the quarter next to the pixel on the left of both linels (the visit's own pixel)
            hx = _DX[(din + 1) & 3] + _DX[(dout + 1) & 3]
            hy = _DY[(din + 1) & 3] + _DY[(dout + 1) & 3]
            _rect_of(c, r, hx, hy, rect, k)
            r0[nv, 0] = 4 * c + (1 if hx > 0 else -1)
            r0[nv, 1] = 4 * r + (1 if hy > 0 else -1)
            r0t[nv] = k
            nv += 1
    gp = np.empty((n, 2), np.int32)
    gq = np.empty((n, 2), np.int32)
    gdir = np.empty(n, np.int8)
    _gates(rect, gp, gq, gdir)
    return rect, pel, gp, gq, gdir, np.array([full], np.int64), r0[:nv], r0t[:nv]


@njit(cache=True)
def dual_corridors_all(
    codes: np.ndarray, off: np.ndarray, sx: np.ndarray, sy: np.ndarray, h: int, w: int, kcap: int
) -> Corridors:  # pragma: no cover
    """Phase 1 under ``gauss``: the same :class:`._base.Corridors` as :func:`._kernels.corridors_all`.

    Everything is in the dual frame (pointel (i, j) at (4i, 4j) Q-units); ``special`` is 0 for every ring.
    """
    eoff, ec, er, edin, edout, enl, cnt = dual_elements(codes, off, sx, sy, h, w)
    nr = off.size - 1
    cap = ec.size
    rect = np.empty((cap, 4), np.int32)
    pel = np.empty(cap, np.int32)
    gp = np.empty((cap, 2), np.int32)
    gq = np.empty((cap, 2), np.int32)
    gdir = np.empty(cap, np.int8)
    r0 = np.empty((cap, 2), np.int32)
    r0t = np.empty(cap, np.int32)
    poff = np.zeros(nr + 1, np.int64)
    r0off = np.zeros(nr + 1, np.int64)
    kmax = np.zeros(nr, np.int64)
    special = np.zeros(nr, np.int64)
    full = np.zeros(nr, np.int64)
    pos = 0
    nv = 0
    for k in range(nr):
        e0 = eoff[k]
        e1 = eoff[k + 1]
        rc, pl, p, q, g, fl, rv, rt = dual_pieces(e0, e1, ec, er, edin, edout, cnt)
        _cp2(rect, pos, rc)
        _cp1(pel, pos, pl)
        _cp2(gp, pos, p)
        _cp2(gq, pos, q)
        _cp1(gdir, pos, g)
        _cp2(r0, nv, rv)
        _cp1(r0t, nv, rt)
        full[k] = fl[0]
        kmax[k] = min(_kmax_for(rc), kcap)
        pos += e1 - e0
        nv += rt.size
        poff[k + 1] = pos
        r0off[k + 1] = nv
    return Corridors(
        eoff,
        ec,
        er,
        edin,
        edout,
        enl,
        cnt,
        r0off,
        r0[:nv],
        r0t[:nv],
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
