"""Benchmark: label volumes to meshes — ``polygonize_volume`` against marching cubes run per label.

Ours = ``mrm.geometry.reconstruct.polygonize_3d.polygonize_volume(labels)``: one closed mesh per region (a
6-connected component of one label), a face between two regions the same triangles in both meshes, reversed,
and D_gauss of each mesh its region exactly (docs/polygonize-3d.md). The peer, on the same volume:

- MC: ``skimage.measure.marching_cubes`` of each label's mask (cropped to its box, padded by one voxel) at
  level 0.5, the mesh in world coordinates (``benchmarks.reconstruct3d.marching_cubes`` / ``mc_to_world``):
  the usual way to mesh a segmentation. Each label's mesh cuts the corners of its own voxels, so two
  neighbouring labels' meshes differ wherever their common boundary bends: the table gives the triangles of
  MC not shared (no label holds the same triangle reversed), apart from those on the box's outer faces, and
  the volume of the gaps: the box's volume minus the sum of the labels' mesh volumes (each label's mesh is
  inside its voxels, so what is missing is a gap between labels). Burnt back with the exact ``gauss``
  voxelization (``voxelize_solid``) MC gives each label its voxels here (its surface passes midway between
  centres), so "MC wrong" counts the voxels claimed by two labels or by none: the voxel test does not see
  the gaps, the shared-triangle test does.

The same two measures are taken of ours: its unshared triangles away from the border must be 0; its gap is
what a region gives to the outside at the box's border where it meets itself only along an edge (a few
quarter cells, multiples of 1/64).

Volumes: seeded random blobs, the argmax over ``--labels`` fields of gaussian noise drawn on a grid 8 times
coarser (blurred by 1.5 of its cells) and interpolated trilinearly to N³: blobs of the same size at every N
(a coarse cell is 8 voxels), so more of them in a larger box.
Times are medians of ``--repeat`` runs in this process after one warm call (numba's compilation or cache
load at the start); memory is tracemalloc's peak of one call.

Usage: ``.venv/bin/python benchmarks/polygonize3d.py [--sizes 64 128 256] [--labels 3 50] [--repeat 3]
[--seed 0] [--no-mc]``
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from typing import Any

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)

from benchmarks.discretize import median_time, peak_memory  # noqa: E402
from benchmarks.reconstruct3d import marching_cubes, mc_to_world  # noqa: E402
from mrm.geometry.discretize.voxels import voxelize_solid  # noqa: E402
from mrm.geometry.reconstruct.polygonize_3d import polygonize_volume  # noqa: E402


def blobs(n: int, labels: int, seed: int) -> np.ndarray:
    """The argmax (labels 1 … ``labels``) of smooth random fields on an n³ box: blobs of a few 10⁴ voxels."""
    from scipy import ndimage

    rng = np.random.default_rng(seed)
    coarse = max(n // 8, 2)
    best = np.full((n, n, n), -np.inf, np.float32)
    lab = np.zeros((n, n, n), np.int32)
    for value in range(1, labels + 1):
        field = ndimage.gaussian_filter(rng.standard_normal((coarse + 2,) * 3), 1.5, mode="wrap")
        big = ndimage.zoom(field, n / coarse, order=1)[:n, :n, :n].astype(np.float32)
        more = big > best
        best[more] = big[more]
        lab[more] = value
    return lab


def mc_per_label(lab: np.ndarray) -> list[tuple[int, np.ndarray, np.ndarray]]:
    """Marching cubes of each label's mask, cropped to its box: (label, vertices (x, y, z), triangles)."""
    out = []
    for value in np.unique(lab[lab != 0]).tolist():
        mask = lab == value
        zz, yy, xx = (np.flatnonzero(mask.any(axis=tuple(a for a in range(3) if a != d))) for d in range(3))
        sub = mask[zz[0] : zz[-1] + 1, yy[0] : yy[-1] + 1, xx[0] : xx[-1] + 1]
        v, t = mc_to_world(*marching_cubes(sub), (int(xx[0]), int(yy[0]), int(zz[0])))
        out.append((value, v, t))
    return out


