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
from mrm.geometry.polyhedra import Polyhedron
from mrm.geometry.reconstruct.safety_net_3d import SafetyNet3D, safety_net_3d
from mrm.reps.region_3d import region_3d_of
from tests.model.voxel_shapes import ball, hollow, random_mask, smoothed_noise, solid_torus
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
    # R takes the net without the search for triangles meeting improperly (its construction proves there are
    # none): the whole exact validation, that search included, accepts it
    Polyhedron(net.vertices, net.triangles)


@settings(max_examples=40, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.integers(8, 28),
    st.sampled_from(["noise 0.3", "noise 0.5", "noise 0.7", "blobs"]),
)
def test_bigger_random_nets_pass_the_whole_validation(seed: int, n: int, kind: str) -> None:
    """R keeps the net above the compact limit without searching it for triangles that meet improperly
    (reconstruct._net_polyhedron): on sets of hundreds to thousands of surfels, with thin parts, cavities
    and edge contacts, that search finds none."""
    m = smoothed_noise(n, seed % 1000) if kind == "blobs" else random_mask(seed, (n, n, n), float(kind[6:]))
    net = safety_net_3d(m, (-3, 5, 1))
    Polyhedron(net.vertices, net.triangles)


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


# ------------------------------------------------------------------------------- the definition, literally


def doubled_cells(m: np.ndarray) -> np.ndarray:
    """The cells of the doubled grid of A padded by one voxel: cell 2p is the core of voxel p, 2p + 1 the
    seam of voxels p and p + 1 (on each axis); a cell is in R(A) when all its voxels are in A."""
    cells = np.pad(m.astype(bool), 1)
    for axis in range(3):
        n = cells.shape[axis]
        shape = list(cells.shape)
        shape[axis] = 2 * n - 1
        out = np.zeros(shape, bool)
        idx: list[slice] = [slice(None)] * 3
        idx[axis] = slice(0, None, 2)
        out[tuple(idx)] = cells
        idx[axis] = slice(1, None, 2)
        out[tuple(idx)] = np.take(cells, range(n - 1), axis) & np.take(cells, range(1, n), axis)
        cells = out
    return cells


def row_runs(bd: np.ndarray, r: int, sign: int) -> list[tuple[int, int]]:
    """The runs [c0, c1) of squares of the sign in row r (none outside the plane)."""
    if not 0 <= r < bd.shape[0]:
        return []
    out, c = [], 0
    while c < bd.shape[1]:
        if bd[r, c] == sign:
            c0 = c
            while c < bd.shape[1] and bd[r, c] == sign:
                c += 1
            out.append((c0, c))
        else:
            c += 1
    return out


def face_labels(bd: np.ndarray, first: int) -> tuple[np.ndarray, int]:
    """4-connected squares of one sign, numbered from ``first`` by their first square in raster order."""
    label = -np.ones(bd.shape, np.int64)
    n = first
    for r, c in np.ndindex(*bd.shape):
        if bd[r, c] and label[r, c] < 0:
            label[r, c] = n
            todo = [(r, c)]
            while todo:
                i, j = todo.pop()
                for i2, j2 in ((i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)):
                    inside = 0 <= i2 < bd.shape[0] and 0 <= j2 < bd.shape[1]
                    if inside and bd[i2, j2] == bd[r, c] and label[i2, j2] < 0:
                        label[i2, j2] = n
                        todo.append((i2, j2))
            n += 1
    return label, n


#: Planes normal to x, y, z: (normal, row, column) axes as (x, y, z) indices, (column, row, normal)
#: right-handed.
LAYOUTS = ((0, 2, 1), (1, 0, 2), (2, 1, 0))


def plane_squares(cells: np.ndarray, axes: tuple[int, int, int], p: int) -> np.ndarray:
    """Plane p normal to axes[0], between cells p − 1 and p: +1 (−1) where the cell below (above) is in
    R(A) and the other not, by (row, column)."""
    c = cells.transpose(2, 1, 0).transpose(axes)  # indexed (normal, row, column)
    below = c[p - 1] if p >= 1 else np.zeros(c.shape[1:], bool)
    above = c[p] if p < c.shape[0] else np.zeros(c.shape[1:], bool)
    return below.astype(np.int64) - above.astype(np.int64)


