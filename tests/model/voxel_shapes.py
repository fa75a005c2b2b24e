"""Voxel masks shared by the 3D region and safety-net tests: known shapes and seeded random masks."""

from __future__ import annotations

import numpy as np


def ball(r: float, n: int) -> np.ndarray:
    z, y, x = np.mgrid[0:n, 0:n, 0:n] - (n - 1) / 2
    return x * x + y * y + z * z <= r * r


def solid_torus(n: int = 15, big: float = 4.5, small: float = 2.0) -> np.ndarray:
    z, y, x = np.mgrid[0:n, 0:n, 0:n] - (n - 1) / 2
    return (np.hypot(x, y) - big) ** 2 + z * z <= small * small


def hollow(n: int = 9) -> np.ndarray:
    return ball(n / 2 - 0.5, n) & ~ball(n / 2 - 2.5, n)


def random_mask(seed: int, shape: tuple[int, int, int], density: float) -> np.ndarray:
    return np.random.default_rng(seed).random(shape) < density


def smoothed_noise(n: int, seed: int) -> np.ndarray:
    """Blobs: uniform noise over an n³ box, averaged over its 3 neighbours along each axis four times,
    thresholded at ½ (not convex, many small plane segments: a decimation of several seconds at n = 40)."""
    f = np.random.default_rng(seed).random((n, n, n))
    for _ in range(4):
        for axis in range(3):
            f = (np.roll(f, 1, axis) + f + np.roll(f, -1, axis)) / 3
    return f > 0.5


def assert_within_border_cubes(poly: object, vs: object) -> None:
    """∂P meets only cubes of border voxels: each voxel its triangles touch (their supercover, exactly) has
    both a voxel of A and one outside in its 3×3×3 block (docs/design.md §11, item 2 under gauss)."""
    from mrm.core.grids import VoxelSet
    from mrm.geometry.discretize.voxels import voxelize_triangles

    assert isinstance(vs, VoxelSet)
    touched, origin = voxelize_triangles(poly.vertices, poly.triangles, "supercover", limit=None)  # type: ignore[attr-defined]
    x0, y0, z0, x1, y1, z1 = vs.bbox
    frame = (min(x0, origin[0]) - 2, min(y0, origin[1]) - 2, min(z0, origin[2]) - 2,
             max(x1, origin[0] + touched.shape[2]) + 2, max(y1, origin[1] + touched.shape[1]) + 2,
             max(z1, origin[2] + touched.shape[0]) + 2)  # fmt: skip
    box = VoxelSet(touched, origin).to_array(frame)  # the voxels the surface meets
    a = vs.to_array(frame)
    padded = np.pad(a, 1)
    block = sum(
        padded[dz : dz + a.shape[0], dy : dy + a.shape[1], dx : dx + a.shape[2]].astype(int)
        for dz in range(3)
        for dy in range(3)
        for dx in range(3)
    )
    border = (block > 0) & (block < 27)
    assert not (box & ~border).any()


def assert_convex_r_commutes_with_the_cube(vs: object, model: str) -> object:
    """R of a digitally convex A (the hull paths, ``convex_reconstruction``) under the 24 rotations of the
    cube gives the turned R, triangle for triangle (corners compared exactly), and a far translation gives R
    translated (``==``). A must have no symmetry of its own. Returns R(A)'s ``ConvexR``."""
    import mrm
    from mrm.core.grids import VoxelSet
    from mrm.geometry.reconstruct.convex_3d import convex_reconstruction
    from mrm.geometry.reconstruct.decimate_3d import ROTATIONS

    assert isinstance(vs, VoxelSet)

    def turned(points: np.ndarray, perm: tuple[int, ...], signs: tuple[int, ...]) -> np.ndarray:
        return points[:, list(perm)] * np.array(signs)

    def triangles(p: mrm.Polyhedron) -> set[tuple[tuple[float, ...], ...]]:
        out = set()  # each triangle's corners from its least one, the cyclic order kept
        for t in p.triangles:
            corners = [tuple(p.vertices[i]) for i in t]
            k = corners.index(min(corners))
            out.add(tuple(corners[k:] + corners[:k]))
        return out

    found = convex_reconstruction(vs, model)
    assert found is not None
    poly = found.polyhedron
    for perm, signs in ROTATIONS:
        got = convex_reconstruction(VoxelSet.from_points(turned(vs.points(), perm, signs)), model)
        assert got is not None
        expected = mrm.Polyhedron(turned(poly.vertices, perm, signs), poly.triangles)
        assert triangles(got.polyhedron) == triangles(expected)
        assert got.polyhedron.n_faces == poly.n_faces
    t = (2**30, -(2**29), 12345)
    moved = convex_reconstruction(vs.translate(*t), model)
    assert moved is not None and moved.polyhedron == poly.translate(t)
    return found