def sharing(meshes: list[tuple[np.ndarray, np.ndarray]], n: int) -> dict[str, Any]:
    """The same measures of both methods' meshes on an n³ box (no background inside it).

    ``unshared``: triangles away from the box's border (every corner at least one voxel inside it) whose
    reverse no other mesh holds (exact coordinates); ``interior``: all those triangles; ``gap``: n³ minus
    the sum of the meshes' volumes (what no mesh covers, or covers twice with the opposite sign).
    """
    keys: dict[tuple[float, ...], int] = {}
    corners = []
    for idx, (v, t) in enumerate(meshes):
        c = v[t]  # (m, 3, 3)
        corners.append(c)
        for tri in c.tolist():
            start = min(range(3), key=lambda s, tri=tri: tuple(tri[s]))
            keys[tuple(x for s in range(3) for x in tri[(start + s) % 3])] = idx
    unshared = interior = 0
    volume = 0.0
    for idx, c in enumerate(corners):
        volume += float(np.einsum("ij,ij->", c[:, 0], np.cross(c[:, 1], c[:, 2]))) / 6.0
        inside = ((c >= 0.5) & (c <= n - 1.5)).all(axis=(1, 2))
        for tri in c[inside].tolist():
            interior += 1
            rev = tri[::-1]
            start = min(range(3), key=lambda s, rev=rev: tuple(rev[s]))
            other = keys.get(tuple(x for s in range(3) for x in rev[(start + s) % 3]), -1)
            if other < 0 or other == idx:
                unshared += 1
    return {"unshared": unshared, "interior": interior, "gap": float(n**3) - volume}


def wrong_voxels(meshes: list[tuple[np.ndarray, np.ndarray]], shape: tuple[int, ...]) -> int:
    """Voxels claimed by two meshes or by none when each is burnt back exactly (gauss, ``voxelize_solid``)."""
    claims = np.zeros(shape, np.int32)
    for v, t in meshes:
        mask, (ox, oy, oz) = voxelize_solid(v, t, "gauss", limit=None)
        claims[oz : oz + mask.shape[0], oy : oy + mask.shape[1], ox : ox + mask.shape[2]] += mask
    return int(np.count_nonzero(claims != 1))


def shown(m: dict[str, Any]) -> str:
    return f"{m['unshared']:>9,} ({100 * m['unshared'] / max(m['interior'], 1):>4.1f} %) {m['gap']:>9.2f}"


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[64, 128, 256])
    ap.add_argument("--labels", type=int, nargs="+", default=[3, 50])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--no-mc", action="store_true", help="skip marching cubes (its measures take a while)")
    args = ap.parse_args()

    t0 = time.perf_counter()
    polygonize_volume(blobs(8, 3, 0))
    print(f"first call (numba compile or cache load): {time.perf_counter() - t0:.2f} s")
    print(f"times: median of {args.repeat} runs, seconds; memory: tracemalloc peak of one call\n")
    head = (
        f"{'size':>5} {'labels':>6} {'regions':>7} {'surfels':>10} | {'ours tri':>10} {'ours vert':>10} "
        f"{'ours s':>7} {'ours MB':>8} {'unshared':>18} {'gap vol':>9} | {'MC tri':>10} {'MC s':>6} "
        f"{'unshared':>18} {'gap vol':>9} {'MC wrong':>8}"
    )
    print(head)
    print("-" * len(head))
    for n in args.sizes:
        for labels in args.labels:
            lab = blobs(n, labels, args.seed)
            out = polygonize_volume(lab)
            ours_s = median_time(lambda lab=lab: polygonize_volume(lab), args.repeat)
            ours_mb = peak_memory(lambda lab=lab: polygonize_volume(lab)) / 2**20
            ours = [(out.vertices, r.triangles) for r in out.regions]
            line = (
                f"{n:>5} {labels:>6} {len(out.regions):>7} {out.surfels:>10,} | {out.n_triangles:>10,} "
                f"{out.vertices.shape[0]:>10,} {ours_s:>7.2f} {ours_mb:>8.0f} {shown(sharing(ours, n))}"
            )
            if not args.no_mc:
                meshes = mc_per_label(lab)
                mc_s = median_time(lambda lab=lab: mc_per_label(lab), args.repeat)
                mc = [(v, t) for _, v, t in meshes]
                mc_tri = sum(len(t) for _, t in mc)
                wrong = wrong_voxels(mc, lab.shape)
                line += f" | {mc_tri:>10,} {mc_s:>6.2f} {shown(sharing(mc, n))} {wrong:>8,}"
            print(line, flush=True)


if __name__ == "__main__":
    main()
