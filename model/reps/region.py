"""The region representation of a pixel set: components, holes, Euler number, crack boundaries.

Reference: docs/design.md §4.

Topology (4, 8): the components of a pixel set A are its 4-connected components; a hole is a bounded
8-connected component of Z² − A, attached to the component that encloses it (the one on the other side of the
hole's boundary). Boundaries are closed crack chains over pointels (pixel corners; pointel (i, j) is the
Euclidean point (i − ½, j − ½), the lower-left corner of pixel (i, j)) with Freeman codes 0 = E, 1 = N, 2 = W,
3 = S. The object is on the LEFT of every chain: outer boundaries run counter-clockwise, hole boundaries
clockwise. Every chain starts at its lowest-leftmost pointel (smallest (y, x)), so outer chains start with
code 0 and hole chains with code 1.

Canonical orders: components are sorted by the start of their outer chain (equivalently by (y, x) of their
lowest-leftmost pixel) and labelled 1..n in that order; the holes of a component are sorted by the start of
their chain.

Region → discrete is exact: :func:`fill` rebuilds the pixel set from the chains alone, so editing the region
(dropping a component, filling a hole) is an edit of the discrete object.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.gc_pause import paused_gc
from mrm.core.grids import Box, LabelMap, PixelSet
from mrm.geometry.topology.cracks import (
    DX,
    DY,
    LX,
    LY,
    RX,
    RY,
    fill_rings,
    paint_rings,
    ring_extent,
    trace_mask,
)

IntArray = npt.NDArray[np.int64]

_NOT_CODES = str.maketrans("", "", "0123")


def _code_array(codes: str) -> npt.NDArray[np.uint8]:
    return np.frombuffer(codes.encode("ascii"), dtype=np.uint8) - np.uint8(48)


@dataclass(frozen=True, slots=True)
class CrackChain:
    """A chain of linels (unit edges between pixels) given by a start pointel and Freeman codes.

    Parameters
    ----------
    start : tuple of int
        The pointel (i, j) the chain starts from, i.e. the Euclidean point (i − ½, j − ½).
    codes : str
        Freeman codes over "0123": 0 = E (+1, 0), 1 = N (0, +1), 2 = W (−1, 0), 3 = S (0, −1).

    Notes
    -----
    The text form ``"X,Y,CODES"`` (see :meth:`from_string` and ``str()``) is what files and the CLI use.
    """

    start: tuple[int, int]
    codes: str

    def __post_init__(self) -> None:
        s = self.start
        if not (isinstance(s, tuple) and len(s) == 2 and all(isinstance(v, int | np.integer) for v in s)):
            raise ParameterError(f"a crack chain start must be a pair of integers, got {s!r}")
        if not isinstance(self.codes, str) or self.codes.translate(_NOT_CODES):
            raise ParameterError("crack chain codes must be a string over '0123' (0=E, 1=N, 2=W, 3=S)")
        object.__setattr__(self, "start", (int(s[0]), int(s[1])))

    @classmethod
    def _trusted(cls, start: tuple[int, int], codes: str) -> CrackChain:
        # Skips validation for chains built by the tracer (hundreds of thousands on big images).
        c = object.__new__(cls)
        object.__setattr__(c, "start", start)
        object.__setattr__(c, "codes", codes)
        return c

    @classmethod
    def from_string(cls, text: str) -> CrackChain:
        """Parse ``"X,Y,CODES"``, e.g. ``"3,-2,0123"`` (spaces around the fields are ignored).

        Raises
        ------
        ParameterError
            When the text is not of that form.
        """
        parts = [p.strip() for p in str(text).split(",")]
        if len(parts) != 3:
            raise ParameterError(f"a crack chain is written 'X,Y,CODES', got {text!r}")
        try:
            x, y = int(parts[0]), int(parts[1])
        except ValueError:
            raise ParameterError(f"the start of a crack chain must be two integers, got {text!r}") from None
        return cls((x, y), parts[2])

    def __str__(self) -> str:
        return f"{self.start[0]},{self.start[1]},{self.codes}"

    def __len__(self) -> int:
        return len(self.codes)

    def code_array(self) -> npt.NDArray[np.uint8]:
        """The codes as a uint8 array of values 0..3."""
        return _code_array(self.codes)

    def points(self) -> IntArray:
        """The (n+1, 2) int64 pointels visited, from the start; a closed chain ends at its start."""
        c = self.code_array()
        out = np.empty((c.size + 1, 2), dtype=np.int64)
        out[0] = self.start
        out[1:, 0] = self.start[0] + np.cumsum(DX[c])
        out[1:, 1] = self.start[1] + np.cumsum(DY[c])
        return out

    def is_closed(self) -> bool:
        """True when the chain has at least one code and comes back to its start."""
        c = self.codes
        return len(c) > 0 and c.count("0") == c.count("2") and c.count("1") == c.count("3")

    def area2(self) -> int:
        """Twice the signed area enclosed by the (closed) chain: > 0 counter-clockwise, < 0 clockwise.

        For an open chain this is the value for the polygon closed by the segment back to the start.
        """
        p = self.points() - np.asarray(self.start, dtype=np.int64)  # small numbers: no int64 overflow
        x, y = p[:, 0], p[:, 1]
        return int(np.sum(x[:-1] * y[1:] - x[1:] * y[:-1]) + x[-1] * y[0] - x[0] * y[-1])

    def _side_pixels(self, ox: IntArray, oy: IntArray) -> IntArray:
        c = self.code_array()
        p = self.points()[:-1]
        return np.stack([p[:, 0] + ox[c], p[:, 1] + oy[c]], axis=1)

    def left_pixels(self) -> IntArray:
        """The (n, 2) pixels on the left of each code (code 0 at pointel (i, j) → pixel (i, j), etc.)."""
        return self._side_pixels(LX, LY)

    def right_pixels(self) -> IntArray:
        """The (n, 2) pixels on the right of each code (code 0 at pointel (i, j) → pixel (i, j − 1), etc.)."""
        return self._side_pixels(RX, RY)

    def translate(self, dx: int, dy: int) -> CrackChain:
        """Return the chain moved by the integer vector (dx, dy)."""
        return CrackChain._trusted((self.start[0] + int(dx), self.start[1] + int(dy)), self.codes)


@dataclass(frozen=True, slots=True)
class Hole:
    """A hole: a bounded 8-connected component of the complement.

    Attributes
    ----------
    pixels : int
        The number of pixels of the hole itself (not counting the components nested inside it).
    bbox : Box
        (xmin, ymin, xmax, ymax) of the hole's pixels, bounds included.
    boundary : CrackChain
        Its boundary, clockwise with the enclosing component on the left, from the lowest-leftmost pointel.
    """

    pixels: int
    bbox: Box
    boundary: CrackChain


@dataclass(frozen=True, slots=True)
class Component:
    """A 4-connected component with its holes.

    Attributes
    ----------
    label : int
        Its number, 1..n in canonical order (the value it has in :attr:`Region.labels`).
    pixels : int
        Its number of pixels.
    bbox : Box
        (xmin, ymin, xmax, ymax) of its pixels, bounds included.
    outer : CrackChain
        Its outer boundary, counter-clockwise, from its lowest-leftmost pointel (the lower-left corner of
        its lowest-leftmost pixel).
    holes : tuple of Hole
        The holes it encloses, sorted by the start of their boundary (smallest (y, x) first).
    """

    label: int
    pixels: int
    bbox: Box
    outer: CrackChain
    holes: tuple[Hole, ...]


@dataclass(frozen=True, slots=True, init=False)
class Region:
    """The region representation of a pixel set.

    Parameters
    ----------
    components : tuple of Component
        The 4-connected components in canonical order (``components[k].label == k + 1``).
    labels : LabelMap, optional
        The component label image, if already known; otherwise it is painted from the chains on first use.

    Notes
    -----
    The components determine everything else, so equality and hashing look at them only.
    """

    components: tuple[Component, ...]
    _labels: LabelMap | None = field(default=None, repr=False, compare=False, hash=False)

    def __init__(self, components: Iterable[Component], labels: LabelMap | None = None) -> None:
        object.__setattr__(self, "components", tuple(components))
        object.__setattr__(self, "_labels", labels)

    @property
    def labels(self) -> LabelMap:
        """The component label image: a pixel has the label of its component, 0 off the set.

        Painted from the boundary chains on first use (weighted winding numbers), then kept.
        """
        lm = self._labels
        if lm is None:
            lm = _paint_labels(self.components)
            object.__setattr__(self, "_labels", lm)
        return lm

    @property
    def n_components(self) -> int:
        """The number of 4-connected components."""
        return len(self.components)

    @property
    def n_holes(self) -> int:
        """The number of holes (bounded 8-components of the complement)."""
        return sum(len(c.holes) for c in self.components)

    @property
    def euler(self) -> int:
        """The Euler number, #components − #holes."""
        return self.n_components - self.n_holes

    @property
    def pixels(self) -> int:
        """The number of pixels of the set."""
        return sum(c.pixels for c in self.components)

    @property
    def boundary_chains(self) -> tuple[CrackChain, ...]:
        """All boundary chains: for each component, its outer chain then its hole chains."""
        return tuple(ch for c in self.components for ch in (c.outer, *(h.boundary for h in c.holes)))

    def component_of(self, x: int, y: int) -> Component | None:
        """Return the component holding pixel (x, y), or None when the pixel is not in the set."""
        lab = self.labels.labels
        c, r = int(x) - self.labels.origin[0], int(y) - self.labels.origin[1]
        if not (0 <= r < lab.shape[0] and 0 <= c < lab.shape[1] and lab[r, c] > 0):
            return None
        k = int(lab[r, c])
        comps = self.components
        if k <= len(comps) and comps[k - 1].label == k:
            return comps[k - 1]
        # An edited region (a component dropped) no longer has its labels in 1..n.
        return next((comp for comp in comps if comp.label == k), None)


