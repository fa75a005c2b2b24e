"""Border paths and corridors of crack chains: where a reversible polygon may run.

Reference: docs/algorithms.md §2.5, §3.4.

A crack chain (object on the left) is walked linel by linel. Its **border path** is the cyclic 4-connected
sequence of the pixels on its left, one *element* per maximal run of linels with the same inner pixel, plus
an *elbow* element at every right turn (the pixel ahead on the left, which the path must step through so as
not to cut the reflex corner). A pixel met by several elements (of one ring or of several rings of the same
component: one-pixel-wide arms and walls) is *visited* several times.

The **corridor** of a ring is the sequence of open axis-parallel rectangles (*pieces*) its polygon must run
through, in path order, and of the open segments (*gates*) between consecutive pieces:

* cover models (``standard``, ``supercover``): a pixel visited once is one piece, its open square; a pixel
  visited several times gives each visit its own part, the part of the square on the outer side of the path
  of pixel centres (half a square along a straight stretch, a quarter at an elbow, a half and a quarter at a
  convex corner, two halves at the tip of an arm), so that the parts of different visits are disjoint;
* ``gauss``: the *dual* corridor instead (:mod:`mrm.geometry.reconstruct._dual`, ADR 0012): the open unit
  squares whose corners are the four pixel centres around each pointel of the chain, joined by the open
  segments between the centres on either side of each linel (a quarter of the square for each visit of a
  pointel met twice). It holds no pixel centre, so the polygon keeps every centre of A strictly inside and
  every other centre strictly outside, and stays within the voxels of the border pixels.

A ring that enters every piece through its gate and leaves through the next one, with every vertex strictly
inside a piece, is simple, disjoint from the rings of the other visits, and D(polygon) = A
(:mod:`mrm.geometry.reconstruct` builds such rings, :mod:`mrm.geometry.reconstruct.verify` checks them
exactly).

Coordinates are plane coordinates: pixel (x, y) is centred on (x, y); pointel (i, j) is (i − ½, j − ½).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mrm.geometry.reconstruct import _dual as _dk
from mrm.geometry.reconstruct import _kernels as _k
from mrm.reps.region import CrackChain

IntArray = npt.NDArray[np.int64]
FloatArray = npt.NDArray[np.float64]

#: Names of the element kinds (``BorderPath.kinds``): the number of linels of a run, 0 for an elbow.
KIND_NAMES = {0: "elbow", 1: "straight", 2: "convex corner", 3: "tip", 4: "isolated pixel"}


@dataclass(frozen=True)
class BorderPath:
    """The 4-connected border path of one crack chain.

    Attributes
    ----------
    pixels : ndarray of int64, shape (m, 2)
        The path's pixels (x, y), in order; consecutive ones (cyclically) are 4-adjacent.
    step_in : ndarray of int64, shape (m,)
        Freeman direction of the step into each element.
    kinds : ndarray of int64, shape (m,)
        0 for an elbow (right turn of the crack), else the number of linels of the run: 1 straight, 2 convex
        corner, 3 tip of a one-pixel-wide arm, 4 isolated pixel (see :data:`KIND_NAMES`).
    """

    pixels: IntArray
    step_in: IntArray
    kinds: IntArray

    def __len__(self) -> int:
        return int(self.pixels.shape[0])


@dataclass(frozen=True)
class Corridor:
    """The pieces and gates one reconstructed ring must follow.

    Attributes
    ----------
    pieces : ndarray of float64, shape (n, 4)
        Open rectangles [xmin, xmax, ymin, ymax] in path order.
    gate_left, gate_right : ndarray of float64, shape (n, 2)
        Gate k, between piece k−1 and piece k (gate 0 closes the ring), is the open segment from
        ``gate_left[k]`` to ``gate_right[k]``: the left and right ends as seen when crossing it.
    gate_dir : ndarray of int64, shape (n,)
        The Freeman direction in which gate k is crossed.
    full : bool
        True when every piece is a whole pixel square.
    """

    pieces: FloatArray
    gate_left: FloatArray
    gate_right: FloatArray
    gate_dir: IntArray
    full: bool

    def __len__(self) -> int:
        return int(self.pieces.shape[0])


def _chains_arrays(
    chains: Sequence[CrackChain],
) -> tuple[npt.NDArray[np.uint8], IntArray, IntArray, IntArray]:
    lengths = np.fromiter((len(c.codes) for c in chains), dtype=np.int64, count=len(chains))
    off = np.zeros(len(chains) + 1, dtype=np.int64)
    np.cumsum(lengths, out=off[1:])
    codes = np.frombuffer("".join(c.codes for c in chains).encode("ascii"), dtype=np.uint8) - np.uint8(48)
    sx = np.fromiter((c.start[0] for c in chains), dtype=np.int64, count=len(chains))
    sy = np.fromiter((c.start[1] for c in chains), dtype=np.int64, count=len(chains))
    return np.ascontiguousarray(codes), off, sx, sy


def _elements(chains: Sequence[CrackChain]) -> tuple[tuple[IntArray, ...], int, int]:
    # The elements relative to the chains' lowest start (mx, my): the kernel stores coordinates as int32
    # (._base.Corridors); the chains of one pixel set lie anywhere up to ±2⁴⁰ but span far less.
    for c in chains:
        if not c.is_closed():
            raise ValueError(f"crack chain {c} is not closed")
    codes, off, sx, sy = _chains_arrays(chains)
    mx, my = int(sx.min()), int(sy.min())
    if max(int(sx.max()) - mx, int(sy.max()) - my) + int(np.diff(off).max()) > 2**28:
        raise ValueError("the crack chains spread over more than 2^28 pixels")
    return tuple(_k.build_elements(codes, off, sx - mx, sy - my)), mx, my


def border_paths(chains: Sequence[CrackChain]) -> list[BorderPath]:
    """Return the border path of each closed crack chain (object on the left).

    Raises
    ------
    ValueError
        If a chain is not closed.
    """
    if not chains:
        return []
    (eoff, ec, er, edin, _edout, enl, *_), mx, my = _elements(chains)
    out = []
    for k in range(len(chains)):
        a, b = int(eoff[k]), int(eoff[k + 1])
        out.append(
            BorderPath(
                np.stack([ec[a:b].astype(np.int64) + mx, er[a:b].astype(np.int64) + my], axis=1),
                edin[a:b].astype(np.int64),
                enl[a:b].astype(np.int64),
            )
        )
    return out


def border_path(chain: CrackChain) -> BorderPath:
    """Return the border path of one closed crack chain (see :class:`BorderPath`)."""
    return border_paths([chain])[0]


def visit_counts(paths: Sequence[BorderPath]) -> dict[tuple[int, int], int]:
    """How many elements of the given border paths sit on each pixel."""
    counts: dict[tuple[int, int], int] = {}
    for p in paths:
        for x, y in p.pixels.tolist():
            counts[(x, y)] = counts.get((x, y), 0) + 1
    return counts


def corridors(chains: Sequence[CrackChain], model: str = "standard") -> list[Corridor]:
    """Return the corridor of each chain, for the chains of one pixel set (or of one component).

    Parameters
    ----------
    chains : sequence of CrackChain
        Every boundary chain of the set (or of one component): visits are counted over all of them, so a
        pixel on two rings (a wall between a hole and the outside) is split between them.
    model : {"standard", "supercover", "gauss"}
        The cover models share one corridor; ``gauss`` uses the dual squares of the crack pointels
        (:mod:`mrm.geometry.reconstruct._dual`).
    """
    if not chains:
        return []
    if model == "gauss":
        return _dual_corridors(chains)
    (eoff, ec, er, edin, edout, enl, _r0off, _r0, _r0e), ox, oy = _elements(chains)
    # Shift to non-negative array indices for the visit counter.
    dx, dy = int(ec.min()), int(er.min())
    cx = ec - np.int32(dx)
    cy = er - np.int32(dy)
    mx, my = ox + dx, oy + dy
    cnt = _k.element_visits(cx, cy, int(cy.max()) + 1, int(cx.max()) + 1)
    out = []
    for k in range(len(chains)):
        a, b = int(eoff[k]), int(eoff[k + 1])
        if b - a == 1 and enl[a] == 4:
            # an isolated pixel: one piece, its open square, no gate
            x, y = int(ec[a]) + ox, int(er[a]) + oy
            out.append(
                Corridor(
                    np.array([[x - 0.5, x + 0.5, y - 0.5, y + 0.5]]),
                    np.zeros((0, 2)),
                    np.zeros((0, 2)),
                    np.zeros(0, np.int64),
                    True,
                )
            )
            continue
        rect, _pel, gp, gq, gdir, full = _k.build_pieces(a, b, cx, cy, edin, edout, enl, cnt)
        shift = np.array([4 * mx, 4 * mx, 4 * my, 4 * my], dtype=np.int64)
        out.append(
            Corridor(
                (rect + shift) / 4.0,
                (gp + shift[[0, 2]]) / 4.0,
                (gq + shift[[0, 2]]) / 4.0,
                gdir.astype(np.int64),
                bool(full[0]),
            )
        )
    return out


def _dual_corridors(chains: Sequence[CrackChain]) -> list[Corridor]:
    # gauss: the dual squares of each chain's pointels (quarters where a pointel is met twice), in plane
    # coordinates; ``element`` is the pointel's index along the chain.
    codes, off, sx, sy = _chains_arrays(chains)
    # pointels of all chains, shifted to non-negative indices for the visit counter
    pts = [c.points() for c in chains]
    mx = min(int(p[:, 0].min()) for p in pts)
    my = min(int(p[:, 1].min()) for p in pts)
    w = max(int(p[:, 0].max()) for p in pts) - mx
    h = max(int(p[:, 1].max()) for p in pts) - my
    eoff, ec, er, edin, edout, _enl, cnt = _dk.dual_elements(codes, off, sx - mx, sy - my, h, w)
    out = []
    for k in range(len(chains)):
        a, b = int(eoff[k]), int(eoff[k + 1])
        rect, _pel, gp, gq, gdir, full, _r0, _r0t = _dk.dual_pieces(a, b, ec, er, edin, edout, cnt)
        # dual Q-units → plane: pointel (i, j) is (i − ½, j − ½)
        shift = np.array([4 * mx - 2, 4 * mx - 2, 4 * my - 2, 4 * my - 2], dtype=np.int64)
        out.append(
            Corridor(
                (rect + shift) / 4.0,
                (gp + shift[[0, 2]]) / 4.0,
                (gq + shift[[0, 2]]) / 4.0,
                gdir.astype(np.int64),
                bool(full[0]),
            )
        )
    return out
