"""The analytical representation: every boundary chain cut into digital straight segments (docs/design.md §5).

For each closed crack chain of a region (outer boundaries counter-clockwise, holes clockwise, over pointels:
pointel (i, j) is the Euclidean point (i − ½, j − ½)), the chain's pointels are segmented into standard
(4-connected) DSS, as DGtal does on a grid curve's points:

* ``mode="greedy"`` (the default): :func:`mrm.geometry.dss.segmentation.greedy_segmentation` from the chain's
  start, read as closed; the last segment ends back on the start (``closed_end="wrap"``), so the segments
  cover every linel and consecutive ones share an end pointel;
* ``mode="maximal"``: all maximal segments (the tangential cover), which overlap.

Each segment carries its index range in the chain's pointels (``first``, ``last``; on a chain of n codes
point k is pointel ``k mod n``), its characteristics (a, b, μ, ω) in DGtal's convention (μ ≤ a·i − b·j < μ + ω
for every pointel (i, j) of the segment), its leaning points, its preimage (:mod:`mrm.geometry.dss.preimage`,
in pointel coordinates, computed on demand) and the chosen Euclidean line: the median line
a·i − b·j = μ + (ω − 1)/2, which lies in the open preimage.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.gc_pause import paused_gc
from mrm.geometry.dss import Segment
from mrm.geometry.dss import _kernels as K
from mrm.geometry.dss.preimage import Preimage, segment_preimage

IntArray = npt.NDArray[np.int64]
Mode = Literal["greedy", "maximal"]
Line = tuple[int, int, Fraction]

_DX = np.array([1, 0, -1, 0], dtype=np.int64)
_DY = np.array([0, 1, 0, -1], dtype=np.int64)


def _row_segment(r: Sequence[int]) -> Segment:
    return Segment(
        int(r[0]), int(r[1]), int(r[2]), int(r[3]), int(r[4]), int(r[5]),
        (int(r[6]), int(r[7])), (int(r[8]), int(r[9])), (int(r[10]), int(r[11])), (int(r[12]), int(r[13])),
    )  # fmt: skip


class ChainSegments:
    """The segments of one closed boundary chain.

    Attributes
    ----------
    start : tuple of int
        The chain's start pointel.
    codes : str
        Its Freeman codes (0 = E, 1 = N, 2 = W, 3 = S).
    component : int
        The label of the component it bounds (0 when the chain was given without a region).
    hole : bool
        True for a hole boundary (clockwise).
    table : ndarray of int64, shape (k, 14), read-only
        One row per segment: first, last, a, b, mu, omega, then Uf, Ul, Lf, Ll (x, y each).
    """

    __slots__ = ("_pre", "_segs", "codes", "component", "hole", "start", "table")

    def __init__(
        self, start: tuple[int, int], codes: str, table: IntArray, component: int = 0, hole: bool = False
    ):
        self.start = (int(start[0]), int(start[1]))
        self.codes = codes
        self.component = int(component)
        self.hole = bool(hole)
        t = np.array(table, dtype=np.int64).reshape(-1, K.SEG_COLS)
        t.flags.writeable = False
        self.table = t
        self._segs: tuple[Segment, ...] | None = None
        self._pre: dict[int, Preimage] = {}

    def __len__(self) -> int:
        return int(self.table.shape[0])

    @property
    def segments(self) -> tuple[Segment, ...]:
        """The segments, in chain order."""
        if self._segs is None:
            self._segs = tuple(_row_segment(r) for r in self.table.tolist())
        return self._segs

    def points(self) -> IntArray:
        """The chain's n + 1 pointels (the last one is the start again)."""
        c = np.frombuffer(self.codes.encode("ascii"), dtype=np.uint8).astype(np.int64) - 48
        out = np.empty((c.size + 1, 2), dtype=np.int64)
        out[0] = self.start
        out[1:, 0] = self.start[0] + np.cumsum(_DX[c])
        out[1:, 1] = self.start[1] + np.cumsum(_DY[c])
        return out

    def segment_points(self, k: int) -> IntArray:
        """The pointels of segment k, in order (indices wrap around the chain)."""
        s = self.segments[k]
        pts = self.points()[:-1]
        return pts[np.arange(s.first, s.last + 1) % len(pts)]

    def preimage(self, k: int) -> Preimage:
        """The preimage of segment k: an exact polygon in the (u, w) line space of its frame (pointels)."""
        pre = self._pre.get(k)
        if pre is None:
            pts = self.points()[:-1]
            pre = segment_preimage([tuple(p) for p in pts.tolist()], self.segments[k])
            self._pre[k] = pre
        return pre

    def line(self, k: int) -> Line:
        """The chosen (median) line of segment k in pointel coordinates: (a, b, c) for a·i − b·j = c."""
        return self.segments[k].median_line

    def euclidean_line(self, k: int) -> Line:
        """The chosen line of segment k in plane coordinates: (a, b, c) for a·x − b·y = c.

        Pointel (i, j) is the point (i − ½, j − ½), so a·i − b·j = c becomes a·x − b·y = c − (a − b)/2.
        """
        a, b, c = self.line(k)
        return a, b, c - Fraction(a - b, 2)

    def __repr__(self) -> str:
        kind = "hole" if self.hole else "outer"
        return (
            f"ChainSegments({kind} of {self.component}, start={self.start}, "
            f"{len(self.codes)} linels, {len(self)} segments)"
        )