def _pack(chains: Sequence[CrackChain]) -> tuple[npt.NDArray[np.uint8], IntArray, IntArray, IntArray]:
    """Concatenated codes, offsets and starts of chains, for the numba kernels."""
    lengths = np.fromiter((len(c.codes) for c in chains), dtype=np.int64, count=len(chains))
    off = np.zeros(len(chains) + 1, dtype=np.int64)
    np.cumsum(lengths, out=off[1:])
    codes = _code_array("".join(c.codes for c in chains))
    sx = np.fromiter((c.start[0] for c in chains), dtype=np.int64, count=len(chains))
    sy = np.fromiter((c.start[1] for c in chains), dtype=np.int64, count=len(chains))
    return codes, off, sx, sy


def _paint_labels(components: tuple[Component, ...]) -> LabelMap:
    chains = [ch for c in components for ch in (c.outer, *(h.boundary for h in c.holes))]
    if not chains:
        return LabelMap(np.zeros((0, 0), dtype=np.int32))
    weights = np.fromiter(
        (c.label for c in components for _ in range(1 + len(c.holes))), dtype=np.int32, count=len(chains)
    )
    codes, off, sx, sy = _pack(chains)
    xmin, ymin, xmax, ymax, closed = ring_extent(codes, off, sx, sy)
    if not closed:
        raise InvalidGeometryError("cannot paint the labels: a crack chain does not come back to its start")
    image = paint_rings(codes, off, sx, sy, weights, (xmin, ymin, xmax - 1, ymax - 1))
    if image.size and int(image.min()) < 0:
        return LabelMap(image, (xmin, ymin))  # which says what is wrong
    # Painted over the chains' own box, so the labels touch its four sides: taken as they are. The
    # constructor's check and private copy were a second full-size label image (300 MB at 10⁸ pixels) of
    # fresh memory, page-faulted in on the cores the window shares.
    return LabelMap._canonical(image, (xmin, ymin))


