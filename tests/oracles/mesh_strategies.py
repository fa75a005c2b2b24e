"""Hypothesis strategies for closed triangle meshes and triangle sets, random and adversarial (design §11).

A mesh is a pair (vertices: float64 (n, 3), triangles: int64 (m, 3)), outward. Coordinates favour the grid:
voxel centres (integers), voxel faces (half-integers), quarter-integers, and free floats; shapes include
axis-aligned boxes (faces along voxel faces or through centres), tetrahedra, slivers thinner than a voxel,
star-shaped (non-convex) subdivided octahedra, a box with a cavity (an inner shell oriented inward) and two
shells. Exactness of every vertex is kept: the only arithmetic is on small dyadic numbers.
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
from hypothesis import strategies as st

Mesh = tuple[np.ndarray, np.ndarray]

#: A grid-friendly coordinate: centres, faces, quarters, a hair off them, or a free float.
coords = st.one_of(
    st.integers(-6, 6).map(float),
    st.integers(-12, 12).map(lambda n: n / 2),
    st.integers(-24, 24).map(lambda n: n / 4),
    # near-ties: a hair (2^-45) off the grid, where the float filters cannot decide and the expansions must
    st.tuples(st.integers(-24, 24), st.integers(-2, 2)).map(lambda p: p[0] / 4 + p[1] * 2.0**-45),
    st.floats(-3.0, 3.0, allow_nan=False, allow_infinity=False).filter(
        lambda u: u == 0.0 or abs(u) > 2.0**-30
    ),
)
points = st.tuples(coords, coords, coords)


def _det(a, b, c, d) -> Fraction:  # type: ignore[no-untyped-def]
    """det[b − a; c − a; d − a] exactly."""
    u = [Fraction(b[i]) - Fraction(a[i]) for i in range(3)]
    v = [Fraction(c[i]) - Fraction(a[i]) for i in range(3)]
    w = [Fraction(d[i]) - Fraction(a[i]) for i in range(3)]
    return (
        u[0] * (v[1] * w[2] - v[2] * w[1])
        - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
    )


def tetra_mesh(a, b, c, d) -> Mesh:  # type: ignore[no-untyped-def]
    """The tetrahedron abcd, outward (b and c swapped when it is negatively oriented)."""
    if _det(a, b, c, d) < 0:
        b, c = c, b
    v = np.array([a, b, c, d], dtype=np.float64)
    t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int64)
    return v, t


@st.composite
def tetras(draw) -> Mesh:  # type: ignore[no-untyped-def]
    pts = draw(st.tuples(points, points, points, points).filter(lambda p: _det(*p) != 0))
    return tetra_mesh(*pts)


@st.composite
def slivers(draw) -> Mesh:  # type: ignore[no-untyped-def]
    """A tetrahedron whose fourth vertex lies a tiny distance off the plane of the other three."""
    a, b, c = draw(st.tuples(points, points, points))
    off = draw(st.sampled_from([2.0**-3, 2.0**-10, 2.0**-30, 1e-9]))
    axis = draw(st.integers(0, 2))
    w = draw(st.floats(0.05, 0.9))
    d = [a[i] * w + b[i] * (1 - w) / 2 + c[i] * (1 - w) / 2 for i in range(3)]
    d[axis] += off
    if _det(a, b, c, d) == 0:
        d[(axis + 1) % 3] += off
    pts = (a, b, c, tuple(d))
    if _det(*pts) == 0:
        return tetra_mesh((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, off))
    return tetra_mesh(*pts)


def box_mesh(lo, hi, inward: bool = False) -> Mesh:  # type: ignore[no-untyped-def]
    """The axis-aligned box [lo, hi] as 12 triangles, outward (or inward, for a cavity)."""
    v = np.array([[(lo, hi)[(n >> d) & 1][d] for d in range(3)] for n in range(8)], dtype=np.float64)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    t = []
    for a, b, c, d in quads:
        t += [[a, b, c], [a, c, d]]
    tri = np.array(t, dtype=np.int64)
    if inward:
        tri = tri[:, ::-1].copy()
    return v, tri


@st.composite
def boxes(draw) -> Mesh:  # type: ignore[no-untyped-def]
    lo, hi = [], []
    for _ in range(3):
        a, b = draw(st.tuples(coords, coords).filter(lambda p: p[0] != p[1]))
        lo.append(min(a, b))
        hi.append(max(a, b))
    return box_mesh(lo, hi)


def _octahedron_directions() -> tuple[list[tuple[float, float, float]], list[tuple[int, int, int]]]:
    """The octahedron with each face split in four: directions from the centre and outward triangles."""
    dirs: list[tuple[float, float, float]] = []
    index: dict[tuple[float, float, float], int] = {}

    def vid(p: tuple[float, float, float]) -> int:
        if p not in index:
            index[p] = len(dirs)
            dirs.append(p)
        return index[p]

    tris = []
    for sx, sy, sz in itertools.product((1.0, -1.0), repeat=3):
        x, y, z = (sx, 0.0, 0.0), (0.0, sy, 0.0), (0.0, 0.0, sz)
        mxy = (sx / 2, sy / 2, 0.0)
        myz = (0.0, sy / 2, sz / 2)
        mzx = (sx / 2, 0.0, sz / 2)
        for a, b, c in ((x, mxy, mzx), (y, myz, mxy), (z, mzx, myz), (mxy, myz, mzx)):
            if _det((0, 0, 0), a, b, c) < 0:
                b, c = c, b
            tris.append((vid(a), vid(b), vid(c)))
    return dirs, tris


_DIRS, _STAR_TRIS = _octahedron_directions()
radii = st.one_of(st.integers(1, 10).map(lambda n: n / 4), st.floats(0.2, 2.5))


def star_mesh(c, r) -> Mesh:  # type: ignore[no-untyped-def]
    """The split octahedron centred at ``c`` with radius r[n] along direction n (star-shaped from c)."""
    v = np.array([[c[d] + ri * di[d] for d in range(3)] for ri, di in zip(r, _DIRS, strict=True)])
    return v, np.array(_STAR_TRIS, dtype=np.int64)


STAR_VERTICES = len(_DIRS)


@st.composite
def stars(draw, max_radius: float = 2.5) -> Mesh:  # type: ignore[no-untyped-def]
    """A star-shaped (generally non-convex) polyhedron: the split octahedron with a radius per vertex."""
    c = draw(points)
    r = draw(st.lists(radii.map(lambda u: min(u, max_radius)), min_size=len(_DIRS), max_size=len(_DIRS)))
    return star_mesh(c, r)


def concat(*meshes: Mesh) -> Mesh:
    """Several meshes as one (shells of one solid, or one triangle set)."""
    vs, ts, n = [], [], 0
    for v, t in meshes:
        vs.append(v)
        ts.append(t + n)
        n += v.shape[0]
    return np.concatenate(vs), np.concatenate(ts)


@st.composite
def cavities(draw) -> Mesh:  # type: ignore[no-untyped-def]
    """A box with a box-shaped cavity (an inner shell oriented inward) strictly inside it."""
    lo, hi, ilo, ihi = [], [], [], []
    for _ in range(3):
        vals = sorted(draw(st.lists(coords, min_size=4, max_size=4, unique=True)))
        lo.append(vals[0])
        ilo.append(vals[1])
        ihi.append(vals[2])
        hi.append(vals[3])
    return concat(box_mesh(lo, hi), box_mesh(ilo, ihi, inward=True))


def translate(mesh: Mesh, t) -> Mesh:  # type: ignore[no-untyped-def]
    v, tri = mesh
    return v + np.asarray(t, dtype=np.float64), tri


@st.composite
def separated_pairs(draw) -> tuple[Mesh, Mesh]:  # type: ignore[no-untyped-def]
    """Two solids with disjoint interiors: the second moved along x beyond the first (touching allowed)."""
    p = draw(st.one_of(tetras(), boxes(), stars(max_radius=1.5)))
    q = draw(st.one_of(tetras(), boxes(), stars(max_radius=1.5)))
    gap = draw(st.sampled_from([0.0, 0.25, 0.5, 1.0]))
    shift = float(p[0][:, 0].max() - q[0][:, 0].min()) + gap
    if shift != float(Fraction(p[0][:, 0].max()) - Fraction(q[0][:, 0].min()) + Fraction(gap)):
        shift = float(np.ceil(shift)) + 1.0  # keep the translation exact and the solids apart
    return p, translate(q, (shift, 0.0, 0.0))


def solids() -> st.SearchStrategy[Mesh]:
    """Any closed solid of the families above (one shell, a cavity, or two shells)."""
    return st.one_of(
        tetras(),
        boxes(),
        slivers(),
        stars(),
        cavities(),
        separated_pairs().map(lambda pq: concat(*pq)),
    )


@st.composite
def triangle_sets(draw, max_size: int = 4) -> Mesh:  # type: ignore[no-untyped-def]
    """A few free triangles, degenerate ones (segments, points) included."""
    n = draw(st.integers(1, max_size))
    tris = []
    for _ in range(n):
        a = draw(points)
        kind = draw(st.sampled_from(["triangle", "triangle", "segment", "point", "axis-edge"]))
        if kind == "triangle":
            b, c = draw(points), draw(points)
        elif kind == "segment":
            b = draw(points)
            c = b
        elif kind == "point":
            b = c = a
        else:  # an edge along a voxel edge or face, the third vertex anywhere
            axis = draw(st.integers(0, 2))
            b = list(a)
            b[axis] = draw(coords)
            b = tuple(b)
            c = draw(points)
        tris.append((a, b, c))
    v = np.array([p for t in tris for p in t], dtype=np.float64)
    return v, np.arange(3 * n, dtype=np.int64).reshape(n, 3)
