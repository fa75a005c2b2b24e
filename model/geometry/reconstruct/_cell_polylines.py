"""The polyline of one 1-cell of a label map under ``gauss``: its corridor, its conditions, how it is chosen.

:mod:`.subdivision` reconstructs every 1-cell c of a label map once, as an open polyline γ_c between its two
0-cells or as a ring when it meets no 0-cell, and assembles the parts from these polylines. This module
builds one polyline (:func:`_polyline`) and checks it exactly (:func:`_verify_chain`); what that check
guarantees (Lemmas 1–3 below) is what the theorem of :mod:`.subdivision` builds on. The per-chain
construction is a notion of its own, and the compiled kernel that follows it step for step
(:mod:`._subdivision_kernels`) refers to it function by function.

The corridor and the conditions
-------------------------------
Write the chain of c as pointels v_0 … v_n (linel k joins v_{k−1} to v_k) and let

* the **piece** of v_k be the open unit square centred on v_k, whose corners are the four pixel centres
  around v_k (the *dual square* of v_k);
* the **gate** g_k be the open segment joining the two pixel centres on either side of linel k, the one
  with the left label and the one with the right label (the *rung* of the linel): it is the common side of
  the pieces of v_{k−1} and v_k.

The dual squares of distinct pointels are disjoint, and every pointel other than a 0-cell lies on exactly
one 1-cell. So the corridors of distinct 1-cells — the pieces of their interior pointels, the open gates, and,
at a 0-cell s, the open triangle between s and the gate of the linel leaving s (one quarter of the dual
square of s per linel) — are pairwise disjoint, and none holds a pixel centre: centres are corners of pieces
and end points of gates, never inside them.

**Conditions** (checked exactly for every polyline, :func:`_verify_chain`): every vertex lies strictly inside
a piece (the two end points are the 0-cells, the centres of the pieces of v_0 and v_n), the pieces of
consecutive vertices are strictly increasing along the chain (cyclically once around for a ring), and each
edge A→B from piece i to piece j crosses the open gates g_{i+1} … g_j: for each gate, with ℓ and r its left
and right centres, cross(r − A, ℓ − A) > 0 (the gate faces A) and cross(B − A, ℓ − A) > 0 >
cross(B − A, r − A) (the ray A→B passes strictly between its ends).

**Lemma 1 (an edge stays in its corridor).** Under these conditions the edge A→B lies in the open pieces
i … j and the open gates between them, and meets them in that order. *Proof.* The ray from A starts inside
the convex piece i and leaves it once; it meets g_{i+1}, a side of piece i, so it leaves there (a ray from
an inside point meets the boundary of a convex set once). Beyond g_{i+1} it is inside piece i+1 and leaves
it once; g_{i+2} is another side of piece i+1 (open sides are disjoint) that the ray meets, so it leaves
there; and so on up to piece j. B lies strictly inside piece j and on the ray, and the ray's part inside
the open piece j is one open interval that starts on g_j, so B comes after every crossing. □

**Lemma 2 (simple, and disjoint from the others).** Each polyline is simple, and two polylines meet only at
common 0-cells. *Proof.* Edges whose piece ranges share no piece lie in disjoint open sets (Lemma 1; pieces
of distinct pointels and distinct gates are disjoint). Consecutive edges share only the piece of their
common vertex, where one runs from a gate to the vertex and the other from the vertex to a different gate
of that convex piece, so they meet only at the vertex. Non-consecutive edges have disjoint piece ranges
because each piece holds at most one vertex. The corridors of distinct 1-cells are disjoint except for the
0-cells, where only end points lie. □

**Lemma 3 (every pixel centre keeps its side).** γ_c is homotopic to the crack chain of c, with the end
points fixed, in the plane minus Z² (minus all pixel centres). *Proof.* Each piece P minus its corners is
star-shaped about any interior point, hence contractible, and contains no pixel centre. Let the crack cross
gate k at its midpoint m_k and γ_c at q_k (both in the open gate). Inside piece k both the crack's stretch
from m_k to m_{k+1} and the path m_k → q_k (along g_k) · γ_c's stretch · q_{k+1} → m_{k+1} (along
g_{k+1}) join the same points in piece k minus its corners (the crack runs along linels, which meet pieces
only inside them or on open gates), so they are homotopic there; the detours along the gates cancel in the
concatenation. At a 0-cell end the quarter triangle minus its two centre corners is contractible as well. □

The crack chain itself satisfies the conditions (vertices at its turning pointels, the centres of their
pieces; each edge runs along linels through their gates' midpoints), which makes it the local safety net.

How the polylines are chosen (a "V4" on the dual grid)
------------------------------------------------------
Shifted by (½, ½), the pointels become pixel centres and the pieces their open squares: γ_c must cross
a 4-connected path of squares through their open shared sides, from the centre of the first to the centre
of the last. For every window of pointels that is a standard digital straight segment (a, b, μ, ω) (the
reach table of :func:`mrm.geometry.dss.segmentation.standard_dss_reach_table`), the left centres of its linels
have a·x − b·y ≤ μ + ω/2 − 1 and the right ones ≥ μ + ω/2 (pointel coordinates), so every line in the open
strip between (around the median line a·x − b·y = μ + (ω − 1)/2) separates them: it crosses every gate of the
window. From the current vertex A (a 0-cell to begin with) the cone of directions through the following
gates is narrowed gate by gate (exact); the next vertex is put on the median line of the window with the
largest reach that still meets that cone inside one of the pieces, at the middle of the admissible stretch,
then snapped to the coarsest dyadic grid that keeps it admissible and in its strip; the last edge goes to the
end 0-cell as soon as the cone allows. A pass then drops every vertex whose neighbours see each other.
Every polyline is verified exactly (:func:`_verify_chain`) and replaced by the crack staircase of its 1-cell
when it fails or has no fewer vertices — a local fallback, never a global one.

The Python functions below are the definition of the construction. The polylines of all 1-cells are built by
one compiled kernel that follows them step for step on int64 with every product checked
(:mod:`mrm.geometry.reconstruct._subdivision_kernels`, docs/adr/0024): a chain whose numbers would leave the
checked range is built by the Python functions on Python integers, so the result is the same either way.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from mrm.core.errors import ParameterError
from mrm.geometry.dss.segmentation import standard_dss_reach_table

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

#: Doubled pointel coordinates ("Q"): pointel (i, j) is at (2i, 2j), the centre of pixel (x, y) at
#: (2x + 1, 2y + 1), and a Euclidean point (X, Y) at (2X + 1, 2Y + 1).
#: A dyadic point of Q coordinates (x / 2^e, y / 2^e), as (x, y, e) with the smallest e.
Vertex = tuple[int, int, int]

_MAX_SNAP_BITS = 60
_CANDIDATE_BUDGET = 400  # median lines tried per vertex before settling for a free vertex


def _cross(ax: int, ay: int, bx: int, by: int) -> int:
    return ax * by - ay * bx


def _vertex(x: int, y: int, e: int) -> Vertex:
    """(x / 2^e, y / 2^e) with the smallest e."""
    while e > 0 and not (x & 1) and not (y & 1):
        x, y, e = x >> 1, y >> 1, e - 1
    return x, y, e


class _Chain:
    """The corridor of one 1-cell: pointels, gates and the DSS reach of its windows.

    Coordinates are Q coordinates relative to the first pointel (``origin``), so numbers stay small.
    """

    __slots__ = ("closed", "gl", "gr", "index", "n", "origin", "params", "pts", "reach", "turns")

    def __init__(self, pts: IntArray, closed: bool) -> None:
        self.closed = closed
        self.n = int(pts.shape[0]) - 1
        self.origin = (int(pts[0, 0]), int(pts[0, 1]))
        loc = pts - pts[0]
        self.pts: list[tuple[int, int]] = list(map(tuple, loc.tolist()))
        # the turning pointels: where the linel before differs from the linel after (cyclically on a ring)
        d = np.diff(loc, axis=0)
        if closed:
            turn = np.flatnonzero(np.any(d != np.roll(d, 1, axis=0), axis=1))
        else:
            turn = np.flatnonzero(np.any(d[1:] != d[:-1], axis=1)) + 1
        self.turns: list[int] = turn.tolist()

    def build(self) -> None:
        """Compute the gates, the piece index and the DSS reach table (only the chains that need them).

        Most 1-cells of a big label map are one or two linels or straight, and :func:`_polyline` returns
        their staircase without a corridor; building it for them cost more than everything else.
        """
        if hasattr(self, "reach"):
            return
        loc = np.asarray(self.pts, dtype=np.int64)
        d = np.diff(loc, axis=0)
        mid = 2 * loc[:-1] + d
        nrm = np.stack([-d[:, 1], d[:, 0]], axis=1)
        # gate k (1 … n) is row k − 1: the left and right pixel centres of linel k
        self.gl: list[tuple[int, int]] = list(map(tuple, (mid + nrm).tolist()))
        self.gr: list[tuple[int, int]] = list(map(tuple, (mid - nrm).tolist()))
        # pointel -> position; the end points of an open chain are 0-cells, not pieces of this chain
        inner = range(self.n) if self.closed else range(1, self.n)
        self.index = {self.pts[k]: k for k in inner}
        if self.n >= 2:
            reach, params = standard_dss_reach_table(loc, closed=False)
            self.reach: list[int] = reach.tolist()
            self.params: list[list[int]] = params.tolist()
        else:
            self.reach, self.params = [self.n] * (self.n + 1), [[0, 1, 0, 1]] * (self.n + 1)

    def q(self, k: int) -> Vertex:
        """Pointel k as a vertex."""
        x, y = self.pts[k]
        return 2 * x, 2 * y, 0

    def gate(self, k: int) -> tuple[tuple[int, int], tuple[int, int]]:
        """Left and right centres of gate k (1 … n; taken cyclically on a ring)."""
        i = (k - 1) % self.n
        return self.gl[i], self.gr[i]

    def edge_ok(self, a: Vertex, ia: int, b: Vertex, ib: int) -> bool:
        """Whether the segment a→b crosses the open gates ia+1 … ib, exactly (module docstring)."""
        e = max(a[2], b[2])
        ax, ay = a[0] << (e - a[2]), a[1] << (e - a[2])
        dx, dy = (b[0] << (e - b[2])) - ax, (b[1] << (e - b[2])) - ay
        for k in range(ia + 1, ib + 1):
            (lx, ly), (rx, ry) = self.gate(k)
            lx_, ly_, rx_, ry_ = (lx << e) - ax, (ly << e) - ay, (rx << e) - ax, (ry << e) - ay
            if rx_ * ly_ - ry_ * lx_ <= 0 or dx * ly_ - dy * lx_ <= 0 or dx * ry_ - dy * rx_ >= 0:
                return False
        return True

    def in_piece(self, v: Vertex, k: int) -> bool:
        """Whether v lies strictly inside the piece (dual square) of pointel k."""
        cx, cy = self.pts[k % self.n] if self.closed else self.pts[k]
        e = v[2]
        return abs(v[0] - (cx << (e + 1))) < (1 << e) and abs(v[1] - (cy << (e + 1))) < (1 << e)

    def staircase(self) -> list[tuple[Vertex, int]]:
        """The crack chain itself: its end points and turning pointels, with their positions."""
        ks = self.turns if self.closed else [0, *self.turns, self.n]
        return [(self.q(k), k) for k in ks]


class _Cone:
    """The open cone of directions strictly between ``lo`` (clockwise bound) and ``hi`` (< π apart)."""

    __slots__ = ("hi", "lo")

    def __init__(self, lo: tuple[int, int], hi: tuple[int, int]) -> None:
        self.lo = lo
        self.hi = hi

    def holds(self, dx: int, dy: int) -> bool:
        return _cross(self.lo[0], self.lo[1], dx, dy) > 0 and _cross(dx, dy, self.hi[0], self.hi[1]) > 0


def _cones(ch: _Chain, p: Vertex, ip: int, last: int) -> list[_Cone]:
    """cones[j]: the directions from p through gates ip+1 … ip+1+j (stops at the first empty one)."""
    px, py, e = p
    out: list[_Cone] = []
    lox = loy = hix = hiy = 0
    for k in range(ip + 1, last + 1):
        (lx, ly), (rx, ry) = ch.gate(k)
        lx_, ly_, rx_, ry_ = (lx << e) - px, (ly << e) - py, (rx << e) - px, (ry << e) - py
        if rx_ * ly_ - ry_ * lx_ <= 0:
            break  # the gate does not face p
        if not out:
            lox, loy, hix, hiy = rx_, ry_, lx_, ly_
        else:
            nlx, nly = (rx_, ry_) if lox * ry_ - loy * rx_ > 0 else (lox, loy)
            nhx, nhy = (lx_, ly_) if lx_ * hiy - ly_ * hix > 0 else (hix, hiy)
            if nlx * nhy - nly * nhx <= 0:
                break
            # a direction strictly inside both the old cone and this gate's wedge, or the cone is empty
            mx, my = nlx + nhx, nly + nhy
            if not (
                lox * my - loy * mx > 0
                and mx * hiy - my * hix > 0
                and rx_ * my - ry_ * mx > 0
                and mx * ly_ - my * lx_ > 0
            ):
                break
            lox, loy, hix, hiy = nlx, nly, nhx, nhy
        out.append(_Cone((lox, loy), (hix, hiy)))
    return out


Bound = tuple[int, int] | None


def _bound(lo: Bound, hi: Bound, num: int, den: int) -> tuple[Bound, Bound]:
    """Add the constraint s > num/den (den > 0) or s < num/den (den < 0) to the interval (lo, hi)."""
    if den > 0:
        if lo is None or num * lo[1] > lo[0] * den:
            lo = (num, den)
    else:
        num, den = -num, -den
        if hi is None or num * hi[1] < hi[0] * den:
            hi = (num, den)
    return lo, hi


def _on_line(
    a: int, b: int, c: int, constraints: Sequence[tuple[int, int, int]]
) -> tuple[int, int, int] | None:
    """The middle of the open stretch of the line a·X − b·Y = c where every αx·X + αy·Y + α0 > 0.

    Exact integer arithmetic: a point of the line is located by s = b·X + a·Y, which grows along the
    direction (b, a); each constraint bounds s on one side. Returns the point as (X·D, Y·D, D), D > 0.
    """
    lo: tuple[int, int] | None = None
    hi: tuple[int, int] | None = None
    n2 = a * a + b * b
    for ax, ay, a0 in constraints:
        g = ax * b + ay * a  # the constraint's rate along (b, a)
        if g == 0:
            # parallel to the line: constant on it, f = λ·c + α0 with (αx, αy) = λ·(a, −b)
            f = (ax * c + a0 * a) * a if a != 0 else (-ay * c + a0 * b) * b  # sign of f times a² or b²
            if f <= 0:
                return None
            continue
        lo, hi = _bound(lo, hi, c * (b * ay - a * ax) - a0 * n2, g)
    if lo is None or hi is None or lo[0] * hi[1] >= hi[0] * lo[1]:
        return None
    sn, sd = lo[0] * hi[1] + hi[0] * lo[1], 2 * lo[1] * hi[1]  # the midpoint s = sn / sd
    d = sd * n2
    return a * c * sd + b * sn, a * sn - b * c * sd, d


def _square(ch: _Chain, q: int, e: int) -> list[tuple[int, int, int]]:
    """The open piece of pointel q as four constraints αx·X + αy·Y + α0 > 0 (coordinates scaled by 2^e)."""
    cx, cy = ch.pts[q]
    vx, vy, h = cx << (e + 1), cy << (e + 1), 1 << e
    return [(1, 0, h - vx), (-1, 0, vx + h), (0, 1, h - vy), (0, -1, vy + h)]


def _in_cone(p: Vertex, cone: _Cone) -> list[tuple[int, int, int]]:
    """cross(lo, X − p) > 0 and cross(X − p, hi) > 0 as constraints on X (scaled by 2^e)."""
    px, py, _ = p
    (lx, ly), (hx, hy) = cone.lo, cone.hi
    return [(-ly, lx, ly * px - lx * py), (hy, -hx, py * hx - px * hy)]


def _on_median(ch: _Chain, i2: int, q: int, p: Vertex, cone: _Cone) -> tuple[int, int, int] | None:
    """The middle of the stretch of window i2's median line inside piece q and inside the cone, if any.

    A rational point (X·D, Y·D, D) of coordinates scaled by 2^e, e the scale of p.
    """
    a, b, mu, om = ch.params[i2]
    if a == 0 and b == 0:
        return None
    e = p[2]
    return _on_line(a, b, (2 * mu + om - 1) << e, _square(ch, q, e) + _in_cone(p, cone))


def _free_vertex(ch: _Chain, p: Vertex, q: int, cone: _Cone) -> tuple[int, int, int]:
    """A point of piece q on the cone's central ray from p (the ray crosses the gates up to q first)."""
    dx, dy = cone.lo[0] + cone.hi[0], cone.lo[1] + cone.hi[1]
    px, py, e = p
    # the line through p along d: a·X − b·Y = c with (b, a) = d
    a, b = dy, dx
    pt = _on_line(a, b, a * px - b * py, _square(ch, q, e))
    if pt is None:  # cannot happen: the ray crosses gate q, a side of the piece, into it
        raise AssertionError("the central ray misses its piece")
    return pt