def _empty_region() -> Region:
    return Region((), LabelMap(np.zeros((0, 0), dtype=np.int32)))


def region_of(ps: PixelSet) -> Region:
    """Compute the region representation of a pixel set.

    Parameters
    ----------
    ps : PixelSet
        The pixel set A.

    Returns
    -------
    Region
        The 4-connected components of A in canonical order, each with its pixel count, bounding box,
        counter-clockwise outer crack chain and its holes (bounded 8-components of the complement, with
        clockwise chains), and the component label image.
    """
    if ps.is_empty():
        return _empty_region()
    x0, y0 = ps.origin
    rings = trace_mask(ps.mask)
    runs = rings.runs
    n = runs.n_labels
    # One str for all the codes; each chain is a slice of it (str from ASCII bytes is a plain copy).
    text = (rings.codes + np.uint8(48)).tobytes().decode("ascii")
    off = rings.off.tolist()
    sx = (rings.sx + x0).tolist()
    sy = (rings.sy + y0).tolist()
    # Pointel extents xmin .. xmax cover the pixels xmin .. xmax − 1.
    bx0 = (rings.box[:, 0] + x0).tolist()
    by0 = (rings.box[:, 1] + y0).tolist()
    bx1 = (rings.box[:, 2] + (x0 - 1)).tolist()
    by1 = (rings.box[:, 3] + (y0 - 1)).tolist()
    is_hole = rings.area2 < 0
    comp = rings.comp
    outer_of = np.empty(n + 1, dtype=np.int64)
    outer_idx = np.flatnonzero(~is_hole)
    outer_of[comp[outer_idx]] = outer_idx
    hole_idx = np.flatnonzero(is_hole)
    hole_idx = hole_idx[np.lexsort((rings.sx[hole_idx], rings.sy[hole_idx], comp[hole_idx]))]
    first = np.searchsorted(comp[hole_idx], np.arange(n + 2)).tolist()
    hole_list = hole_idx.tolist()
    hole_pixels = runs.bg_counts[rings.bg].tolist()
    counts = runs.counts.tolist()
    outer_list = outer_of.tolist()
    chain = CrackChain._trusted
    components = []
    with paused_gc():
        for lab in range(1, n + 1):
            k = outer_list[lab]
            f0, f1 = first[lab], first[lab + 1]
            holes: tuple[Hole, ...] = ()
            if f0 != f1:
                holes = tuple(
                    Hole(
                        hole_pixels[h],
                        (bx0[h], by0[h], bx1[h], by1[h]),
                        chain((sx[h], sy[h]), text[off[h] : off[h + 1]]),
                    )
                    for h in hole_list[f0:f1]
                )
            outer = chain((sx[k], sy[k]), text[off[k] : off[k + 1]])
            components.append(Component(lab, counts[lab], (bx0[k], by0[k], bx1[k], by1[k]), outer, holes))
    return Region(components)


