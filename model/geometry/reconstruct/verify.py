"""Exact verification that a polygonal geometry is a reversible continuation of a pixel set.

Reference: docs/design.md §3.

The check is the corridor condition of docs/algorithms.md §3.4, made exact with integers: every float64
coordinate is a dyadic rational, so the coordinates of a ring are scaled by a power of two to integers and
every test is a sign of a sum of products that fits in 64 bits. For a geometry P and a pixel set A, with the
corridors of :mod:`mrm.geometry.reconstruct.border`:

* each polygon ring is matched to one crack ring of A (outer ring ↔ shell, hole ring ↔ hole of the same
  4-component, each used once), so the polygons are the 4-components and the holes the bounded
  8-components of the complement;
* every vertex lies strictly inside a piece of its ring's corridor, the pieces visited in path order, once
  around;
* every edge crosses the gates between its end pieces, strictly inside each gate and in order;
* no fold, and no two edges meet inside a piece that holds two or more vertices.

Pieces of different visits are disjoint, so these conditions make every ring simple and the rings pairwise
disjoint, keep ∂P inside V(A) crossing between pixels only through open sides shared by two pixels of A,
make ∂P cross every border pixel and keep every outside centre out (cover models: conditions C1–C3, hence
D_standard(P) = D_supercover(P) = A). Under ``gauss`` the corridor is made of the dual squares of the crack
pointels (:mod:`mrm.geometry.reconstruct._dual`): it holds no pixel centre, so a ring following it is
homotopic to
its crack ring in the plane minus the centres, every centre of A is strictly inside P, every other centre
strictly outside, none on ∂P, and ∂P stays within the voxels of the border pixels on either side.
A pixel with no neighbour in A (its crack ring is its own) only needs its ring inside the open square (and,
under ``gauss``, around its centre).

The conditions are sufficient, not necessary: a geometry that passes is proven reversible; one that fails
may still discretize to A by other means (the report says which condition failed where).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.grids import PixelSet
from mrm.geometry.reconstruct import _kernels as _k
from mrm.geometry.reconstruct.border import Corridor, corridors
from mrm.reps.region import region_of

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

_MAX_BITS = 30  # coordinate differences (scaled) stay below 2^30: products below 2^60


@dataclass
class Report:
    """The outcome of :func:`verify`: ``ok`` and, when not, what failed where."""

    ok: bool = True
    problems: list[str] = field(default_factory=list)

    def fail(self, message: str) -> None:
        """Record a failed condition."""
        self.ok = False
        self.problems.append(message)

    def __bool__(self) -> bool:
        return self.ok


def _dyadic_bits(v: FloatArray) -> int:
    # The number of fractional bits needed to write every value exactly: v = m · 2^e with 53-bit m.
    v = v[v != 0]
    if v.size == 0:
        return 0
    m, e = np.frexp(v)
    mi = (m * 2.0**53).astype(np.int64)
    tz = np.log2((mi & -mi).astype(np.float64)).astype(np.int64)  # trailing zero bits of the mantissa
    return int(max(0, int(np.max(53 - e - tz))))


def _scaled(coords: FloatArray, k: int) -> IntArray:
    return np.asarray(np.round(coords * float(2**k)), dtype=np.int64)


def _cell_key(x: float, y: float, gauss: bool) -> tuple[int, int]:
    # The unit cell a point strictly inside a piece belongs to: the pixel (cover models, pieces are parts of
    # pixel squares) or the dual square [i − 1, i] × [j − 1, j] of a pointel (gauss), keyed by its corner.
    if gauss:
        return math.floor(x), math.floor(y)
    return round(x), round(y)


def _locate(
    coords: FloatArray,
    cor: list[Corridor],
    where: dict[tuple[int, int], list[tuple[int, int]]],
    gauss: bool,
) -> tuple[int, IntArray] | None:
    # The crack ring holding every vertex strictly inside one of its pieces, and the piece of each vertex.
    ring = -1
    pieces = np.empty(coords.shape[0], dtype=np.int64)
    for i, (x, y) in enumerate(coords.tolist()):
        px, py = _cell_key(x, y, gauss)
        hit = None
        for r, t in where.get((int(px), int(py)), ()):
            a = cor[r].pieces[t]
            if a[0] < x < a[1] and a[2] < y < a[3]:
                hit = (r, t)
                break
        if hit is None or (ring >= 0 and hit[0] != ring):
            return None
        ring = hit[0]
        pieces[i] = hit[1]
    return ring, pieces


def _unwrap(t: IntArray, n: int) -> tuple[int, IntArray] | None:
    # Rotate so that the piece indices are non-decreasing and go round at most once; return the rotation.
    m = t.size
    drops = [i for i in range(m) if t[i] < t[i - 1]]
    if len(drops) > 1:
        return None
    start = drops[0] if drops else 0
    r = np.roll(t, -start)
    if np.any(np.diff(r) < 0) or r[-1] > r[0] + n:
        return None
    return start, r.astype(np.int64)


def _point_inside(ring: IntArray, x: int, y: int) -> bool:
    # Strictly inside a simple ring (integer coordinates): crossing number, point on the boundary = False.
    inside = False
    m = ring.shape[0]
    for i in range(m):
        ax, ay = int(ring[i, 0]), int(ring[i, 1])
        bx, by = int(ring[(i + 1) % m, 0]), int(ring[(i + 1) % m, 1])
        cr = (bx - ax) * (y - ay) - (by - ay) * (x - ax)
        if cr == 0 and min(ax, bx) <= x <= max(ax, bx) and min(ay, by) <= y <= max(ay, by):
            return False
        if (ay > y) != (by > y) and (cr > 0) == (by > ay):
            inside = not inside
    return inside


def _check_ring(
    coords: FloatArray,
    cor: list[Corridor],
    where: dict[tuple[int, int], list[tuple[int, int]]],
    model: str,
    label: str,
    report: Report,
) -> int:
    """Verify one polygon ring; return the crack ring it follows (−1 when it fails)."""
    if coords.shape[0] < 3:
        report.fail(f"{label}: fewer than 3 vertices")
        return -1
    for attempt in (coords, coords[::-1]):
        found = _locate(attempt, cor, where, model == "gauss")
        if found is None:
            continue
        r, t = found
        c = cor[r]
        if c.gate_dir.size == 0:
            # an isolated pixel: inside its open square (checked by _locate); gauss: around its centre
            if model == "gauss":
                k = _dyadic_bits(attempt.ravel())
                cx, cy = (c.pieces[0, 0] + c.pieces[0, 1]) / 2, (c.pieces[0, 2] + c.pieces[0, 3]) / 2
                sc = _scaled(attempt, k)
                if not _point_inside(sc, round(cx * 2**k), round(cy * 2**k)):
                    report.fail(
                        f"{label}: the centre of isolated pixel ({cx:g}, {cy:g}) is not strictly inside"
                    )
                    return -1
            return r
        n = c.gate_dir.size
        un = _unwrap(t, n)
        if un is None:
            continue
        start, vt = un
        ring = np.roll(attempt, -start, axis=0)
        k = _dyadic_bits(ring.ravel())
        lo = np.minimum(ring.min(axis=0), c.pieces[:, [0, 2]].min(axis=0))
        hi = np.maximum(ring.max(axis=0), c.pieces[:, [1, 3]].max(axis=0))
        ext_bits = int(np.ceil(np.log2(float(np.max(hi - lo)) * 4 + 2)))
        if ext_bits + k > _MAX_BITS:
            report.fail(f"{label}: coordinates too fine for the exact check ({k} fractional bits)")
            return -1
        # Q-units (quarter pixels) of the corridor, vertices scaled by 2^k on top
        origin = np.floor(lo).astype(np.int64)
        rect = np.round((c.pieces - np.repeat(origin, 2)) * 4).astype(np.int64)
        gp = np.round((c.gate_left - origin) * 4).astype(np.int64)
        gq = np.round((c.gate_right - origin) * 4).astype(np.int64)
        iv = _scaled((ring - origin) * 4, k)
        bad = np.zeros(ring.shape[0], dtype=np.bool_)
        ok = _k.verify_ring(
            np.ascontiguousarray(iv[:, 0]),
            np.ascontiguousarray(iv[:, 1]),
            vt,
            rect,
            gp,
            gq,
            c.gate_dir,
            1 << k,
            bad,
        )
        if ok:
            return r
        where_bad = np.flatnonzero(bad)[:3]
        pts = ", ".join(f"({ring[i, 0]:g}, {ring[i, 1]:g})" for i in where_bad)
        report.fail(f"{label}: the ring leaves its corridor near {pts}")
        return -1
    report.fail(f"{label}: its vertices do not follow the corridor of one crack ring in order")
    return -1


def verify(geom: Any, ps: PixelSet, model: str = "standard") -> Report:
    """Prove exactly that ``geom`` is a reversible continuation of ``ps``, or say which condition fails.

    See the module docstring for the conditions.

    Parameters
    ----------
    geom : shapely Polygon or MultiPolygon
        The candidate R(A), with dyadic float64 coordinates (every float64 is one).
    ps : PixelSet
        The pixel set A.
    model : {"standard", "supercover", "gauss"}
        The discretization model.

    Returns
    -------
    Report
        ``ok`` (truthy) when every condition holds.
    """
    report = Report()
    if not isinstance(geom, Polygon | MultiPolygon):
        report.fail(f"not a Polygon or MultiPolygon: {type(geom).__name__}")
        return report
    if ps.is_empty():
        if not geom.is_empty:
            report.fail("the pixel set is empty but the geometry is not")
        return report
    polys = list(geom.geoms) if isinstance(geom, MultiPolygon) else ([geom] if not geom.is_empty else [])
    region = region_of(ps)
    chains = region.boundary_chains
    owner: list[tuple[int, bool]] = []  # (component index, is hole) per crack ring
    for ci, comp in enumerate(region.components):
        owner.append((ci, False))
        owner.extend((ci, True) for _ in comp.holes)
    cor = corridors(chains, model)
    where: dict[tuple[int, int], list[tuple[int, int]]] = {}
    for r, c in enumerate(cor):
        for t, a in enumerate(c.pieces.tolist()):
            key = _cell_key((a[0] + a[1]) / 2, (a[2] + a[3]) / 2, model == "gauss")
            where.setdefault(key, []).append((r, t))
    if len(polys) != len(region.components):
        report.fail(f"{len(polys)} polygons for {len(region.components)} 4-connected components")
    used = [False] * len(chains)
    for pi, poly in enumerate(polys):
        rings = [np.asarray(poly.exterior.coords, dtype=np.float64)[:-1]]
        rings += [np.asarray(h.coords, dtype=np.float64)[:-1] for h in poly.interiors]
        shell_comp = -1
        for ri, coords in enumerate(rings):
            if not np.all(np.isfinite(coords)):
                report.fail(f"polygon {pi}: non-finite coordinates")
                return report
            label = f"polygon {pi} {'shell' if ri == 0 else f'hole {ri - 1}'}"
            r = _check_ring(coords, cor, where, model, label, report)
            if r < 0:
                continue
            if used[r]:
                report.fail(f"{label}: follows a crack ring already used")
            used[r] = True
            c_idx, is_hole = owner[r]
            if is_hole != (ri > 0):
                report.fail(f"{label}: follows a {'hole' if is_hole else 'outer'} boundary")
            if ri == 0:
                shell_comp = c_idx
            elif shell_comp >= 0 and c_idx != shell_comp:
                report.fail(f"{label}: a hole of another component")
    if report.ok and not all(used):
        report.fail(f"{used.count(False)} crack rings have no polygon ring")
    return report
