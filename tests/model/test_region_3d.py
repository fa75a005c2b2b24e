"""Region representation of voxel sets: components, cavities, Euler characteristic, tunnels, surfaces.

Reference: docs/design.md §11. Checked against ``scipy.ndimage.label`` and an Euler characteristic counted on
the cubical complex (tests/oracles/region_3d_reference.py).
"""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest
import scipy.ndimage as ndi
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import SizeLimitError
from mrm.geometry.topology.labeling_3d import euler_3d, label_3d, label_runs_3d, paint_background_3d
from mrm.geometry.topology.surfels import DIRS, edge_sides
from mrm.reps.region_3d import Region3D, region_3d_of
from tests.model.voxel_shapes import ball, hollow, random_mask, solid_torus
from tests.oracles import region_3d_reference as ref

# ---------------------------------------------------------------------------------------------- helpers

masks = st.builds(
    random_mask,
    st.integers(0, 2**32 - 1),
    st.tuples(st.integers(1, 7), st.integers(1, 7), st.integers(1, 7)),
    st.sampled_from([0.05, 0.2, 0.4, 0.5, 0.6, 0.8, 0.95]),
)


def _box_of(sel: np.ndarray) -> tuple[int, ...]:
    k, j, i = np.nonzero(sel)
    return (3 + i.min(), -5 + j.min(), 7 + k.min(), 3 + i.max(), -5 + j.max(), 7 + k.max())


def check_against_reference(m: np.ndarray) -> Region3D:
    reg = region_3d_of(m, (3, -5, 7))
    lab, n = ref.components(m)
    cav, nc = ref.cavities(m)
    assert reg.n_components == n
    assert reg.n_cavities == nc
    assert reg.euler == ref.euler(m) == euler_3d(m)
    assert reg.n_tunnels == reg.n_components + reg.n_cavities - reg.euler
    assert reg.voxels == int(m.sum())
    if n == 0:
        return reg
    # labels in canonical (z, y, x) raster order: scipy numbers components the same way
    nz_k, nz_j, nz_i = (np.flatnonzero(m.any(axis=a)) for a in ((1, 2), (0, 2), (0, 1)))
    crop = (slice(nz_k[0], nz_k[-1] + 1), slice(nz_j[0], nz_j[-1] + 1), slice(nz_i[0], nz_i[-1] + 1))
    assert np.array_equal(reg.labels(), lab[crop])
    assert np.array_equal(reg.mask(), m[crop])
    assert reg.origin == (3 + int(nz_i[0]), -5 + int(nz_j[0]), 7 + int(nz_k[0]))
    for c in reg.components:
        assert c.voxels == int((lab == c.label).sum())
        assert c.bbox == _box_of(lab == c.label)
        assert c.euler == ref.euler(lab == c.label)
        assert c.tunnels >= 0
        # its cavities: each is a cavity of A lying in a bounded complement component of the component
        # alone (so enclosed by it), and 6-adjacent to it (not nested deeper)
        alone, _ = ref.cavities(lab == c.label)
        grown = ndi.binary_dilation(lab == c.label, ref.S6)
        for cv in c.cavities:
            ids = [
                b
                for b in range(1, nc + 1)
                if _box_of(cav == b) == cv.bbox and int((cav == b).sum()) == cv.voxels
            ]
            assert any(np.all(alone[cav == b] > 0) and np.any(grown & (cav == b)) for b in ids), cv
    assert sum(cv.voxels for c in reg.components for cv in c.cavities) == int((cav > 0).sum())
    return reg


# ---------------------------------------------------------------------------------------------- known shapes


def test_empty() -> None:
    reg = region_3d_of(np.zeros((3, 4, 5), bool), (1, 2, 3))
    assert reg.components == () and reg.euler == 0 and reg.surfaces == () and reg.origin == (0, 0, 0)
    assert reg.mask().shape == (0, 0, 0)


@pytest.mark.parametrize(
    ("mask", "comps", "cavs", "tunnels"),
    [
        (ball(4.0, 11), 1, 0, 0),
        (hollow(), 1, 1, 0),
        (solid_torus(), 1, 0, 1),
        (np.ones((1, 1, 1), bool), 1, 0, 0),
    ],
    ids=["ball", "hollow sphere", "solid torus", "one voxel"],
)
def test_known_shapes(mask: np.ndarray, comps: int, cavs: int, tunnels: int) -> None:
    reg = check_against_reference(mask)
    assert (reg.n_components, reg.n_cavities, reg.n_tunnels) == (comps, cavs, tunnels)
    assert reg.euler == comps - tunnels + cavs