def reference_net(m: np.ndarray, origin: tuple[int, int, int]) -> SafetyNet3D:
    """The safety net straight from the module's definition, slowly: each plane's boundary squares of the
    doubled grid, its faces, the rectangles and their strips, the required corners grown pass by pass until
    a pass adds none."""
    cells = doubled_cells(m)
    required: set[tuple[int, int, int]] = set()
    while True:
        tris: list[tuple[tuple[int, int, int], ...]] = []
        faces: list[int] = []
        n_faces = 0
        for axes in LAYOUTS:

            def corner(p: int, v: int, u: int, axes: tuple[int, int, int] = axes) -> tuple[int, int, int]:
                xyz = [0, 0, 0]
                xyz[axes[0]], xyz[axes[1]], xyz[axes[2]] = p, v, u
                return (xyz[0], xyz[1], xyz[2])

            for p in range(cells.shape[2 - axes[0]] + 1):
                bd = plane_squares(cells, axes, p)
                label, n_faces = face_labels(bd, n_faces)
                for sign in (1, -1):
                    covered: set[tuple[int, int]] = set()
                    for r in range(bd.shape[0]):
                        for c0, c1 in row_runs(bd, r, sign):
                            if (r, c0) in covered:
                                continue
                            r1 = r + 1  # the rectangle's top row line
                            while (
                                r1 < bd.shape[0]
                                and corner(p, r1, c0) not in required
                                and corner(p, r1, c1) not in required
                                and (c0, c1) in row_runs(bd, r1, sign)
                            ):
                                covered.add((r1, c0))
                                r1 += 1
                            # on each side: its corners, required corners, the ends of the row beyond's runs
                            bot, top = (
                                [
                                    u
                                    for u in range(c0, c1 + 1)
                                    if u in (c0, c1)
                                    or corner(p, line, u) in required
                                    or any(u in run for run in row_runs(bd, beyond, sign))
                                ]
                                for line, beyond in ((r, r - 1), (r1, r1))
                            )
                            i = j = 0
                            while i < len(bot) - 1 or j < len(top) - 1:
                                if j == len(top) - 1 or (i < len(bot) - 1 and bot[i + 1] <= top[j + 1]):
                                    t = [(r, bot[i]), (r, bot[i + 1]), (r1, top[j])]
                                    i += 1
                                else:
                                    t = [(r, bot[i]), (r1, top[j + 1]), (r1, top[j])]
                                    j += 1
                                if sign < 0:
                                    t[1], t[2] = t[2], t[1]
                                tris.append(tuple(corner(p, v, u) for v, u in t))
                                faces.append(int(label[r, c0]))
        used = {q for t in tris for q in t}
        if used <= required:
            break
        required |= used
    order = sorted(used, key=lambda q: (q[2], q[1], q[0]))
    number = {q: i for i, q in enumerate(order)}
    # corner m of an axis lies at (origin − 1) + (2m − 1)/4
    base = np.array(origin, np.float64) - 1
    vertices = base + (2 * np.array(order, np.int64).reshape(-1, 3) - 1).astype(np.float64) / 4.0
    triangles = np.array([[number[q] for q in t] for t in tris], np.int64).reshape(-1, 3)
    return SafetyNet3D(vertices, triangles, np.array(faces, np.int64), n_faces)


@settings(max_examples=100, deadline=None)
@given(
    st.builds(
        random_mask,
        st.integers(0, 2**32 - 1),
        st.tuples(*[st.integers(1, 5)] * 3),
        st.sampled_from([0.2, 0.5, 0.8]),
    ),
    st.tuples(*[st.integers(-3, 3)] * 3),
)
def test_the_net_is_its_definition(m: np.ndarray, origin: tuple[int, int, int]) -> None:
    # The fast net (runs, stacks, a bitmap of corners) is the literal definition, to the order of vertices,
    # triangles and faces.
    net = safety_net_3d(m, origin)
    ref = reference_net(m, origin)
    if not m.any():
        assert len(net.triangles) == 0 and net.n_faces == 0
        return
    assert np.array_equal(net.vertices, ref.vertices)
    assert np.array_equal(net.triangles, ref.triangles)
    assert np.array_equal(net.face, ref.face) and net.n_faces == ref.n_faces
