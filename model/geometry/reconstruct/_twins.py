"""Rings that are translates of an earlier ring: R computes one and moves the others (ADR 0036).

A ring's corridor — its pieces, gates, safety net, snapping depth — is a function of its crack code and of
how many elements share each of its pixels (``cnt``, which is how other rings reach into it), placed at the
ring's start. Two rings with the same codes and the same counts therefore have corridors that are exact
integer translates of each other, and every later phase (reach, greedy, the exact checks, the searches) is
exact integer work on that corridor, so the ring R makes of the second one is the first one's, moved.
Real images repeat small rings a lot (70 % of the rings of the thresholded coins, 80 % of a 50 % noise
image's), and the small rings are the ones whose searches cost most per linel.
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit

#: ``Corridors.special`` of a ring left to its twin (the phases skip it).
TWIN = 3

_FNV_OFFSET = np.uint64(14695981039346656037)
_FNV_PRIME = np.uint64(1099511628211)


@leaf_njit(cache=True)
def _same(codes: np.ndarray, off: np.ndarray, eoff: np.ndarray, cnt: np.ndarray, k: int, r: int) -> bool:
    # Rings k and r have the same codes and the same element counts.
    if off[k + 1] - off[k] != off[r + 1] - off[r] or eoff[k + 1] - eoff[k] != eoff[r + 1] - eoff[r]:
        return False
    for i in range(off[k + 1] - off[k]):
        if codes[off[k] + i] != codes[off[r] + i]:
            return False
    ne = eoff[k + 1] - eoff[k]
    i = 0
    while i < ne and cnt[eoff[k] + i] == cnt[eoff[r] + i]:
        i += 1
    return bool(i == ne)


@njit(cache=True)
def ring_twins(
    codes: np.ndarray, off: np.ndarray, eoff: np.ndarray, cnt: np.ndarray, special: np.ndarray
) -> np.ndarray:  # pragma: no cover
    """For each ring, the first ring whose corridor it translates (compared exactly), or itself.

    Rings with ``special`` ≠ 0 (an isolated pixel, a domino: already cheap) are their own. O(linels) for
    the hashes, then a sort of the rings by hash; equal hashes are compared element by element.
    """
    nr = off.size - 1
    h = np.empty(nr, np.uint64)
    for k in range(nr):
        x = _FNV_OFFSET
        for i in range(off[k], off[k + 1]):
            x = (x ^ np.uint64(codes[i])) * _FNV_PRIME
        x = (x ^ np.uint64(255)) * _FNV_PRIME  # the codes end here (they are 0 … 3)
        for e in range(eoff[k], eoff[k + 1]):
            x = (x ^ np.uint64(cnt[e])) * _FNV_PRIME
        h[k] = x
    order = np.argsort(h, kind="mergesort")  # stable: within one hash, rings in index order
    rep = np.arange(nr)
    i = 0
    while i < nr:
        j = i + 1
        while j < nr and h[order[j]] == h[order[i]]:
            j += 1
        for u in range(i + 1, j):
            k = order[u]
            if special[k] != 0:
                continue
            for v in range(i, u):
                r = order[v]
                if rep[r] == r and special[r] == 0 and _same(codes, off, eoff, cnt, k, r):
                    rep[k] = r
                    break
        i = j
    return rep


@njit(cache=True)
def fill_twins(
    rep: np.ndarray,
    sx: np.ndarray,
    sy: np.ndarray,
    poff: np.ndarray,
    reach: np.ndarray,
    lines: np.ndarray,
    xy: np.ndarray,
    roff: np.ndarray,
    status: np.ndarray,
    src: np.ndarray,
    win: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Every twin's ring, reach and lines: its ring's, moved by the difference of their starts.

    ``xy`` … ``win`` hold an empty ring for each twin; returns them with the twins' rings in place (plane
    coordinates: the move is a whole number of pixels, exact). ``reach`` and ``lines`` (per piece, lines
    in Q-units) are filled in place when they hold every piece (empty: R kept them a batch at a time).
    """
    nr = rep.size
    length = np.empty(nr, np.int64)
    for k in range(nr):
        length[k] = roff[rep[k] + 1] - roff[rep[k]]
    noff = np.zeros(nr + 1, np.int64)
    for k in range(nr):
        noff[k + 1] = noff[k] + length[k]
    nxy = np.empty((noff[nr], 2), np.float64)
    nsrc = np.empty(noff[nr], np.int64)
    nwin = np.empty(noff[nr], np.int64)
    nstatus = np.empty(nr, np.int64)
    for k in range(nr):
        r = rep[k]
        dx = float(sx[k] - sx[r])
        dy = float(sy[k] - sy[r])
        for i in range(length[k]):
            nxy[noff[k] + i, 0] = xy[roff[r] + i, 0] + dx
            nxy[noff[k] + i, 1] = xy[roff[r] + i, 1] + dy
            nsrc[noff[k] + i] = src[roff[r] + i]
            nwin[noff[k] + i] = win[roff[r] + i]
        nstatus[k] = status[r]
        if r != k and reach.size > 0:
            for i in range(poff[k + 1] - poff[k]):
                reach[poff[k] + i] = reach[poff[r] + i]
                lines[poff[k] + i, 0] = lines[poff[r] + i, 0] + 4.0 * dx
                lines[poff[k] + i, 1] = lines[poff[r] + i, 1] + 4.0 * dy
                lines[poff[k] + i, 2] = lines[poff[r] + i, 2]
                lines[poff[k] + i, 3] = lines[poff[r] + i, 3]
    return nxy, noff, nstatus, nsrc, nwin