def test_a_frame_has_three_tunnels_and_a_pretzel_two() -> None:
    frame = np.ones((5, 5, 5), bool)
    frame[1:4, 1:4, :] = False  # tunnel along x
    frame[1:4, :, 1:4] = False  # along y
    frame[:, 1:4, 1:4] = False  # along z: the 12 edges of a cube
    reg = check_against_reference(frame)
    assert (reg.n_components, reg.n_cavities, reg.n_tunnels, reg.euler) == (1, 0, 5, -4)
    pretzel = np.ones((3, 3, 5), bool)
    pretzel[:, 1, 1] = pretzel[:, 1, 3] = False
    reg = check_against_reference(pretzel)
    assert (reg.n_tunnels, reg.euler) == (2, -1)


def test_nested_island_in_a_cavity() -> None:
    m = hollow(11)
    m[5, 5, 5] = True  # an island in the cavity
    reg = check_against_reference(m)
    assert reg.n_components == 2 and reg.n_cavities == 1
    outer, island = reg.components
    assert len(outer.cavities) == 1 and island.cavities == ()
    assert island.voxels == 1 and island.bbox == (3 + 5, -5 + 5, 7 + 5) * 2
    assert [(s.component, s.cavity) for s in reg.surfaces] == [(1, -1), (1, 0), (2, -1)]


def test_cavities_go_to_their_own_components() -> None:
    m = np.zeros((5, 5, 12), bool)
    m[:, :, :3] = True  # a solid block, first in raster order (z, y, x): no cavity
    m[1:4, 1:4, 4:7] = True
    m[2, 2, 5] = False  # a hollow cube, third (it starts at z = 1)
    m[:, :, 8:] = True
    m[1:4, 1:3, 9:11] = False  # a block with a bigger cavity, second
    reg = check_against_reference(m)
    assert [len(c.cavities) for c in reg.components] == [0, 1, 1]
    assert [c.cavities[0].voxels for c in reg.components[1:]] == [12, 1]
    assert [(s.component, s.cavity) for s in reg.surfaces] == [(1, -1), (2, -1), (2, 0), (3, -1), (3, 0)]
    check_surfaces(m)


def test_edge_and_corner_touching_cubes_are_apart() -> None:
    edge = np.zeros((2, 2, 2), bool)
    edge[0, 0, :] = edge[1, 1, :] = True  # two rods meeting along an edge
    corner = np.zeros((2, 2, 2), bool)
    corner[0, 0, 0] = corner[1, 1, 1] = True
    for m in (edge, corner):
        reg = check_against_reference(m)
        assert reg.n_components == 2 and reg.n_cavities == 0 and reg.n_tunnels == 0
        assert len(reg.surfaces) == 2


def test_a_cavity_open_through_a_corner_is_not_a_cavity() -> None:
    m = np.ones((4, 4, 4), bool)
    m[1, 1, 1] = False  # would be a cavity ...
    m[0, 0, 0] = False  # ... but its corner neighbour reaches the outside: 26-connected
    reg = check_against_reference(m)
    assert reg.n_cavities == 0
    assert len(reg.surfaces) == 1
    m[0, 0, 0] = True
    assert check_against_reference(m).n_cavities == 1


def test_checkerboard() -> None:
    z, y, x = np.mgrid[0:6, 0:6, 0:6]
    m = (x + y + z) % 2 == 0
    reg = check_against_reference(m)
    assert reg.n_components == int(m.sum()) == reg.euler
    assert reg.n_cavities == 0
    reg = check_against_reference(~m)  # the interior voxels of ~m are isolated too; 26-connected complement
    assert reg.n_cavities == 0


def test_translation_and_padding() -> None:
    m = random_mask(5, (6, 5, 7), 0.5)
    a = region_3d_of(m, (0, 0, 0))
    b = region_3d_of(np.pad(m, ((2, 1), (0, 3), (4, 0))), (10 - 4, -20, 30 - 2))
    assert [c.voxels for c in a.components] == [c.voxels for c in b.components]
    for ca, cb in zip(a.components, b.components, strict=True):
        assert tuple(v + t for v, t in zip(ca.bbox, (10, -20, 30) * 2, strict=True)) == cb.bbox
        assert ca.euler == cb.euler and len(ca.cavities) == len(cb.cavities)
        for va, vb in zip(ca.cavities, cb.cavities, strict=True):
            assert va.voxels == vb.voxels
            assert tuple(v + t for v, t in zip(va.bbox, (10, -20, 30) * 2, strict=True)) == vb.bbox
    assert a.components == tuple(region_3d_of(m).components)


