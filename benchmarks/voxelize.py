"""Benchmark: exact voxelization (three models) against trimesh and Open3D, in the same run (issue 28 item 3).

A closed, non-convex 100,800-triangle mesh (a bumpy UV sphere, generated here, coordinates generic floats)
fills a 512³ box. Prints the warm median time of each of our models, trimesh's ``voxelized(pitch=1)`` +
``fill()`` (one run: it takes minutes) and Open3D's ``VoxelGrid.create_from_triangle_mesh_within_bounds``
(a surface voxelization: Open3D does not fill), the ratios, the peak memory of ours per voxel of the bounding
box (tracemalloc), and how many voxels the peers get wrong against our exact results:

* trimesh (filled) against our solid ``gauss`` and ``supercover``: voxels it claims whose cube does not even
  touch the solid (wrong in every model), voxels whose centre is inside the solid that it misses (wrong in
  every model), and the symmetric differences with each of our results;
* Open3D (surface) against our exact ``supercover`` of the triangles (the closed-cube rule it implements in
  floating point): voxels claimed that no triangle touches, and voxels touched that it misses.

Both peers put voxel centres on integer coordinates here (pitch 1; Open3D's bounds are shifted by ½), so the
grids coincide with ours (docs/design.md §11).

Run:  .venv/bin/python benchmarks/voxelize.py [--repeats 5] [--size 512] [--no-trimesh] [--no-open3d]

Open3D is large and is not installed by `.ci/setup.sh`: `.venv/bin/pip install -e '.[bench3d]'` (it needs
Debian's libusb-1.0-0); without it the script says so and measures the rest.
"""

from __future__ import annotations

import argparse
import gc
import os
import sys
import time
from typing import Any

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
sys.path.insert(0, os.path.dirname(__file__))

from discretize import median_time, peak_memory

from mrm.core.models import Model
from mrm.geometry.discretize.voxels import voxelize_solid, voxelize_triangles

MODELS = Model.names()


def bumpy_sphere(n_phi: int = 400, n_theta: int = 128, size: int = 512) -> tuple[np.ndarray, np.ndarray]:
    """A closed outward UV sphere with radial bumps, 2·n_phi·(n_theta − 2) triangles, filling a size³ box."""
    th = np.linspace(0.0, np.pi, n_theta)[1:-1]
    ph = np.linspace(0.0, 2.0 * np.pi, n_phi, endpoint=False)
    t_, p_ = np.meshgrid(th, ph, indexing="ij")
    r = (1.0 + 0.06 * np.sin(5 * t_) * np.cos(3 * p_) + 0.03 * np.cos(7 * p_))[..., None]
    d = np.stack([np.sin(t_) * np.cos(p_), np.sin(t_) * np.sin(p_), np.cos(t_)], -1)
    ring = (r * d).reshape(-1, 3)
    v = np.concatenate([ring, [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]])
    lo, hi = v.min(0), v.max(0)
    v = (v - lo) / (hi - lo).max() * (size - 1.02) + 0.01  # generic float coordinates in (0, size − 1)
    nt = n_theta - 2
    idx = np.arange(nt * n_phi).reshape(nt, n_phi)
    a, b = idx[:-1], idx[1:]
    c, e = np.roll(idx[1:], -1, 1), np.roll(idx[:-1], -1, 1)
    top, bottom = len(ring), len(ring) + 1
    tris = [
        np.stack([a, b, c], -1).reshape(-1, 3),
        np.stack([a, c, e], -1).reshape(-1, 3),
        np.stack([np.full(n_phi, top), idx[0], np.roll(idx[0], -1)], -1),
        np.stack([np.full(n_phi, bottom), np.roll(idx[-1], -1), idx[-1]], -1),
    ]
    return v, np.concatenate(tris).astype(np.int64)