def _snapped(
    ch: _Chain, x: tuple[int, int, int], q: int, p: Vertex, cone: _Cone, strip: tuple[int, int, int] | None
) -> Vertex | None:
    """Move x to the coarsest dyadic grid on which it stays in piece q, in the cone (and in its strip).

    x = (X·D, Y·D, D) is a rational point of coordinates scaled by 2^e like p. Rounding is floor(v·2^k + ½),
    which commutes with integer translations (unlike round-half-even).
    """
    px, py, e = p
    xn, yn, d = x
    den = 2 * d << e
    for k in range(_MAX_SNAP_BITS + 1):
        s = 1 << k
        yx, yy = (2 * xn * s + (d << e)) // den, (2 * yn * s + (d << e)) // den
        y = (yx, yy, k)
        if not ch.in_piece(y, q):
            continue
        m = max(k, e)
        if not cone.holds((yx << (m - k)) - (px << (m - e)), (yy << (m - k)) - (py << (m - e))):
            continue
        if strip is not None:
            a, b, c = strip
            if abs(a * yx - b * yy - c * s) >= s:
                continue
        return _vertex(yx, yy, k)
    return None


def _greedy(ch: _Chain) -> list[tuple[Vertex, int]] | None:
    """The polyline from v_0 to v_n (module docstring), as (vertex, piece) pairs; None if it gets stuck."""
    n = ch.n
    end = ch.q(n)
    p, ip = ch.q(0), 0
    out: list[tuple[Vertex, int]] = [(p, 0)]
    while True:
        cones = _cones(ch, p, ip, n)
        if not cones:
            return None
        far = ip + len(cones)  # the farthest gate p sees
        e = p[2]
        if far >= n and cones[n - ip - 1].holds((end[0] << e) - p[0], (end[1] << e) - p[1]):
            out.append((end, n))
            return out
        best: tuple[tuple[int, int, int], int, tuple[int, int, int]] | None = None
        budget = _CANDIDATE_BUDGET
        top = min(far, n - 1)
        for i2 in range(top, -1, -1):
            if ch.reach[i2] <= ip + 1 or budget <= 0:
                break
            for q in range(max(i2, ip + 1), min(top, ch.reach[i2]) + 1):
                budget -= 1
                x = _on_median(ch, i2, q, p, cones[q - ip - 1])
                if x is not None:
                    a, b, mu, om = ch.params[i2]
                    best = (x, q, (a, b, 2 * mu + om - 1))
                    break
            if best is not None:
                break
        y: Vertex | None = None
        if best is not None:
            x, q, strip = best
            y = _snapped(ch, x, q, p, cones[q - ip - 1], strip)
        if y is None:
            q = top
            if q < ip + 1:
                return None
            cone = cones[q - ip - 1]
            y = _snapped(ch, _free_vertex(ch, p, q, cone), q, p, cone, None)
            if y is None:
                return None
        out.append((y, q))
        p, ip = y, q


