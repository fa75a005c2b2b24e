"""Reference voxelization: the definitions of docs/design.md §11, evaluated with fractions.Fraction.

D(E) = { p ∈ Z³ : E ∩ K(p) ≠ ∅ } with τ = (ε, ε², ε³), ε → 0⁺, and

    open        K(p) = int V(p)                 (only for the sandwich property; not a product model)
    standard    K(p) = int V(p) + τ
    supercover  K(p) = V(p)
    gauss       K(p) = { p + τ }

Quantities that depend on ε are 4-tuples (v0, v1, v2, v3) meaning v0 + v1·ε + v2·ε² + v3·ε³; Python
compares tuples lexicographically, which is exactly "for every sufficiently small ε > 0". Every kernel is an
axis-aligned box lo ⋖ x ⋖ hi whose bounds are such tuples (⋖ is < for the open boxes, ≤ for the closed ones).

A closed triangle abc is { a + s(b − a) + t(c − a) : s, t ≥ 0, s + t ≤ 1 }; it meets a kernel box when the
linear system in (s, t) made of those three inequalities and the six of the box has a solution, decided by
Fourier–Motzkin elimination (strict inequalities stay strict; coefficients are rationals, right-hand sides are
tuples). Degenerate triangles (segments, points) need no special case.

A solid P is given by its closed boundary. p + τ ∈ P is decided by the parity of the triangles crossed by the
ray from p + τ towards +z (the kernels cast theirs towards +x): the ray's projection (p_x + ε, p_y + ε²) is
never on a projected edge, and p + τ is never on a triangle. K(p) meets P when it meets a triangle, or else
(K(p) is connected and misses ∂P, so it lies wholly inside or outside) when p + τ ∈ K(p) is inside.

Nothing here is shared with mrm.geometry: no float filter, no separating axes, no scanline.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from fractions import Fraction

Q = Fraction
Eps = tuple[int, int, int, int]
Pt = tuple[Fraction, Fraction, Fraction]
IPt = tuple[int, int, int]
Voxel = tuple[int, int, int]

REFERENCE_MODELS = ("open", "standard", "supercover", "gauss")
HALF = Q(1, 2)
ZERO4: Eps = (0, 0, 0, 0)

# Speed, without changing any answer: the whole problem is scaled by S = 2·(the common denominator of the
# coordinates: their lcm, not their largest denominator, which is the same only for powers of two; an exact
# image under α = 1/5 has fifths and quarters), so that every coordinate and every half-integer of the grid
# becomes an integer and the arithmetic runs on Python ints. Scaling all real parts by S > 0 keeps every
# comparison; the ε coefficients are left as they are (scaling the coefficients of one power of ε by a
# positive constant in every quantity at once keeps every sign, and all quantities are combinations with
# positive weights).


def _e(v0: int, axis: int = -1) -> Eps:
    """v0, plus the axis's infinitesimal of τ when ``axis`` is 0, 1 or 2 (ε, ε², ε³)."""
    out = [v0, 0, 0, 0]
    if axis >= 0:
        out[axis + 1] = 1
    return (out[0], out[1], out[2], out[3])


def _add(u: Eps, v: Eps) -> Eps:
    return (u[0] + v[0], u[1] + v[1], u[2] + v[2], u[3] + v[3])


def _scale(u: Eps, f: int) -> Eps:
    return (u[0] * f, u[1] * f, u[2] * f, u[3] * f)


def kernel_box(p: Voxel, model: str, scale: int) -> tuple[list[Eps], list[Eps], bool]:
    """(lo, hi, strict): K(p) = { x : lo[d] ⋖ x[d] ⋖ hi[d] for d = x, y, z }, scaled by ``scale``."""
    h = scale // 2
    c = [scale * u for u in p]
    if model == "open":
        return [_e(u - h) for u in c], [_e(u + h) for u in c], True
    if model == "standard":
        return [_e(u - h, d) for d, u in enumerate(c)], [_e(u + h, d) for d, u in enumerate(c)], True
    if model == "supercover":
        return [_e(u - h) for u in c], [_e(u + h) for u in c], False
    if model == "gauss":
        return [_e(u, d) for d, u in enumerate(c)], [_e(u, d) for d, u in enumerate(c)], False
    raise ValueError(model)


# A constraint c_s·s + c_t·t ⋖ r: (c_s, c_t, r, strict).
Constraint = tuple[int, int, Eps, bool]


def _feasible(cons: list[Constraint]) -> bool:
    """Fourier–Motzkin: does some real (s, t) satisfy every constraint (for all small ε)?"""
    for var in (0, 1):
        upper, lower, rest = [], [], []
        for c in cons:
            (upper if c[var] > 0 else lower if c[var] < 0 else rest).append(c)
        new = list(rest)
        for u in upper:
            for lo in lower:
                fu, fl = -lo[var], u[var]  # positive weights that cancel the variable
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


def triangle_meets(tri: Sequence[IPt], box: tuple[list[Eps], list[Eps], bool]) -> bool:
    """Is there a point of the closed triangle (a, b, c) in the kernel box?"""
    a, b, c = tri
    lo, hi, strict = box
    cons: list[Constraint] = [(-1, 0, ZERO4, False), (0, -1, ZERO4, False), (1, 1, _e(1), False)]
    for d in range(3):
        us, ut = b[d] - a[d], c[d] - a[d]
        cons.append((us, ut, _add(hi[d], _e(-a[d])), strict))  # a + s·u + t·w ⋖ hi
        cons.append((-us, -ut, _add(_e(a[d]), _scale(lo[d], -1)), strict))  # lo ⋖ a + s·u + t·w
    return _feasible(cons)


