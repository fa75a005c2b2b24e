"""Greedy colouring of an adjacency graph (the 3D analytical view's plane segments), compiled.

The view gives each digital plane segment one of k colours so that segments sharing a surfel edge differ
where k allows. The loop over segments ran in Python (a numpy call per segment) and held the GIL for up to
190 ms at 20,000 segments on a worker, which the GUI thread waited for; compiled, it releases the GIL.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit

Ints = npt.NDArray[np.int64]


@njit(cache=True)
def _greedy(start: Ints, adjacent: Ints, k: int) -> Ints:  # pragma: no cover - compiled
    n = start.size - 1
    colour = np.full(n, -1, np.int64)
    used = np.zeros(k, np.bool_)
    for s in range(n):
        used[:] = False
        for t in range(start[s], start[s + 1]):
            c = colour[adjacent[t]]
            if c >= 0:
                used[c] = True
        colour[s] = s % k
        for c in range(k):
            if not used[c]:
                colour[s] = c
                break
    return colour


def greedy_colouring(n_nodes: int, pairs: npt.ArrayLike, k: int) -> Ints:
    """A colour in 0 … k − 1 per node; nodes joined by a pair differ where k colours allow.

    Parameters
    ----------
    n_nodes : int
        The number of nodes, 0 … n_nodes − 1.
    pairs : int array (m, 2)
        The edges, each in one or both directions; sorted or not.
    k : int
        The number of colours (≥ 1). Nodes take colours in node order, each the smallest its coloured
        neighbours leave free (node mod k when none is free).

    Returns
    -------
    int64 array (n_nodes,)
    """
    if k < 1:
        raise ValueError("k must be at least 1")
    p = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    both = np.concatenate([p, p[:, ::-1]])
    both = both[both[:, 0] != both[:, 1]]
    order = np.argsort(both[:, 0], kind="stable")
    adjacent = np.ascontiguousarray(both[order, 1])
    start = np.searchsorted(both[order, 0], np.arange(n_nodes + 1)).astype(np.int64)
    return _greedy(start, adjacent, int(k))