def _merge(ch: _Chain, verts: list[tuple[Vertex, int]]) -> list[tuple[Vertex, int]]:
    """Drop every inner vertex whose neighbours are joined by an admissible edge (one pass)."""
    out = [verts[0]]
    for k in range(1, len(verts) - 1):
        a, ia = out[-1]
        b, ib = verts[k + 1]
        if not ch.edge_ok(a, ia, b, ib):
            out.append(verts[k])
    out.append(verts[-1])
    return out


def _polyline(ch: _Chain) -> tuple[list[Vertex], bool]:
    """γ_c for one chain: vertices (open: v_0 … v_n; ring: no repeat) and whether it is the staircase."""
    stair = [v for v, _ in ch.staircase()]
    if ch.n <= 2 or len(stair) <= 2:  # nothing to gain: one or two linels, or a straight chain
        return stair, True
    ch.build()
    verts = _greedy(ch)
    if verts is None:
        return stair, True
    verts = _merge(ch, verts)
    if ch.closed:
        ring = verts[:-1]
        # the start pointel was only an anchor: drop it when its neighbours see each other round the ring
        if len(ring) > 3:
            a, ia = ring[-1]
            b, ib = ring[1]
            if ch.edge_ok(a, ia, b, ib + ch.n):
                ring = ring[1:]
        verts = ring
    pts = [v for v, _ in verts]
    if len(pts) >= len(stair) or not _verify_chain(ch, pts):
        return stair, True
    return pts, False