def _fill_chains(chains: Sequence[CrackChain]) -> PixelSet:
    if not chains:
        return PixelSet.empty()
    codes, off, sx, sy = _pack(chains)
    mask, xmin, ymin, problem = fill_rings(codes, off, sx, sy)
    if problem:
        raise InvalidGeometryError(f"cannot fill the crack chains: {problem}")
    return PixelSet(mask, (xmin, ymin))


def fill_chains(outer: CrackChain, holes: Iterable[CrackChain] = ()) -> PixelSet:
    """Return the pixels enclosed by a counter-clockwise outer chain minus its clockwise hole chains.

    Parameters
    ----------
    outer : CrackChain
        A closed counter-clockwise chain.
    holes : iterable of CrackChain
        Closed clockwise chains inside it.

    Raises
    ------
    InvalidGeometryError
        When a chain is not closed, or the chains overlap or are wrongly oriented, so that they do not
        bound a set of pixels.
    """
    return _fill_chains([outer, *holes])


def fill(region: Region) -> PixelSet:
    """Rebuild the pixel set of a region from its boundary chains alone (the inverse of :func:`region_of`).

    Raises
    ------
    InvalidGeometryError
        When the chains do not bound a set of pixels (see :func:`fill_chains`).
    """
    return _fill_chains(region.boundary_chains)
