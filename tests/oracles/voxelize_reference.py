"""Reference voxelization: the definitions of docs/design.md §11, evaluated with fractions.Fraction.

D(E) = { p ∈ Z³ : E ∩ K(p) ≠ ∅ } with τ = (ε, ε², ε³), ε → 0⁺, and

    open        K(p) = int V(p)                 (only for the sandwich property; not a product model)
    standard    K(p) = int V(p) + τ
    supercover  K(p) = V(p)
    gauss       K(p) = { p + τ }

Quantities that depend on ε are 4-tuples (v0, v1, v2, v3) meaning v0 + v1·ε + v2·ε² + v3·ε³; Python compares
tuples lexicographically, which is exactly "for every sufficiently small ε > 0". Every kernel is an axis-aligned
box lo ⋖ x ⋖ hi whose bounds are such tuples (⋖ is < for the open boxes, ≤ for the closed ones).

A closed triangle abc is { a + s(b − a) + t(c − a) : s, t ≥ 0, s + t ≤ 1 }; it meets a kernel box when the
linear system in (s, t) made of those three inequalities and the six of the box has a solution, decided by
Fourier–Motzkin elimination (strict inequalities stay strict; coefficients are rationals, right-hand sides are
tuples). Degenerate triangles (segments, points) need no special case.

A solid P is given by its closed boundary. p + τ ∈ P is decided by the parity of the triangles crossed by the
ray from p + τ towards +z (the kernels cast theirs towards +x): the ray's projection (p_x + ε, p_y + ε²) is never
on a projected edge, and p + τ is never on a triangle. K(p) meets P when it meets a triangle, or else (K(p) is
connected and misses ∂P, so it lies wholly inside or outside) when p + τ ∈ K(p) is inside.

Nothing here is shared with mrm.geometry: no float filter, no separating axes, no scanline.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from fractions import Fraction

Q = Fraction
Eps = tuple[Fraction, Fraction, Fraction, Fraction]
Pt = tuple[Fraction, Fraction, Fraction]
Voxel = tuple[int, int, int]

REFERENCE_MODELS = ("open", "standard", "supercover", "gauss")
HALF = Q(1, 2)
ZERO4: Eps = (Q(0), Q(0), Q(0), Q(0))


def _e(v0: Fraction | int, axis: int = -1) -> Eps:
    """v0, plus the axis's infinitesimal of τ when ``axis`` is 0, 1 or 2 (ε, ε², ε³)."""
    out = [Q(v0), Q(0), Q(0), Q(0)]
    if axis >= 0:
        out[axis + 1] = Q(1)
    return (out[0], out[1], out[2], out[3])


def _add(u: Eps, v: Eps) -> Eps:
    return (u[0] + v[0], u[1] + v[1], u[2] + v[2], u[3] + v[3])


def _scale(u: Eps, f: Fraction) -> Eps:
    return (u[0] * f, u[1] * f, u[2] * f, u[3] * f)


def kernel_box(p: Voxel, model: str) -> tuple[list[Eps], list[Eps], bool]:
    """(lo, hi, strict): K(p) = { x : lo[d] ⋖ x[d] ⋖ hi[d] for d = x, y, z }."""
    if model == "open":
        return [_e(c - HALF) for c in p], [_e(c + HALF) for c in p], True
    if model == "standard":
        return [_e(c - HALF, d) for d, c in enumerate(p)], [_e(c + HALF, d) for d, c in enumerate(p)], True
    if model == "supercover":
        return [_e(c - HALF) for c in p], [_e(c + HALF) for c in p], False
    if model == "gauss":
        return [_e(c, d) for d, c in enumerate(p)], [_e(c, d) for d, c in enumerate(p)], False
    raise ValueError(model)


# A constraint c_s·s + c_t·t ⋖ r: (c_s, c_t, r, strict).
Constraint = tuple[Fraction, Fraction, Eps, bool]


def _feasible(cons: list[Constraint]) -> bool:
    """Fourier–Motzkin: does some real (s, t) satisfy every constraint (for all small ε)?"""
    for var in (0, 1):
        upper, lower, rest = [], [], []
        for c in cons:
            (upper if c[var] > 0 else lower if c[var] < 0 else rest).append(c)
        new = list(rest)
        for u in upper:
            for lo in lower:
                fu, fl = 1 / u[var], 1 / -lo[var]
                new.append(
                    (
                        u[0] * fu + lo[0] * fl,
                        u[1] * fu + lo[1] * fl,
                        _add(_scale(u[2], fu), _scale(lo[2], fl)),
                        u[3] or lo[3],
                    )
                )
        cons = new
    # Only 0 ⋖ r is left.
    return all((r > ZERO4) if strict else (r >= ZERO4) for _, _, r, strict in cons)


