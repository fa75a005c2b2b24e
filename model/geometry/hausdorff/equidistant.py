"""The points equidistant from three features of ∂B (vertices and edges' lines), solved exactly.

Three vertices meet at a circumcentre; a vertex and a line are equidistant on a parabola, which meets a
bisector line at roots of a quadratic; two lines have two angle bisectors with coefficients in ``Q(√(N₁N₂))``.
The same code runs on a tower (:class:`mrm.geometry.hausdorff.exact_numbers._Tower`, exact) or on the
interval kit (:data:`mrm.geometry.hausdorff.intervals._IV_TOWER`, enclosures that may raise ``_Undecided``).
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING, Any

from mrm.geometry.hausdorff.exact_numbers import Num, _div, _neg, _sign, _solve_quadratic, _Tower
from mrm.geometry.hausdorff.intervals import Rat, _IVTower
from mrm.geometry.hausdorff.shapes import _Shape

if TYPE_CHECKING:
    from mrm.geometry.hausdorff.branch_and_bound import _Run


def _could_be_nearest(b: _Shape, trio: tuple[tuple[str, Any, Rat, Rat], ...], x: Num, y: Num) -> bool:
    """Check necessary conditions for the three features to be nearest to (x, y) outside B.

    The point lies on the outer side of each edge's line and in its slab, and in each vertex's normal cone
    (no incident edge comes nearer). Raises _Undecided in interval mode when a sign is unclear.
    """
    for kind, f, _, _ in trio:
        if kind == "e":
            ux, uy, wx, wy = b.edges[f]
            mx, my = wx - ux, wy - uy
            if _sign(mx * (y - uy) - my * (x - ux)) > 0:
                return False
            proj = (x - ux) * mx + (y - uy) * my
            if _sign(proj) < 0 or _sign(proj - b.norms[f]) > 0:
                return False
        else:
            vx, vy = f
            dx, dy = x - vx, y - vy
            for ix, iy, ox, oy in b.wedges[f]:
                if _sign(dx * ix + dy * iy) < 0 or _sign(dx * ox + dy * oy) > 0:
                    return False
    return True


def _line(b: _Shape, e: int) -> tuple[int, int, int, int]:
    """(a, b, c, N) with ℓ(x) = a·x + b·y + c = cross(w − u, x − u) and N = a² + b²."""
    ux, uy, wx, wy = b.edges[e]
    mx, my = wx - ux, wy - uy
    return -my, mx, my * ux - mx * uy, b.norms[e]


def _equidistant(
    run: _Run, trio: tuple[tuple[str, Any, Rat, Rat], ...], t: _Tower | _IVTower
) -> list[tuple[Num, Num]]:
    """The points equidistant from three features (exact with a tower, enclosures with the interval kit)."""
    b = run.b
    vs = [f[1] for f in trio if f[0] == "v"]
    es = [_line(b, f[1]) for f in trio if f[0] == "e"]
    out: list[tuple[Num, Num]] = []
    if len(vs) == 3:
        (x1, y1), (x2, y2), (x3, y3) = vs
        ax, ay, bx, by = x2 - x1, y2 - y1, x3 - x1, y3 - y1
        det = 2 * (ax * by - ay * bx)
        if det == 0:
            return []
        ra, rb = ax * ax + ay * ay, bx * bx + by * by
        ux = Fraction(by * ra - ay * rb, det)
        uy = Fraction(ax * rb - bx * ra, det)
        return [(x1 + ux, y1 + uy)]
    if len(vs) == 2:
        la, lb, lc, n = es[0]
        on = [la * v[0] + lb * v[1] + lc == 0 for v in vs]
        if on[0] and on[1]:
            return []  # both on the line: their normal lines are parallel
        if on[0]:
            vs = vs[::-1]  # the parabola of a vertex on the line degenerates: use the other vertex
        (x1, y1), (x2, y2) = vs
        nx, ny = x2 - x1, y2 - y1
        h = Fraction(x2 * x2 + y2 * y2 - x1 * x1 - y1 * y1, 2)
        nn = nx * nx + ny * ny
        x0, y0 = nx * h / nn, ny * h / nn
        mx, my = -ny, nx
        return _line_meets_parabola(t, x0, y0, mx, my, (x1, y1), (la, lb, lc, n))
    if len(vs) == 1:
        (vx, vy) = vs[0]
        on = [e[0] * vx + e[1] * vy + e[2] == 0 for e in es]
        if on[0] and on[1]:
            return []  # the normal lines at v of both lines meet at v only (distance 0)
        if on[0] or on[1]:
            # d(x, v) = d(x, line) for v on the line is the normal line at v; meet it with the other parabola.
            na, nb, _, _ = es[0] if on[0] else es[1]
            other = es[1] if on[0] else es[0]
            return _line_meets_parabola(t, vx, vy, na, nb, (vx, vy), other)
        (a1, b1, c1, n1), (a2, b2, c2, n2) = es
        kk = t.sqrt(n1 * n2)
        for sg in (1, -1):
            # The angle bisector N2·ℓ1 = σ·√(N1N2)·ℓ2, i.e. ba·x + bb·y + bc = 0.
            ba: Num = n2 * a1 - sg * kk * a2
            bb: Num = n2 * b1 - sg * kk * b2
            bc: Num = n2 * c1 - sg * kk * c2
            sa, sb = _sign(ba), _sign(bb)
            if sa == 0 and sb == 0:
                continue
            # A point of the bisector: where it meets the x axis, or the y axis when it is horizontal.
            px0, py0 = (_neg(_div(bc, ba)), 0) if sa != 0 else (0, _neg(_div(bc, bb)))
            out.extend(_line_meets_parabola(t, px0, py0, _neg(bb), ba, vs[0], (a1, b1, c1, n1)))
        return out
    (a1, b1, c1, n1), (a2, b2, c2, n2), (a3, b3, c3, n3) = es
    k12, k13 = t.sqrt(n1 * n2), t.sqrt(n1 * n3)
    for s2 in (1, -1):
        for s3 in (1, -1):
            ra = (n2 * a1 - s2 * k12 * a2, n2 * b1 - s2 * k12 * b2, n2 * c1 - s2 * k12 * c2)
            rb = (n3 * a1 - s3 * k13 * a3, n3 * b1 - s3 * k13 * b3, n3 * c1 - s3 * k13 * c3)
            det = ra[0] * rb[1] - rb[0] * ra[1]
            if _sign(det) == 0:
                continue
            x = _div(ra[1] * rb[2] - rb[1] * ra[2], det)
            y = _div(rb[0] * ra[2] - ra[0] * rb[2], det)
            out.append((x, y))
    return out


def _line_meets_parabola(
    t: _Tower | _IVTower,
    x0: Num,
    y0: Num,
    mx: Num,
    my: Num,
    v: tuple[int, int],
    line: tuple[int, int, int, int],
) -> list[tuple[Num, Num]]:
    """Points x0 + s·m with ℓ(x)² = N·|x − v|²."""
    la, lb, lc, n = line
    p0 = la * x0 + lb * y0 + lc
    p1 = la * mx + lb * my
    wx, wy = x0 - v[0], y0 - v[1]
    mm = mx * mx + my * my
    qa = p1 * p1 - n * mm
    qb = 2 * (p0 * p1 - n * (wx * mx + wy * my))
    qc = p0 * p0 - n * (wx * wx + wy * wy)
    roots = _solve_quadratic(t, qa, qb, qc)
    return [(x0 + s * mx, y0 + s * my) for s in roots or ()]
