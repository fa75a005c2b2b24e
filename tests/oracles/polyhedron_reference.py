"""Reference point-in-polyhedron test: ray parity with Fractions and a symbolically perturbed ray.

For a closed triangle mesh (float64 vertices, which are rationals) and a point p, count the triangles crossed
by the ray from p' = p + (0, δ, δ²) towards +x, δ → 0⁺. The perturbation keeps the ray off every edge and
vertex that a ray through p itself might graze: whether the projection of p' on the yz-plane lies inside a
projected triangle is decided by orientation signs that are polynomials in δ, compared lexicographically.
Triangles parallel to x are never crossed transversally by the perturbed ray and are skipped. p on the
surface (the plane of a crossed triangle passing through p) is reported, not decided.

Nothing here is shared with mrm.geometry.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

import numpy as np

Q = Fraction


def _sign(v: Fraction) -> int:
    return (v > 0) - (v < 0)


def _orient_perturbed(
    a: tuple[Fraction, Fraction], b: tuple[Fraction, Fraction], py: Fraction, pz: Fraction
) -> int:
    # Sign of the 2D orientation (a, b, q) with q = (py + δ, pz + δ²), coordinates (y, z).
    dy, dz = b[0] - a[0], b[1] - a[1]
    for v in (dy * (pz - a[1]) - dz * (py - a[0]), -dz, dy):
        if v:
            return _sign(v)
    return 0  # a == b: a degenerate projected edge


class Polyhedron:
    """A triangle mesh held as Fractions, for :meth:`inside` queries."""

    def __init__(self, vertices: np.ndarray, triangles: np.ndarray) -> None:
        self.tris: list[tuple[tuple[Fraction, Fraction, Fraction], ...]] = []
        verts = [tuple(Q(float(c)) for c in v) for v in np.asarray(vertices).tolist()]
        for t in np.asarray(triangles).tolist():
            a, b, c = (verts[i] for i in t)
            # keep the triangles not parallel to x (non-zero x component of the normal)
            nx = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1])
            if nx:
                self.tris.append((a, b, c))

    def inside(self, p: Sequence[int | Fraction]) -> bool:
        """True when p + (0, δ, δ²) is inside (odd crossings); raises ValueError when p is on the surface."""
        px, py, pz = (Q(v) for v in p)
        crossings = 0
        for a, b, c in self.tris:
            ya = (a[1], a[2])
            yb = (b[1], b[2])
            yc = (c[1], c[2])
            s1 = _orient_perturbed(ya, yb, py, pz)
            s2 = _orient_perturbed(yb, yc, py, pz)
            s3 = _orient_perturbed(yc, ya, py, pz)
            if not (s1 == s2 == s3 != 0):
                continue
            # x of the triangle's plane at (py, pz): n · (X − a) = 0
            ux, uy, uz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
            vx, vy, vz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
            nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
            x = a[0] - (ny * (py - a[1]) + nz * (pz - a[2])) / nx
            if x == px:
                raise ValueError(f"the point {tuple(p)} is on the surface")
            if x > px:
                crossings += 1
        return crossings % 2 == 1


def gauss(
    vertices: np.ndarray, triangles: np.ndarray, box: tuple[int, int, int, int, int, int]
) -> np.ndarray:
    """The voxels of the box (xmin, ymin, zmin, xmax, ymax, zmax) whose centre is inside: mask[z, y, x]."""
    x0, y0, z0, x1, y1, z1 = box
    poly = Polyhedron(vertices, triangles)
    out = np.zeros((z1 - z0 + 1, y1 - y0 + 1, x1 - x0 + 1), bool)
    for k in range(z1 - z0 + 1):
        for j in range(y1 - y0 + 1):
            for i in range(x1 - x0 + 1):
                out[k, j, i] = poly.inside((x0 + i, y0 + j, z0 + k))
    return out


def _dot(a: tuple[Fraction, ...], b: tuple[Fraction, ...]) -> Fraction:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a: tuple[Fraction, ...], b: tuple[Fraction, ...]) -> tuple[Fraction, Fraction, Fraction]:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def triangle_meets_cube(tri: Sequence[tuple[Fraction, ...]], centre: Sequence[int], half: Fraction) -> bool:
    """True when a closed triangle and the closed cube ``centre ± half`` intersect (separating axes, exact).

    Two closed convex sets are disjoint iff some axis separates their projections strictly; for a triangle and
    a box the candidate axes are the box's three normals, the triangle's normal and the nine cross products of
    the triangle's edges with the box's normals.
    """
    c = tuple(Q(v) for v in centre)
    v = [tuple(p[i] - c[i] for i in range(3)) for p in tri]  # the cube centred at the origin
    edges = [tuple(v[(k + 1) % 3][i] - v[k][i] for i in range(3)) for k in range(3)]
    units = [(Q(1), Q(0), Q(0)), (Q(0), Q(1), Q(0)), (Q(0), Q(0), Q(1))]
    axes = [*units, _cross(edges[0], edges[1])]
    axes += [_cross(e, u) for e in edges for u in units]
    for ax in axes:
        if not any(ax):
            continue
        proj = [_dot(p, ax) for p in v]
        r = half * (abs(ax[0]) + abs(ax[1]) + abs(ax[2]))
        if min(proj) > r or max(proj) < -r:
            return False
    return True


def supercover(
    vertices: np.ndarray, triangles: np.ndarray, box: tuple[int, int, int, int, int, int]
) -> np.ndarray:
    """The voxels of the box whose closed cube V(p) meets the closed solid: mask[z, y, x].

    V(p) meets the solid when it meets its boundary (a triangle) or lies inside it (then so does its centre).
    """
    x0, y0, z0, x1, y1, z1 = box
    poly = Polyhedron(vertices, triangles)
    verts = [tuple(Q(float(c)) for c in v) for v in np.asarray(vertices).tolist()]
    tris = [tuple(verts[i] for i in t) for t in np.asarray(triangles).tolist()]
    half = Q(1, 2)
    out = np.zeros((z1 - z0 + 1, y1 - y0 + 1, x1 - x0 + 1), bool)
    for k in range(z1 - z0 + 1):
        for j in range(y1 - y0 + 1):
            for i in range(x1 - x0 + 1):
                p = (x0 + i, y0 + j, z0 + k)
                hit = False
                for t in tris:
                    # a quick exact rejection by boxes before the separating axes
                    if any(
                        min(q[a] for q in t) > p[a] + half or max(q[a] for q in t) < p[a] - half
                        for a in range(3)
                    ):
                        continue
                    if triangle_meets_cube(t, p, half):
                        hit = True
                        break
                out[k, j, i] = hit or poly.inside(p)
    return out