def inside_tau(p: Voxel, tris: Iterable[Sequence[IPt]], scale: int) -> bool:
    """Is p + τ inside the solid bounded by the closed surface ``tris`` (parity of a ray towards +z)?"""
    qx, qy, qz = _e(scale * p[0], 0), _e(scale * p[1], 1), _e(scale * p[2], 2)
    count = 0
    for a, b, c in tris:
        # The ray's projection q = (p_x + ε, p_y + ε²) can only be inside a projection that holds (p_x, p_y).
        if not (min(a[0], b[0], c[0]) <= qx[0] <= max(a[0], b[0], c[0])):
            continue
        if not (min(a[1], b[1], c[1]) <= qy[0] <= max(a[1], b[1], c[1])):
            continue
        area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        if area == 0:
            continue  # seen edge-on from above: never crossed by a generic vertical ray
        inside = True
        for u, w in ((a, b), (b, c), (c, a)):
            # orient(u, w, q) in the (x, y) plane
            side = _add(_scale(_add(qy, _e(-u[1])), w[0] - u[0]), _scale(_add(qx, _e(-u[0])), u[1] - w[1]))
            if (side > ZERO4) != (area > 0):
                inside = False
                break
        if not inside:
            continue
        nx = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1])
        ny = (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2])
        nz = area
        # the plane n·(x − a) = 0 is above q when nz·z_plane > nz·q_z (times the sign of nz):
        # nz·z_plane = nz·a_z − nx·(q_x − a_x) − ny·(q_y − a_y)
        lhs = _add(_e(nz * a[2]), _add(_scale(_add(qx, _e(-a[0])), -nx), _scale(_add(qy, _e(-a[1])), -ny)))
        rhs = _scale(qz, nz)
        if (lhs > rhs) if nz > 0 else (lhs < rhs):
            count += 1
    return count % 2 == 1


# ------------------------------------------------------------------------------------------ entry points
def exact_triangles(
    vertices: Iterable[Iterable[float]], triangles: Iterable[Iterable[int]]
) -> list[list[Pt]]:
    """The triangles as lists of three exact points (every float64 is a rational)."""
    v = [tuple(Q(float(u)) for u in row) for row in vertices]
    return [[v[int(i)] for i in tri] for tri in triangles]  # type: ignore[misc]


def _closed_range(lo: Fraction, hi: Fraction) -> range:
    """Integers k whose closed interval [k − ½, k + ½] meets [lo, hi]."""
    return range(math.ceil(lo - HALF), math.floor(hi + HALF) + 1)


def reference_voxelize_all(
    tris: list[list[Pt]], solid: bool, models: Sequence[str] = REFERENCE_MODELS
) -> dict[str, set[Voxel]]:
    """D(E) = { p : E ∩ K(p) ≠ ∅ } in each model, for the triangles (their union, or the solid they bound)."""
    out: dict[str, set[Voxel]] = {m: set() for m in models}
    if not tris:
        return out
    pts = [q for t in tris for q in t]
    scale = 2 * math.lcm(*(q[d].denominator for q in pts for d in range(3)))
    itris = [[tuple(int(q[d] * scale) for d in range(3)) for q in t] for t in tris]
    ranges = [_closed_range(min(q[d] for q in pts), max(q[d] for q in pts)) for d in range(3)]
    boxes = [
        ([min(q[d] for q in t) for d in range(3)], [max(q[d] for q in t) for d in range(3)]) for t in itris
    ]
    h = scale // 2
    for i in ranges[0]:
        for j in ranges[1]:
            for k in ranges[2]:
                p = (i, j, k)
                c = (scale * i, scale * j, scale * k)
                # K(p) ⊂ V(p): a triangle whose bounding box misses V(p) cannot meet K(p).
                near = [
                    t
                    for t, (tlo, thi) in zip(itris, boxes, strict=True)
                    if all(tlo[d] <= c[d] + h and thi[d] >= c[d] - h for d in range(3))
                ]
                inside: bool | None = None
                for model in models:
                    box = kernel_box(p, model, scale)
                    hit = any(triangle_meets(t, box) for t in near)
                    if not hit and solid:
                        if inside is None:
                            inside = inside_tau(p, itris, scale)
                        hit = inside
                    if hit:
                        out[model].add(p)
    return out


def reference_voxelize(tris: list[list[Pt]], model: str, solid: bool) -> set[Voxel]:
    """D(E) in one model (see :func:`reference_voxelize_all`)."""
    return reference_voxelize_all(tris, solid, (model,))[model]


def voxel_set(mask: object, origin: tuple[int, int, int]) -> set[Voxel]:
    """The voxels of a (mask[k, j, i], origin) pair as a set of (x, y, z)."""
    import numpy as np

    ks, js, is_ = np.nonzero(np.asarray(mask))
    x0, y0, z0 = origin
    return {(int(x0 + i), int(y0 + j), int(z0 + k)) for k, j, i in zip(ks, js, is_, strict=True)}
