"""The 3D safety net R(A) = V(A) eroded by ¼: a valid closed mesh with the topology of A, and D(R(A)) = A.

Reference: docs/design.md §11 ("Continuation R in 3D", item 7). D_gauss(R(A)) = A is checked with an exact
point-in-polyhedron test (tests/oracles/polyhedron_reference.py); the topology against the region
representation (itself checked against scipy in test_region_3d.py).
"""

from __future__ import annotations

from collections import Counter, defaultdict
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import SizeLimitError
from mrm.geometry.reconstruct.safety_net_3d import SafetyNet3D, safety_net_3d
from mrm.reps.region_3d import region_3d_of
from tests.model.voxel_shapes import ball, hollow, random_mask, solid_torus
from tests.oracles.polyhedron_reference import gauss, supercover

masks = st.builds(
    random_mask,
    st.integers(0, 2**32 - 1),
    st.tuples(st.integers(1, 5), st.integers(1, 5), st.integers(1, 5)),
    st.sampled_from([0.1, 0.3, 0.5, 0.7, 0.9]),
)


class Shells:
    """The edge-connected triangle sets of a mesh, with the signed volume and Euler characteristic of each."""

    def __init__(self, net: SafetyNet3D) -> None:
        tri = net.triangles
        parent = list(range(len(tri)))

        def find(a: int) -> int:
            while parent[a] != a:
                parent[a] = parent[parent[a]]
                a = parent[a]
            return a

        owner: dict[tuple[int, int], int] = {}
        for t, (a, b, c) in enumerate(tri.tolist()):
            for e in ((a, b), (b, c), (c, a)):
                owner[e] = t
        for (a, b), t in owner.items():
            o = owner[(b, a)]
            parent[find(t)] = find(o)
        roots = [find(t) for t in range(len(tri))]
        self.ids = sorted(set(roots))
        self.shell = np.array([self.ids.index(r) for r in roots], np.int64)
        v = net.vertices[tri]
        # exact: the coordinates are quarter-integers, the products sums of 1/64ths
        six = np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2]))
        self.volume = [Fraction(float(six[self.shell == s].sum())) / 6 for s in range(len(self.ids))]
        self.euler = []
        for s in range(len(self.ids)):
            ts = tri[self.shell == s]
            n_v = len(np.unique(ts))
            n_e = len({tuple(sorted(e)) for a, b, c in ts.tolist() for e in ((a, b), (b, c), (c, a))})
            self.euler.append(n_v - n_e + len(ts))


def check_mesh(net: SafetyNet3D) -> None:
    """Closed, consistently oriented 2-manifold; vertices in Z + {¼, ¾}; faces coplanar and maximal."""
    v, tri = net.vertices, net.triangles
    assert v.dtype == np.float64 and tri.dtype == np.int64
    if tri.size == 0:
        return
    q = 4 * v
    assert np.array_equal(q, np.round(q)) and np.all(np.round(q).astype(np.int64) % 2 == 1)
    assert len(np.unique(v, axis=0)) == len(v)
    assert np.array_equal(np.unique(tri), np.arange(len(v)))  # every vertex used
    # every directed edge once, with its opposite: closed and consistently oriented
    directed = Counter((a, b) for t in tri.tolist() for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])))
    assert max(directed.values()) == 1
    assert all((b, a) in directed for a, b in directed)
    # non-degenerate
    p = v[tri]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    assert np.all(np.abs(normal).sum(axis=1) > 0)
    # each vertex's link is one cycle (no pinched vertex)
    link: dict[int, dict[int, int]] = defaultdict(dict)
    for a, b, c in tri.tolist():
        link[a][b] = c
        link[b][c] = a
        link[c][a] = b
    for nxt in link.values():
        start = next(iter(nxt))
        cur, steps = nxt[start], 1
        while cur != start:
            cur, steps = nxt[cur], steps + 1
        assert steps == len(nxt)
    # faces: coplanar with one normal, and maximal edge-adjacent coplanar sets
    unit = np.sign(normal).astype(np.int64)
    assert np.all(np.abs(unit).sum(axis=1) == 1)  # axis-aligned
    plane = np.einsum("ij,ij->i", unit, p[:, 0])
    owner = {
        e: t for t, tt in enumerate(tri.tolist()) for e in ((tt[0], tt[1]), (tt[1], tt[2]), (tt[2], tt[0]))
    }
    faces = net.face
    for f in range(net.n_faces):
        sel = faces == f
        assert sel.any()
        assert len({tuple(x) for x in unit[sel].tolist()}) == 1 and len(set(plane[sel].tolist())) == 1
    for (a, b), t in owner.items():
        o = owner[(b, a)]
        same_plane = np.array_equal(unit[t], unit[o]) and plane[t] == plane[o]
        assert same_plane == (faces[t] == faces[o])