@dataclass(frozen=True, eq=False)
class Analytical:
    """The analytical representation of a region.

    Attributes
    ----------
    mode : {"greedy", "maximal"}
        How the chains were segmented.
    chains : tuple of ChainSegments
        One per boundary chain, in the region's order (per component: its outer chain, then its holes).
    """

    mode: str
    chains: tuple[ChainSegments, ...]

    @property
    def n_segments(self) -> int:
        """The total number of segments over all chains (what ``mrm info`` reports as ``segments``)."""
        return sum(len(c) for c in self.chains)

    @property
    def segments(self) -> tuple[Segment, ...]:
        """Every segment, chain after chain (``len(segments) == n_segments``)."""
        return tuple(s for c in self.chains for s in c.segments)

    def __iter__(self) -> Iterator[ChainSegments]:
        return iter(self.chains)

    def __len__(self) -> int:
        return len(self.chains)


def _chains_of(region: Any) -> list[tuple[tuple[int, int], str, int, bool]]:
    comps = getattr(region, "components", None)
    out: list[tuple[tuple[int, int], str, int, bool]] = []
    if comps is not None:
        for comp in comps:
            out.append((tuple(comp.outer.start), comp.outer.codes, int(comp.label), False))
            out.extend((tuple(h.boundary.start), h.boundary.codes, int(comp.label), True) for h in comp.holes)
        return out
    for ch in region:
        if hasattr(ch, "codes"):
            start, codes = ch.start, ch.codes
        else:
            start, codes = ch
        out.append(((int(start[0]), int(start[1])), str(codes), 0, False))
    return out


def analytical_of(region: Any, *, mode: Mode = "greedy") -> Analytical:
    """Segment every boundary chain of a region into standard digital straight segments.

    Parameters
    ----------
    region : Region or iterable of chains
        A :class:`mrm.reps.region.Region` (its components' outer and hole chains), or closed chains given
        as :class:`~mrm.reps.region.CrackChain` or ``(start, codes)`` pairs.
    mode : {"greedy", "maximal"}
        Greedy segmentation (DGtal ``GreedySegmentation``, segments sharing end points, covering each chain
        once) or maximal segments (``SaturatedSegmentation``).

    Returns
    -------
    Analytical

    Raises
    ------
    ParameterError
        For an unknown mode.
    InvalidGeometryError
        If a chain is empty, not made of Freeman codes, or not closed.
    """
    if mode not in ("greedy", "maximal"):
        raise ParameterError(f"mode must be 'greedy' or 'maximal', not {mode!r}")
    chains = _chains_of(region)
    if not chains:
        return Analytical(mode, ())
    table, ptr = _segment_table(chains, mode)
    with paused_gc():  # one object per chain: 10⁵ of them on a noise image
        out = tuple(
            ChainSegments(c[0], c[1], table[ptr[i] : ptr[i + 1]], c[2], c[3]) for i, c in enumerate(chains)
        )
    return Analytical(mode, out)


def segment_count(region: Any, *, mode: Mode = "greedy") -> int:
    """The number of segments :func:`analytical_of` gives, without building its per-chain objects.

    Parameters and errors are those of :func:`analytical_of`.
    """
    if mode not in ("greedy", "maximal"):
        raise ParameterError(f"mode must be 'greedy' or 'maximal', not {mode!r}")
    chains = _chains_of(region)
    return int(_segment_table(chains, mode)[1][-1]) if chains else 0


def _segment_table(
    chains: list[tuple[tuple[int, int], str, int, bool]], mode: Mode
) -> tuple[IntArray, IntArray]:
    """The segment table of every chain in one kernel call: (rows, ptr), chain i's rows ptr[i]:ptr[i + 1]."""
    lengths = np.array([len(c[1]) for c in chains], dtype=np.int64)
    if lengths.min() == 0:
        raise InvalidGeometryError("a boundary chain has no codes")
    joined = "".join(c[1] for c in chains)
    codes = np.frombuffer(joined.encode("ascii", errors="replace"), dtype=np.uint8).astype(np.int64) - 48
    if codes.min() < 0 or codes.max() > 3:
        raise InvalidGeometryError("boundary chain codes must be Freeman codes 0-3")
    offsets = np.zeros(len(chains) + 1, dtype=np.int64)
    np.cumsum(lengths, out=offsets[1:])
    # every point but the closing one: start, then start + the first n − 1 steps' partial sums
    dx = _DX[codes]
    dy = _DY[codes]
    cx = np.cumsum(dx)
    cy = np.cumsum(dy)
    base_x = np.concatenate([[0], cx])[offsets]  # partial sums before each chain
    base_y = np.concatenate([[0], cy])[offsets]
    if np.any(base_x[1:] != base_x[:-1]) or np.any(base_y[1:] != base_y[:-1]):
        bad = int(np.flatnonzero((base_x[1:] != base_x[:-1]) | (base_y[1:] != base_y[:-1]))[0])
        raise InvalidGeometryError(f"boundary chain {bad} ({chains[bad][0]}) is not closed")
    chain_of = np.repeat(np.arange(len(chains)), lengths)
    starts = np.array([c[0] for c in chains], dtype=np.int64)
    # point k of chain c is start_c + (sum of the chain's steps before k)
    before_x = np.concatenate([[0], cx[:-1]]) - base_x[chain_of]
    before_y = np.concatenate([[0], cy[:-1]]) - base_y[chain_of]
    pts = np.empty((codes.size, 2), dtype=np.int64)
    pts[:, 0] = starts[chain_of, 0] + before_x
    pts[:, 1] = starts[chain_of, 1] + before_y
    table, ptr = K.segment_chains_kernel(pts, offsets, mode == "maximal", True, 4)
    return table, ptr