def triangle_meets(tri: Sequence[Pt], box: tuple[list[Eps], list[Eps], bool]) -> bool:
    """Is there a point of the closed triangle (a, b, c) in the kernel box?"""
    a, b, c = tri
    lo, hi, strict = box
    cons: list[Constraint] = [
        (Q(-1), Q(0), ZERO4, False),
        (Q(0), Q(-1), ZERO4, False),
        (Q(1), Q(1), _e(1), False),
    ]
    for d in range(3):
        us, ut = b[d] - a[d], c[d] - a[d]
        cons.append((us, ut, _add(hi[d], _e(-a[d])), strict))  # a + s·u + t·w ⋖ hi
        cons.append((-us, -ut, _add(_e(a[d]), _scale(lo[d], Q(-1))), strict))  # lo ⋖ a + s·u + t·w
    return _feasible(cons)


def inside_tau(p: Voxel, tris: Iterable[Sequence[Pt]]) -> bool:
    """Is p + τ inside the solid bounded by the closed surface ``tris`` (parity of a ray towards +z)?"""
    qx, qy, qz = _e(p[0], 0), _e(p[1], 1), _e(p[2], 2)
    count = 0
    for a, b, c in tris:
        area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        if area == 0:
            continue  # seen edge-on from above: never crossed by a generic vertical ray
        sides = []
        for u, w in ((a, b), (b, c), (c, a)):
            # orient(u, w, q) in the (x, y) plane, q = (p_x + ε, p_y + ε²)
            side = _add(_scale(_add(qy, _e(-u[1])), w[0] - u[0]), _scale(_add(qx, _e(-u[0])), u[1] - w[1]))
            sides.append(side > ZERO4)
        if not all(s == (area > 0) for s in sides):
            continue
        nx = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1])
        ny = (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2])
        nz = area
        # height of the plane n·(x − a) = 0 above q's projection
        z = _add(_e(a[2]), _scale(_add(_scale(_add(qx, _e(-a[0])), nx), _scale(_add(qy, _e(-a[1])), ny)), -1 / nz))
        if z > qz:
            count += 1
    return count % 2 == 1


# ------------------------------------------------------------------------------------------ entry points
def exact_triangles(vertices: Iterable[Iterable[float]], triangles: Iterable[Iterable[int]]) -> list[list[Pt]]:
    """The triangles as lists of three exact points (every float64 is a rational)."""
    v = [tuple(Q(float(u)) for u in row) for row in vertices]
    return [[v[int(i)] for i in tri] for tri in triangles]  # type: ignore[misc]


def _closed_range(lo: Fraction, hi: Fraction) -> range:
    """Integers k whose closed interval [k − ½, k + ½] meets [lo, hi]."""
    return range(math.ceil(lo - HALF), math.floor(hi + HALF) + 1)


def reference_voxelize(tris: list[list[Pt]], model: str, solid: bool) -> set[Voxel]:
    """D(E) = { p : E ∩ K(p) ≠ ∅ } for the triangles ``tris`` (their union, or the solid they bound)."""
    if not tris:
        return set()
    pts = [q for t in tris for q in t]
    ranges = [_closed_range(min(q[d] for q in pts), max(q[d] for q in pts)) for d in range(3)]
    boxes = [
        ([min(q[d] for q in t) for d in range(3)], [max(q[d] for q in t) for d in range(3)]) for t in tris
    ]
    out: set[Voxel] = set()
    for i in ranges[0]:
        for j in ranges[1]:
            for k in ranges[2]:
                p = (i, j, k)
                box = kernel_box(p, model)
                hit = False
                for t, (tlo, thi) in zip(tris, boxes, strict=True):
                    # K(p) ⊂ V(p): a triangle whose bounding box misses V(p) cannot meet K(p).
                    if any(tlo[d] > p[d] + HALF or thi[d] < p[d] - HALF for d in range(3)):
                        continue
                    if triangle_meets(t, box):
                        hit = True
                        break
                if not hit and solid:
                    hit = inside_tau(p, tris)
                if hit:
                    out.add(p)
    return out


def voxel_set(mask: object, origin: tuple[int, int, int]) -> set[Voxel]:
    """The voxels of a (mask[k, j, i], origin) pair as a set of (x, y, z)."""
    import numpy as np

    ks, js, is_ = np.nonzero(np.asarray(mask))
    x0, y0, z0 = origin
    return {(int(x0 + i), int(y0 + j), int(z0 + k)) for k, j, i in zip(ks, js, is_, strict=True)}