def check_topology(m: np.ndarray, net: SafetyNet3D, origin: tuple[int, int, int] = (0, 0, 0)) -> None:
    reg = region_3d_of(m, origin)
    shells = Shells(net)
    outer = [s for s, vol in enumerate(shells.volume) if vol > 0]
    inner = [s for s, vol in enumerate(shells.volume) if vol < 0]
    assert len(outer) == reg.n_components and len(inner) == reg.n_cavities
    assert all(e % 2 == 0 for e in shells.euler)
    assert sum((2 - e) // 2 for e in shells.euler) == reg.n_tunnels
    # per component: a shell's vertex v (in Z + {1/4, 3/4}) is a corner of cells that all touch the voxel
    # round(v), so that voxel is in the shell's component; the genera of its shells add up to its tunnels
    if reg.components:
        labels = reg.labels()
        ox, oy, oz = reg.origin
        genus: dict[int, int] = {}
        for sh in range(len(shells.ids)):
            v = net.vertices[net.triangles[shells.shell == sh][0, 0]]
            x, y, z = (int(np.floor(c + 0.5)) for c in v)
            comp = int(labels[z - oz, y - oy, x - ox])
            assert comp > 0
            genus[comp] = genus.get(comp, 0) + (2 - shells.euler[sh]) // 2
        assert genus == {c.label: c.tunnels for c in reg.components}
    # the volume: one eighth per cell of the doubled grid whose voxels are all in A
    a = np.pad(m, 1)
    cells = a.astype(np.int64)
    for axis in range(3):
        n = cells.shape[axis]
        lo = np.take(a, range(n - 1), axis=axis)
        hi = np.take(a, range(1, n), axis=axis)
        a = np.concatenate([a, lo & hi], axis=axis)  # cores then seams: order does not matter for a count
        cells = a
    assert sum(shells.volume) == Fraction(int(cells.sum()), 8)


def check_gauss(m: np.ndarray, origin: tuple[int, int, int], net: SafetyNet3D) -> None:
    nz, ny, nx = m.shape
    x0, y0, z0 = origin
    got = gauss(net.vertices, net.triangles, (x0 - 1, y0 - 1, z0 - 1, x0 + nx, y0 + ny, z0 + nz))
    assert np.array_equal(got, np.pad(m, 1))


# ---------------------------------------------------------------------------------------------- known shapes


def test_empty() -> None:
    net = safety_net_3d(np.zeros((2, 2, 2), bool))
    assert net.vertices.shape == (0, 3) and net.triangles.shape == (0, 3) and net.n_faces == 0


def test_one_voxel_is_a_cube_of_side_one_half() -> None:
    net = safety_net_3d(np.ones((1, 1, 1), bool), (3, -4, 5))
    assert (len(net.vertices), len(net.triangles), net.n_faces) == (8, 12, 6)
    assert {tuple(x) for x in net.vertices.tolist()} == {
        (x, y, z) for x in (2.75, 3.25) for y in (-4.25, -3.75) for z in (4.75, 5.25)
    }
    check_mesh(net)


@pytest.mark.parametrize(
    ("mask", "shells", "genus"),
    [
        (ball(2.5, 7), 1, 0),
        (hollow(7), 2, 0),
        (solid_torus(9, 2.5, 1.2), 1, 1),
        (np.ones((2, 3, 4), bool), 1, 0),
    ],
    ids=["ball", "hollow sphere", "solid torus", "box"],
)
def test_known_shapes(mask: np.ndarray, shells: int, genus: int) -> None:
    net = safety_net_3d(mask, (1, 2, 3))
    check_mesh(net)
    check_topology(mask, net, (1, 2, 3))
    s = Shells(net)
    assert len(s.ids) == shells and sum((2 - e) // 2 for e in s.euler) == genus


def test_a_box_has_six_faces() -> None:
    net = safety_net_3d(np.ones((2, 3, 4), bool))
    assert (net.n_faces, len(net.triangles), len(net.vertices)) == (6, 12, 8)
    check_mesh(net)


def test_an_l_shape_has_no_t_junction() -> None:
    m = np.zeros((2, 1, 2), bool)
    m[0, 0, :] = True
    m[1, 0, 0] = True  # the -y face is an L: its outline's corners are vertices of the faces around it
    net = safety_net_3d(m)
    check_mesh(net)
    assert net.n_faces == 8


@pytest.mark.parametrize("kind", ["edge", "corner"])
def test_edge_and_corner_touching_voxels_give_separate_shells(kind: str) -> None:
    m = np.zeros((2, 2, 2), bool)
    if kind == "edge":
        m[0, 0, :] = m[1, 1, :] = True
    else:
        m[0, 0, 0] = m[1, 1, 1] = True
    net = safety_net_3d(m)
    check_mesh(net)
    check_topology(m, net)
    assert len(Shells(net).ids) == 2
    check_gauss(m, (0, 0, 0), net)


def test_checkerboard_gives_one_cube_per_voxel() -> None:
    z, y, x = np.mgrid[0:3, 0:3, 0:3]
    m = (x + y + z) % 2 == 0
    net = safety_net_3d(m)
    check_mesh(net)
    assert len(Shells(net).ids) == int(m.sum()) and len(net.triangles) == 12 * int(m.sum())


def test_translation_covariance() -> None:
    m = random_mask(7, (4, 3, 5), 0.6)
    a = safety_net_3d(m, (0, 0, 0))
    for t in ((1, -2, 3), (10**6, -(10**6), 7)):
        b = safety_net_3d(np.pad(m, ((1, 0), (0, 2), (3, 0))), (t[0] - 3, t[1], t[2] - 1))
        assert np.array_equal(b.triangles, a.triangles) and np.array_equal(b.face, a.face)
        assert np.array_equal(b.vertices, a.vertices + np.array(t, np.float64))


def test_limit_is_checked_before_the_work() -> None:
    with pytest.raises(SizeLimitError):
        safety_net_3d(np.ones((3, 3, 3), bool), limit=8 * 5**3 - 1)
    safety_net_3d(np.ones((3, 3, 3), bool), limit=8 * 5**3)


# ---------------------------------------------------------------------------------------------- properties


@settings(max_examples=60)
@given(masks)
def test_random_masks_give_valid_meshes_with_the_topology_of_a(m: np.ndarray) -> None:
    net = safety_net_3d(m, (2, -1, 0))
    check_mesh(net)
    check_topology(m, net, (2, -1, 0))


@settings(max_examples=25)
@given(
    st.builds(
        random_mask,
        st.integers(0, 2**32 - 1),
        st.tuples(*[st.integers(1, 3)] * 3),
        st.sampled_from([0.3, 0.5, 0.7]),
    )
)
def test_gauss_discretization_of_the_net_is_a(m: np.ndarray) -> None:
    net = safety_net_3d(m, (-3, 1, 2))
    check_gauss(m, (-3, 1, 2), net)


@settings(max_examples=15)
@given(
    st.builds(
        random_mask,
        st.integers(0, 2**32 - 1),
        st.tuples(*[st.integers(1, 3)] * 3),
        st.sampled_from([0.3, 0.5, 0.7]),
    )
)
def test_supercover_discretization_of_the_net_is_a_hence_all_three_models(m: np.ndarray) -> None:
    # gauss ⊆ open-square ⊆ standard ⊆ supercover (the kernels are nested: p + τ ∈ int V(p) + τ ⊂ V(p)), so
    # gauss = supercover = A gives standard = A too.
    origin = (4, -2, 1)
    net = safety_net_3d(m, origin)
    nz, ny, nx = m.shape
    x0, y0, z0 = origin
    got = supercover(net.vertices, net.triangles, (x0 - 1, y0 - 1, z0 - 1, x0 + nx, y0 + ny, z0 + nz))
    assert np.array_equal(got, np.pad(m, 1))
    check_gauss(m, origin, net)