def grid_octahedron(n: int = 112, step: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """|x| + |y| + |z| ≤ n·step with each face cut into n² triangles on integer vertices: 8n² triangles.

    The tie-rich case (the paper's Figure 12): every face passes through voxel centres, edges and corners.
    """
    r = n * step
    verts: dict[tuple[int, int, int], int] = {}
    tris = []

    def vid(p: tuple[int, int, int]) -> int:
        return verts.setdefault(p, len(verts))

    for sx in (1, -1):
        for sy in (1, -1):
            for sz in (1, -1):

                def pt(i: int, j: int, sx: int = sx, sy: int = sy, sz: int = sz) -> tuple[int, int, int]:
                    return (sx * i * step, sy * j * step, sz * (r - (i + j) * step))

                flip = sx * sy * sz < 0  # outward: counter-clockwise seen from outside
                for i in range(n):
                    for j in range(n - i):
                        cand = [(pt(i, j), pt(i + 1, j), pt(i, j + 1))]
                        if i + j < n - 1:
                            cand.append((pt(i + 1, j), pt(i + 1, j + 1), pt(i, j + 1)))
                        for a, b, c in cand:
                            tris.append((vid(a), vid(c), vid(b)) if flip else (vid(a), vid(b), vid(c)))
    v = np.array(sorted(verts, key=verts.__getitem__), dtype=np.float64)
    return v, np.array(tris, dtype=np.int64)


def in_box(
    mask: np.ndarray, origin: tuple[int, int, int], box: tuple[int, int, int, int, int, int]
) -> np.ndarray:
    """Our (mask[k, j, i], origin) pasted into the common box (x0, y0, z0, x1, y1, z1)."""
    x0, y0, z0, x1, y1, z1 = box
    out = np.zeros((z1 - z0 + 1, y1 - y0 + 1, x1 - x0 + 1), dtype=bool)
    ox, oy, oz = origin
    nz, ny, nx = mask.shape
    out[oz - z0 : oz - z0 + nz, oy - y0 : oy - y0 + ny, ox - x0 : ox - x0 + nx] = mask
    return out


def points_in_box(xyz: np.ndarray, box: tuple[int, int, int, int, int, int]) -> tuple[np.ndarray, int]:
    """Integer voxel centres (n, 3) as a mask of the common box, and how many fell outside it."""
    x0, y0, z0, x1, y1, z1 = box
    out = np.zeros((z1 - z0 + 1, y1 - y0 + 1, x1 - x0 + 1), dtype=bool)
    i, j, k = xyz[:, 0] - x0, xyz[:, 1] - y0, xyz[:, 2] - z0
    ok = (i >= 0) & (j >= 0) & (k >= 0) & (i < out.shape[2]) & (j < out.shape[1]) & (k < out.shape[0])
    out[k[ok], j[ok], i[ok]] = True
    return out, int((~ok).sum())


def trimesh_filled(v: np.ndarray, t: np.ndarray) -> np.ndarray:
    """trimesh's voxelization + fill, as integer voxel centres (n, 3)."""
    import trimesh

    grid = trimesh.Trimesh(v, t, process=False).voxelized(pitch=1.0).fill()
    idx = grid.sparse_indices.astype(np.float64)
    centres = idx @ grid.transform[:3, :3].T + grid.transform[:3, 3]
    out = np.rint(centres).astype(np.int64)
    assert np.array_equal(out, centres), "trimesh's voxel centres are not on the integer grid"
    return out


def open3d_surface(v: np.ndarray, t: np.ndarray, box: tuple[int, int, int, int, int, int]) -> np.ndarray:
    """Open3D's voxelization of the triangles (surface), as integer voxel centres (n, 3)."""
    import open3d as o3d

    mesh = o3d.geometry.TriangleMesh(
        o3d.utility.Vector3dVector(v), o3d.utility.Vector3iVector(t.astype(np.int32))
    )
    x0, y0, z0, x1, y1, z1 = box
    grid = o3d.geometry.VoxelGrid.create_from_triangle_mesh_within_bounds(
        mesh, 1.0, np.array([x0 - 0.5, y0 - 0.5, z0 - 0.5]), np.array([x1 + 0.5, y1 + 0.5, z1 + 0.5])
    )
    idx = np.array([vox.grid_index for vox in grid.get_voxels()], dtype=np.int64).reshape(-1, 3)
    return idx + np.array([x0, y0, z0])


def timed(f: Any) -> tuple[float, Any]:
    gc.collect()
    t0 = time.perf_counter()
    out = f()
    return time.perf_counter() - t0, out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--no-trimesh", action="store_true")
    parser.add_argument("--no-open3d", action="store_true")
    args = parser.parse_args()
    meshes = {
        "bumpy sphere (generic floats)": bumpy_sphere(size=args.size),
        "grid octahedron (integer vertices: ties everywhere)": grid_octahedron(),
    }
    for name, (v, t) in meshes.items():
        print(f"\n==== {name}")
        run(v, t, args)


def run(v: np.ndarray, t: np.ndarray, args: argparse.Namespace) -> None:
    """Time and compare ours and the peers on one mesh."""
    print(
        f"mesh: {len(t):,} triangles, {len(v):,} vertices, extent {v.min(0).round(2)} .. {v.max(0).round(2)}"
    )

    first = {}
    for m in MODELS:
        first[m], _ = timed(lambda m=m: voxelize_solid(v, t, m))
    print("first call (numba cache load), s: " + ", ".join(f"{m} {s:.2f}" for m, s in first.items()))
    ours = {m: median_time(lambda m=m: voxelize_solid(v, t, m), args.repeats) for m in MODELS}
    surf = median_time(lambda: voxelize_triangles(v, t, "supercover"), args.repeats)
    results = {m: voxelize_solid(v, t, m) for m in ("gauss", "supercover")}
    sc_mask, sc_origin = results["supercover"]
    box_voxels = sc_mask.size
    print(f"\nours, warm median of {args.repeats} runs (solid):")
    for m in MODELS:
        mem = peak_memory(lambda m=m: voxelize_solid(v, t, m))
        print(
            f"  {m:<11} {ours[m]:7.3f} s   peak memory {mem / 2**20:7.1f} MiB"
            f" = {mem / box_voxels:.3f} B/voxel"
        )
    print(f"  supercover of the triangles only (surface): {surf:.3f} s")
    print(
        f"  bounding box {sc_mask.shape[::-1]} = {box_voxels:,} voxels; "
        f"gauss {int(results['gauss'][0].sum()):,} "
        f"voxels, supercover {int(sc_mask.sum()):,}"
    )

    x0, y0, z0 = sc_origin
    nz, ny, nx = sc_mask.shape
    box = (x0 - 2, y0 - 2, z0 - 2, x0 + nx + 1, y0 + ny + 1, z0 + nz + 1)  # room for peers' stray voxels
    g = in_box(*results["gauss"], box)
    s = in_box(*results["supercover"], box)
    del results, sc_mask
    gc.collect()

    if not args.no_trimesh:
        try:
            dt, pts = timed(lambda: trimesh_filled(v, t))
        except Exception as exc:  # a peer failing is a result too
            print(f"\ntrimesh failed: {exc!r}")
        else:
            tm, outside = points_in_box(pts, box)
            del pts
            print(
                f"\ntrimesh voxelized(pitch=1) + fill(): {dt:.2f} s (one run) = "
                f"{dt / ours['gauss']:.0f}× our gauss, "
                f"{dt / ours['supercover']:.0f}× our supercover; {int(tm.sum()) + outside:,} voxels"
            )
            print(
                f"  claimed but the solid does not touch the cube (not in our supercover): "
                f"{int((tm & ~s).sum()) + outside:,}"
            )
            print(f"  centre inside the solid but missed (in our gauss): {int((g & ~tm).sum()):,}")
            print(
                f"  claimed, centre not inside (not in our gauss): {int((tm & ~g).sum()) + outside:,}; "
                f"cube touched but missed (in our supercover): {int((s & ~tm).sum()):,}"
            )
            print(
                f"  differs from our gauss: {int((tm ^ g).sum()) + outside:,}; "
                f"from our supercover: {int((tm ^ s).sum()) + outside:,}"
            )
            del tm
    if not args.no_open3d:
        try:
            import open3d  # noqa: F401
        except ImportError:
            print("\nOpen3D: not installed")
        else:
            surface = in_box(*voxelize_triangles(v, t, "supercover"), box)
            dt, pts = timed(lambda: open3d_surface(v, t, box))
            o3, outside = points_in_box(pts, box)
            print(
                f"\nOpen3D create_from_triangle_mesh_within_bounds (surface only): {dt:.2f} s (one run) = "
                f"{dt / surf:.1f}× our supercover surface; {len(pts):,} voxels, ours {int(surface.sum()):,}"
            )
            print(f"  claimed but no triangle touches the cube: {int((o3 & ~surface).sum()) + outside:,}")
            print(f"  touched by a triangle but missed: {int((surface & ~o3).sum()):,}")


if __name__ == "__main__":
    main()