def test_limit_is_checked_before_the_work() -> None:
    with pytest.raises(SizeLimitError):
        region_3d_of(np.ones((4, 4, 4), bool), limit=63)
    region_3d_of(np.ones((4, 4, 4), bool), limit=64)


# ---------------------------------------------------------------------------------------------- properties


@settings(max_examples=150)
@given(masks)
def test_random_masks_against_scipy_and_the_cubical_complex(m: np.ndarray) -> None:
    check_against_reference(m)


@settings(max_examples=60)
@given(masks)
def test_labelling_both_ways_against_scipy(m: np.ndarray) -> None:
    for conn, structure in ((6, ref.S6), (26, ref.S26)):
        lab, n = label_3d(m, conn)
        expect, ne = ndi.label(m, structure)
        assert n == ne and np.array_equal(lab, expect)
    cav, _ = ref.cavities(m)
    assert np.array_equal(paint_background_3d(label_runs_3d(m, 6)) > 0, cav > 0)


# ---------------------------------------------------------------------------------------------- surfaces


def _corner(v: np.ndarray, d: int, a: int, b: int) -> tuple[int, int, int]:
    # Doubled coordinates of a surfel corner: 2p + n + t_a + t_b.
    p = 2 * v + DIRS[d] + DIRS[a] + DIRS[b]
    return int(p[0]), int(p[1]), int(p[2])


def check_surfaces(m: np.ndarray) -> None:
    reg = region_3d_of(m, (-2, 4, 1))
    surfaces = reg.surfaces
    assert len(surfaces) == reg.n_components + reg.n_cavities
    assert [(s.component, s.cavity) for s in surfaces] == [
        (c.label, k) for c in reg.components for k in range(-1, len(c.cavities))
    ]
    # every surfel of the set, once
    pad = np.pad(m, 1)
    expected = set()
    for d, (dx, dy, dz) in enumerate(DIRS.tolist()):
        out = pad[
            1 + dz : pad.shape[0] - 1 + dz, 1 + dy : pad.shape[1] - 1 + dy, 1 + dx : pad.shape[2] - 1 + dx
        ]
        for k, j, i in zip(*np.nonzero(m & ~out), strict=True):
            expected.add((int(i) - 2, int(j) + 4, int(k) + 1, d))
    got = [(*map(int, v), int(d)) for s in surfaces for v, d in zip(s.voxels, s.directions, strict=True)]
    assert len(got) == len(set(got)) and set(got) == expected
    assert reg.n_surfels == len(expected)
    if not surfaces:
        return
    labels = reg.labels()
    ox, oy, oz = reg.origin
    for s in surfaces:
        # inside: the surface's component
        assert np.all(labels[s.voxels[:, 2] - oz, s.voxels[:, 1] - oy, s.voxels[:, 0] - ox] == s.component)
        # closed: the outward normals sum to zero, and every geometric edge is used an even number of times
        assert not DIRS[s.directions].sum(axis=0).any()
        edges: Counter[tuple[tuple[int, int, int], tuple[int, int, int]]] = Counter()
        for t, (v, d) in enumerate(zip(s.voxels, s.directions, strict=True)):
            sides = edge_sides(int(d))
            for e in range(4):
                # the edge on side sides[e] runs between the corners (side, other + ) and (side, other −)
                other = sides[2:] if e < 2 else sides[:2]
                key = tuple(sorted((_corner(v, d, sides[e], other[0]), _corner(v, d, sides[e], other[1]))))
                edges[key] += 1  # type: ignore[index]
                # the neighbour across that edge: in this surface, shares the edge, and links back
                o = int(s.neighbours[t, e])
                assert t in s.neighbours[o].tolist()
                ov, od = s.voxels[o], int(s.directions[o])
                ocorners = {_corner(ov, od, a, b) for a in edge_sides(od)[:2] for b in edge_sides(od)[2:]}
                assert set(key) <= ocorners  # type: ignore[arg-type]
        assert all(c in (2, 4) for c in edges.values())


def test_surfaces_of_known_shapes() -> None:
    for m in (hollow(), solid_torus(9, 2.5, 1.2), ball(2.5, 7)):
        check_surfaces(m)
    reg = region_3d_of(hollow())
    outer, inner = reg.surfaces
    assert (outer.cavity, inner.cavity) == (-1, 0) and len(inner) < len(outer)


@settings(max_examples=40)
@given(masks)
def test_surfaces_of_random_masks(m: np.ndarray) -> None:
    check_surfaces(m)