def _locate(ch: _Chain, v: Vertex) -> int | None:
    """The position k of the pointel whose open piece holds v, among the chain's own pieces."""
    x, y, e = v
    # v is in the piece of pointel (i, j) iff 2i − 1 < v < 2i + 1 (Q coordinates)
    half, unit = 1 << e, 1 << (e + 1)
    if (x + half) % unit == 0 or (y + half) % unit == 0:
        return None  # on the side of a piece
    return ch.index.get(((x + half) // unit, (y + half) // unit))


def _verify_chain(ch: _Chain, verts: Sequence[Vertex]) -> bool:
    """Check exactly the conditions of the module docstring for a polyline of a chain.

    Independently of how it was built: vertices strictly inside the chain's own pieces, in order, and edges
    through the gates.
    """
    n = ch.n
    seq: list[tuple[Vertex, int]]
    if ch.closed:
        if len(verts) < 3:
            return False
        pos = [_locate(ch, v) for v in verts]
        idx = [k for k in pos if k is not None]
        if len(idx) != len(verts):
            return False
        drops = [t for t in range(len(idx)) if idx[t] <= idx[t - 1]]
        if len(drops) != 1:
            return False
        s = drops[0]
        idx = idx[s:] + [k + n for k in idx[:s]]
        vs = list(verts[s:]) + list(verts[:s])
        if idx[-1] >= idx[0] + n:
            return False
        seq = [*zip(vs, idx, strict=True), (vs[0], idx[0] + n)]
    else:
        if len(verts) < 2 or verts[0] != ch.q(0) or verts[-1] != ch.q(n):
            return False
        inner = [_locate(ch, v) for v in verts[1:-1]]
        mid = [k for k in inner if k is not None]
        if len(mid) != len(inner):
            return False
        idx = [0, *mid, n]
        if any(idx[t] >= idx[t + 1] for t in range(len(idx) - 1)):
            return False
        seq = list(zip(verts, idx, strict=True))
    return all(ch.edge_ok(a, ia, b, ib) for (a, ia), (b, ib) in itertools.pairwise(seq))


def _to_plane(ch: _Chain, verts: Sequence[Vertex]) -> FloatArray:
    """Vertices of a chain to float64 plane coordinates, exactly: X = (Q − 1) / 2."""
    ox, oy = ch.origin
    out = np.empty((len(verts), 2), dtype=np.float64)
    for k, (x, y, e) in enumerate(verts):
        nx, ny = x + ((2 * ox - 1) << e), y + ((2 * oy - 1) << e)
        if max(abs(nx), abs(ny)) >= 1 << 53:
            # far from the origin a fine dyadic vertex has no exact float64 value: refuse, never round
            raise ParameterError(
                f"the label map lies too far from the origin for an exact subdivision in float64: a vertex "
                f"near ({float(nx) / (1 << (e + 1)):.6g}, {float(ny) / (1 << (e + 1)):.6g}) needs {e + 1} "
                f"fractional bits; move the label map closer to the origin"
            )
        out[k, 0], out[k, 1] = nx / (1 << (e + 1)), ny / (1 << (e + 1))
    return out
