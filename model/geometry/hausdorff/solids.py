"""A certified interval for the Hausdorff distance between two polyhedral solids (docs/design.md §8, §11).

What is computed
----------------
The same notion as the 2D package (:mod:`mrm.geometry.hausdorff`): the distance between the *filled* solids.
``h(A, B) = max_{a ∈ A} d(a, B)`` with ``d(a, B) = 0`` for a inside B; ``H = max(h(A, B), h(B, A))``. The
maximum can lie inside A (a cavity of B that A fills: the cavity's centre), not only on A's surface.

How
---
:func:`solid_hausdorff` returns intervals ``[lo, hi]`` with ``lo ≤ h ≤ hi`` guaranteed:

* ``lo`` is the largest lower bound of ``d(x, B)`` over points ``x`` proved to be in A: A's vertices (tried
  first — most chains' maximum is at a vertex) and the centres of the cells below that the exact parity test
  puts inside A.
* ``hi`` comes from a branch-and-bound over dyadic cubes covering A's bounding box. A cube C of centre c and
  half-diagonal r gets an upper bound of ``max d(·, B)`` over ``C ∩ A``, the least of:

  - ``d(c, B) + r`` (1-Lipschitz);
  - for a few triangles T of B (the nearest to c and to C's corners), the maximum over ``C ∩ A`` of the
    convex ``d(·, T) ≥ d(·, B)``. ``C ∩ A`` lies in the convex hull of C's corners that are in A and of the
    pieces ``T_A ∩ C`` of A's triangles, so the maximum is bounded by its values at those corners and, for
    each piece, by the least of its maxima over T_A's vertices, over C's corners, and over points within a
    proven distance of the piece's vertices (:func:`._solids_kernels._piece_points`);
  - the same with ``max(0, signed distance to T's plane)`` when B is flat under C: every triangle of B
    between C and its projection on that plane lies in it (exact) and B is on the far side (exact parity),
    so ``d(x, B)`` is at most the signed distance (two parallel faces at constant distance close at once);
  - 0 when ``C ∩ A ⊆ B`` is proved exactly (containment, below).

  A cube that certainly misses A (no triangle of A may meet it — a conservative box/triangle test — and its
  centre is outside A, exactly) is dropped. Cubes whose bound exceeds ``lo + tolerance`` are split in 8; the
  search stops when none is left (then ``hi − lo ≤ tolerance``), or when the cell budget or the depth limit
  is reached (then the bounds of the open cubes count and the interval is wider;
  :attr:`SolidHausdorff.stopped` says so).

Containment (why shared boundaries do not stall the search): two solids that share faces, edges or corners
(a voxel object and a part of it) have ``d(·, B) = 0`` along the shared boundary, where ``d(c, B) + r``
never reaches 0. A cube C is settled at 0 when (1) no triangle of B may meet it and its centre is inside B;
or (2) the triangles of B that may meet C (or the doubled cube Q, for a cube touching B only on its
boundary) form a convex configuration (each lies on the inner side of the others' planes, exact signs), so
that ∂B ∩ Q lies on the boundary of the convex K = ∩ inner half-spaces; a point of int K ∩ int Q is inside B
(exact parity), so int K ∩ int Q — connected and missing ∂B — lies in B, and so does K ∩ Q; and every
triangle of A that may meet C has its vertices in K, as has every corner of C that is in A: C ∩ A lies in
the convex hull of those, hence in K ∩ Q; or (3) the same oriented triangles of A and of B may meet Q and
the centre is on the same side of both: every component of int Q minus the surface is then on the same side
of both solids; or (4) every triangle of A and B that may meet Q is axis-aligned (voxel reconstructions
are): their planes cut int Q into open boxes that miss both surfaces, and every box whose midpoint is in A
has it in B (exact parity) — shared concave edges and differently triangulated faces settle here.

Exactness and rounding
----------------------
Inside/outside decisions are exact: a parity ray with a symbolic perturbation (q + (ε, ε², ε³)) and exact
3×3/2×2 determinant signs (:mod:`mrm.geometry.discretize._kernels3d`). They need coordinates that are 0 or
of magnitude in [2⁻²⁴⁰, 2⁵⁰]; others are refused. Distances are float enclosures: relative 2⁻⁴⁸ plus
``2⁻⁴⁴·M`` absolute, M the largest coordinate magnitude, which covers the roundings of a point–triangle
distance eight times over (the derivation is in :func:`._solids_kernels.tri_dist`); sums of upper bounds are
rounded up by a relative 2⁻⁵¹; the piece points carry ``2⁻³⁶·M``. Grid searches need no allowance
(monotone bin indices). So the interval is not tighter than about ``2⁻³⁶·M`` where pieces matter: far
from the origin, small details cost precision.

``vertex_error``: when every given vertex may be off from the true one by ``vertex_error`` in each
coordinate, each solid is within ``√3·vertex_error`` of the true one (a point that changes sides while the
vertices move is crossed by a moving triangle, within ``√3·vertex_error`` of its given position), and
``h`` moves by at most the sum of the two: the interval is widened by ``2·√3·vertex_error`` on each side.

Cost: the vertices of A cost one nearest-triangle query each (a uniform bin grid of B's triangles); a
maximum at a vertex closes the search after a few hundred cubes. Maxima spread over many faces (a voxel
object against its translate: every face facing the shift is exactly |t| away) cost tens of thousands of
cubes; when the budget stops the search, the interval is wider but still certain (docs/adr/0059).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mrm.core.errors import ParameterError
from mrm.core.progress import ProgressLike
from mrm.geometry.hausdorff import _solids_kernels as K

log = logging.getLogger(__name__)

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

#: Cubes examined per direction before the search stops with a wider interval (a few seconds at most).
DEFAULT_CELL_BUDGET = 200_000
#: Open cubes split per round of the best-first search (enough to amortize a compiled call).
_ROUND = 4096
_LOW = 2.0**-240
_HIGH = 2.0**50


@dataclass(frozen=True)
class SolidHausdorff:
    """Certified enclosures of the directed distances between two solids.

    Attributes
    ----------
    a_within : tuple of float
        ``(lo, hi)`` with ``lo ≤ h(A, B) ≤ hi``: how far A reaches outside B.
    b_within : tuple of float
        ``(lo, hi)`` with ``lo ≤ h(B, A) ≤ hi``.
    stopped : str
        ``"tolerance"`` when both intervals are within the tolerance, ``"budget"`` when a search spent its
        cell budget, ``"depth"`` when it reached the finest cubes (the intervals are still certain).
    cells : int
        Cubes examined in both searches.
    """

    a_within: tuple[float, float]
    b_within: tuple[float, float]
    stopped: str
    cells: int

    @property
    def value(self) -> tuple[float, float]:
        """``(lo, hi)`` enclosing ``H(A, B) = max(h(A, B), h(B, A))``."""
        return (max(self.a_within[0], self.b_within[0]), max(self.a_within[1], self.b_within[1]))

    @property
    def exact(self) -> bool:
        """True when the enclosure of H is a single proven value."""
        lo, hi = self.value
        return lo == hi


def _as_mesh(vertices: object, triangles: object, what: str) -> tuple[Floats, Ints]:
    # Fresh writeable C arrays: numba compiles one specialization per array layout and per read-only flag,
    # and a Polyhedron's arrays are read-only, so every caller gets the same (warmed-up) signature.
    v = np.array(vertices, dtype=np.float64, order="C").reshape(-1, 3)
    t = np.array(triangles, dtype=np.int64, order="C").reshape(-1, 3)
    if not np.isfinite(v).all():
        raise ParameterError(f"{what}: vertex coordinates must be finite")
    if t.size and (t.min() < 0 or t.max() >= len(v)):
        raise ParameterError(f"{what}: a triangle refers to a vertex that does not exist")
    used = np.unique(t)
    if len(used) < len(v):  # only the vertices of triangles belong to the solid
        v = np.ascontiguousarray(v[used])
        t = np.ascontiguousarray(np.searchsorted(used, t).astype(np.int64))
    _check_range(v, what)
    return v, t


def _check_range(x: Floats, what: str) -> None:
    a = np.abs(x)
    if ((a != 0.0) & ((a < _LOW) | (a > _HIGH))).any():
        raise ParameterError(f"{what}: coordinates must be 0 or of magnitude between 2^-240 and 2^50")


def _index(v: Floats, t: Ints) -> K.Mesh:
    # A uniform bin grid of about 1.5 mean triangle extents per bin, at most MAX_BINS per axis.
    lo = v.min(axis=0) if len(v) else np.zeros(3)
    hi = v.max(axis=0) if len(v) else np.ones(3)
    ext = np.maximum(hi - lo, 0.0)
    if len(t):
        tv = v[t]
        size = float((tv.max(axis=1) - tv.min(axis=1)).max(axis=1).mean()) * 1.5
    else:
        size = 1.0
    size = max(size, float(ext.max()) / K.MAX_BINS, 1e-300)
    n = np.minimum(np.floor(ext / size).astype(np.int64) + 1, K.MAX_BINS)
    while int(np.prod(n)) > 1 << 22:
        size *= 1.25
        n = np.minimum(np.floor(ext / size).astype(np.int64) + 1, K.MAX_BINS)
    o = np.ascontiguousarray(lo, dtype=np.float64)
    s3, i3 = K.build_grid3(v, t, o, size, n)
    s2, i2 = K.build_grid2(v, t, o, size, n)
    return K.Mesh(v, t, o, float(size), n, s3, i3, s2, i2)


def _root(v: Floats) -> tuple[Floats, float]:
    # A dyadic cube of half-side 2H around A's box: H a power of two ≥ the box's half-extent, the centre a
    # multiple of H, so every sub-cube's centre and corners are exact floats.
    lo = v.min(axis=0)
    hi = v.max(axis=0)
    half = float((hi - lo).max()) / 2.0
    e = math.frexp(max(half, 2.0**-200))[1]
    big = math.ldexp(1.0, e)  # ≥ half
    centre = np.round((lo + hi) / 2.0 / big) * big
    return np.ascontiguousarray(centre.reshape(1, 3)), 2.0 * big


def _radius(h: float) -> float:
    # The half-diagonal √3·h of a cube of half-side h (a power of two), rounded up.
    return h * math.sqrt(3.0) * (1.0 + 2.0**-50)


def _same_surface(va: Floats, ta: Ints, vb: Floats, tb: Ints) -> bool:
    # The same set of oriented triangles (coordinates compared exactly, each triangle started at its
    # lexicographically least vertex): the same solid.
    if len(ta) != len(tb):
        return False

    def canonical(v: Floats, t: Ints) -> Floats:
        c = v[t]  # (m, 3, 3)
        order = np.lexsort((c[:, :, 2], c[:, :, 1], c[:, :, 0]), axis=-1)[:, 0]
        rolled = np.stack([c[np.arange(len(c)), (order + k) % 3] for k in range(3)], axis=1)
        flat = rolled.reshape(len(c), 9)
        return flat[np.lexsort(flat.T[::-1])]

    return bool(np.array_equal(canonical(va, ta), canonical(vb, tb)))


def _directed(
    a: K.Mesh,
    b: K.Mesh,
    alpha: float,
    big: float,
    tol: float,
    budget: int,
    progress: ProgressLike | None,
    label: str,
) -> tuple[float, float, str, int]:
    """[lo, hi] of h(A, B) for non-empty A and B, how the search stopped, and the cubes examined."""
    lows = K.vertex_lows(a.V, b, alpha)
    lo = float(lows.max())
    # Best first: each round splits the open cubes with the largest bounds (at most _ROUND of them), so a
    # search stopped by the budget has refined where the upper bound is.
    root, h0 = _root(a.V)
    cells = root
    sizes = np.array([h0])
    his, los = K.process_cells(root, h0, _radius(h0), a, b, alpha, big, lo + tol)
    done = 1
    closed_hi = -math.inf
    stopped = "tolerance"
    while True:
        if len(los):
            lo = max(lo, float(los.max()))
        keep = his > lo + tol
        if (~keep).any():
            closed_hi = max(closed_hi, float(his[~keep].max()))
        cells, sizes, his = cells[keep], sizes[keep], his[keep]
        if len(cells) == 0:
            break
        if progress is not None:
            progress.update(min(done / budget, 1.0), f"Measuring {label}")
        room = (budget - done) // 8
        if room < 1:
            stopped = "budget"
            break
        k = min(len(cells), room, _ROUND)
        pick = np.argpartition(-his, k - 1)[:k] if k < len(cells) else np.arange(len(cells))
        half = sizes[pick] / 2.0
        if (half < _LOW).any() or (half < np.abs(cells[pick]).max(axis=1) * 2.0**-50).any():
            stopped = "depth"
            break
        rest = np.ones(len(cells), bool)
        rest[pick] = False
        new_cells, new_sizes, new_his = [cells[rest]], [sizes[rest]], [his[rest]]
        los_parts = []
        for hn in np.unique(half):
            parents = cells[pick][half == hn]
            offsets = np.array([[dx, dy, dz] for dz in (-hn, hn) for dy in (-hn, hn) for dx in (-hn, hn)])
            kids = np.ascontiguousarray((parents[:, None, :] + offsets[None, :, :]).reshape(-1, 3))
            kh, kl = K.process_cells(kids, float(hn), _radius(float(hn)), a, b, alpha, big, lo + tol)
            done += len(kids)
            new_cells.append(kids)
            new_sizes.append(np.full(len(kids), hn))
            new_his.append(kh)
            los_parts.append(kl)
        cells, sizes, his = np.vstack(new_cells), np.concatenate(new_sizes), np.concatenate(new_his)
        los = np.concatenate(los_parts)
    open_hi = float(his.max()) if len(his) else -math.inf
    hi = max(closed_hi, open_hi, lo)
    log.debug("h(%s): [%r, %r] after %d cubes (%s)", label, lo, hi, done, stopped)
    return lo, hi, stopped, done


def solid_hausdorff(
    a_vertices: object,
    a_triangles: object,
    b_vertices: object,
    b_triangles: object,
    *,
    vertex_error: float = 0.0,
    tolerance: float | None = None,
    progress: ProgressLike | None = None,
    cell_budget: int = DEFAULT_CELL_BUDGET,
) -> SolidHausdorff:
    """Certified intervals of the directed Hausdorff distances between two solids (see the module docstring).

    Parameters
    ----------
    a_vertices, b_vertices : array_like, shape (n, 3)
        float64 coordinates.
    a_triangles, b_triangles : array_like of int, shape (m, 3)
        A valid closed outward triangle mesh each (several shells and cavities allowed); no triangle is
        the empty set.
    vertex_error : float
        How far (≥ 0, in each coordinate) every given vertex may be from the true one; the intervals are
        widened by ``2·√3·vertex_error``.
    tolerance : float, optional
        The search stops when ``hi − lo ≤ tolerance`` for both directions; default 10⁻⁶ × the diameter of
        A ∪ B (at least 1e-9).
    progress : ProgressLike, optional
        Receives ``update(fraction, message)``; may raise :class:`~mrm.core.errors.Cancelled`.
    cell_budget : int
        Cubes examined per direction at most; beyond it the interval is returned wider.

    Returns
    -------
    SolidHausdorff
        ``a_within`` ⊇ h(A, B), ``b_within`` ⊇ h(B, A), ``value`` ⊇ H. An empty solid is the empty set:
        h(∅, X) = 0, h(X, ∅) = inf for a non-empty X.

    Raises
    ------
    ParameterError
        For a negative or non-finite ``vertex_error`` or ``tolerance``, non-finite coordinates, triangles
        naming missing vertices, or coordinates outside the exact range (0 or 2⁻²⁴⁰…2⁵⁰ in magnitude).
    """
    if not (math.isfinite(vertex_error) and vertex_error >= 0.0):
        raise ParameterError("vertex_error must be a finite number ≥ 0")
    if tolerance is not None and not (math.isfinite(tolerance) and tolerance >= 0.0):
        raise ParameterError("tolerance must be a finite number ≥ 0")
    va, ta = _as_mesh(a_vertices, a_triangles, "solid A")
    vb, tb = _as_mesh(b_vertices, b_triangles, "solid B")
    a_empty = len(ta) == 0
    b_empty = len(tb) == 0
    if a_empty or b_empty:
        a_in = (0.0, 0.0) if a_empty else (math.inf, math.inf)
        b_in = (0.0, 0.0) if b_empty else (math.inf, math.inf)
        return SolidHausdorff(a_in, b_in, "tolerance", 0)
    if _same_surface(va, ta, vb, tb):  # an identity chain: the same oriented triangles, exactly 0
        return SolidHausdorff((0.0, 0.0), (0.0, 0.0), "tolerance", 0)
    both = np.vstack([va, vb])
    diam = float(np.linalg.norm(both.max(axis=0) - both.min(axis=0)))
    tol = max(1e-6 * diam, 1e-9) if tolerance is None else float(tolerance)
    roots = []
    for v in (va, vb):
        c, h = _root(v)
        roots.append(np.abs(c) + h)
        _check_range(np.vstack([c - h, c + h]), "the solids' bounding cube")
    big = max(float(np.abs(both).max()), *(float(r.max()) for r in roots))
    alpha = K.ABS * big
    ma = _index(va, ta)
    mb = _index(vb, tb)
    alo, ahi, sa, ca = _directed(ma, mb, alpha, big, tol, cell_budget, progress, "A outside B")
    blo, bhi, sb, cb = _directed(mb, ma, alpha, big, tol, cell_budget, progress, "B outside A")
    if progress is not None:
        progress.update(1.0, "Measured")
    if vertex_error > 0.0:
        # Rounded outward: a sum rounded to nearest is within half an ulp, one nextafter covers it.
        w = 2.0 * math.sqrt(3.0) * vertex_error * (1.0 + 2.0**-50)
        alo, ahi = max(0.0, math.nextafter(alo - w, -math.inf)), math.nextafter(ahi + w, math.inf)
        blo, bhi = max(0.0, math.nextafter(blo - w, -math.inf)), math.nextafter(bhi + w, math.inf)
    stopped = "tolerance"
    for s in (sa, sb):
        if s != "tolerance":
            stopped = s
    return SolidHausdorff((alo, ahi), (blo, bhi), stopped, ca + cb)
