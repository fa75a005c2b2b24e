"""Benchmark: digital plane recognition against DGtal's ChordGenericStandardPlaneComputer.

Both recognizers are given the same point sets, point after point, and stop at the first point refused:

- ours:  ``mrm.geometry.planes.recognition.standard_plane_prefix``, the compiled ``PointPlane`` (exact, the
         cone of normals cut at its vertices, one per octant);
- DGtal: ``ChordGenericStandardPlaneComputer<Z3, Point, int64>`` with width 1/1 (the standard planes), in
         ``benchmarks/dgtal/plane_compare.cpp``, built by ``bash benchmarks/dgtal/build.sh`` (needs the
         ``bench3d`` extra's ``dgtal`` wheel, g++ and Debian's libboost-dev; the script installs them).

Point sets:
- "octahedron faces": the voxels of each of the 8 plane segments of the digital octahedron |x|+|y|+|z| ≤ r,
  in the order our greedy segmentation grew them;
- "ball patches": the same for the plane segments of the digital ball of radius r;
- "plane discs": the points of random standard planes (normals up to 60 in each coordinate) within a
  disc, by distance from the centre;
- "plane discs + 1": the same with one point moved off the plane at a random place (both must refuse it).

Each line gives the number of sets, points, whether both recognizers took the same number of points on every
set (they decide the same question, so they must), how many chosen normals are equal (ours is the smallest
admissible normal; DGtal's is the one its algorithm ends on), and the time per point of the extend/add calls
of each, with the ratio; the last column is the time our smallest-normal search takes per set afterwards
(DGtal's getCharacteristics is not timed). Times: medians over ``--repeat`` runs (ours in this process, DGtal
inside its process, reading excluded).

A second table times the compiled greedy segmentation of whole surfaces (digital balls) that the analytical
representation uses (``mrm.geometry.planes.segmentation.plane_segments``, surfel-patch recognition, no peer:
DGtal has no segmentation of a surfel surface into standard plane segments with this contract).

Usage: ``.venv/bin/python benchmarks/planes.py [--radius 40] [--repeat 3]``
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from statistics import median

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)

PEER = os.path.join(ROOT, "benchmarks", "dgtal", "build", "plane_compare")


def segment_point_sets(mask: np.ndarray, origin: tuple[int, int, int]) -> list[np.ndarray]:
    """The voxels of A of each greedy plane segment of the mask's surfaces, in the order they were added."""
    from mrm.geometry.planes.segmentation import plane_segments
    from mrm.geometry.topology.labeling_3d import label_runs_3d
    from mrm.geometry.topology.surfels import surfels_of

    s = surfels_of(label_runs_3d(mask, 6))
    seg = plane_segments(s.voxel + np.array(origin), s.direction, s.neighbour)
    out = []
    for k in range(len(seg)):
        vox = seg.voxel[seg.surfels_of(k)]
        _, first = np.unique(vox, axis=0, return_index=True)
        out.append(vox[np.sort(first)])
    return out


def segmentation_rows(radii: list[int], repeat: int) -> None:
    """The compiled greedy segmentation of whole surfaces (balls): surfels, segments, time, surfels/s."""
    from mrm.geometry.planes.segmentation import plane_segments
    from mrm.geometry.topology.labeling_3d import label_runs_3d
    from mrm.geometry.topology.surfels import surfels_of

    print()
    print("greedy segmentation of a digital ball's surface (compiled; surfels built beforehand, not timed)")
    print(f"{'radius':>7}{'surfels':>10}{'segments':>10}{'seconds':>10}{'surfels/s':>12}")
    for r in radii:
        x, y, z = centred_grid(r)
        s = surfels_of(label_runs_3d(x * x + y * y + z * z <= r * r, 6))
        times = []
        for _ in range(repeat):
            t = time.perf_counter()
            seg = plane_segments(s.voxel, s.direction, s.neighbour)
            times.append(time.perf_counter() - t)
        t_med = median(times)
        print(f"{r:>7}{len(s.direction):>10}{len(seg):>10}{t_med:>10.3f}{len(s.direction) / t_med:>12,.0f}")


def centred_grid(r: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    g = np.arange(-r - 1, r + 2)
    z, y, x = np.meshgrid(g, g, g, indexing="ij")
    return x, y, z


def plane_discs(rng: np.random.Generator, count: int, radius: int, moved: bool) -> list[np.ndarray]:
    out = []
    for _ in range(count):
        n = rng.integers(-60, 61, 3)
        while not n.any():
            n = rng.integers(-60, 61, 3)
        k = int(np.argmax(np.abs(n)))  # solve for the dominant coordinate: one point per column
        u, v = (k + 1) % 3, (k + 2) % 3
        a, b = np.meshgrid(np.arange(-radius, radius + 1), np.arange(-radius, radius + 1), indexing="ij")
        a, b = a.ravel(), b.ravel()
        keep = a * a + b * b <= radius * radius
        a, b = a[keep], b[keep]
        mu = int(rng.integers(-50, 50))
        # n_k·w + n_u·a + n_v·b ∈ [mu, mu + ω): w = ceil((mu − n_u·a − n_v·b) / n_k) when n_k > 0.
        nk = int(n[k])
        rest = mu - n[u] * a - n[v] * b
        w = -((-rest) // nk) if nk > 0 else -(rest // -nk)
        pts = np.zeros((a.size, 3), np.int64)
        pts[:, k], pts[:, u], pts[:, v] = w, a, b
        order = np.argsort(a * a + b * b, kind="stable")
        pts = pts[order]
        if moved:
            i = int(rng.integers(pts.shape[0] // 4, pts.shape[0]))
            pts[i, k] += int(np.abs(n).sum()) // max(1, abs(nk)) + 1
        out.append(pts)
    return out


def ours(sets: list[np.ndarray]) -> tuple[list[int], list[tuple[int, int, int]], float, float]:
    """(points taken, chosen normals, seconds of the compiled recognition, seconds of the normal choice).

    The recognition is ``point_plane_prefix`` (the compiled PointPlane); the normal choice is what
    ``standard_plane_prefix`` takes beyond it (the smallest admissible normal, in Python).
    """
    from mrm.geometry.planes._kernels import point_plane_prefix
    from mrm.geometry.planes.recognition import standard_plane_prefix

    accepted, normals, t_add, t_normal = [], [], 0.0, 0.0
    for pts in sets:
        arr = np.ascontiguousarray(pts, np.int64)
        t = time.perf_counter()
        k, _, _ = point_plane_prefix(arr)
        t_kernel = time.perf_counter() - t
        t_add += t_kernel
        t = time.perf_counter()
        taken, plane = standard_plane_prefix(arr)
        t_normal += max(0.0, time.perf_counter() - t - t_kernel)
        assert taken == k
        accepted.append(k)
        normals.append(plane.normal if plane is not None else (0, 0, 0))
    return accepted, normals, t_add, t_normal


def dgtal(sets: list[np.ndarray]) -> tuple[list[int], list[tuple[int, int, int]], float]:
    with tempfile.NamedTemporaryFile(suffix=".bin", delete=False) as f:
        data = [np.array([len(sets)], np.int64)]
        for pts in sets:
            data += [np.array([len(pts)], np.int64), np.ascontiguousarray(pts, np.int64).ravel()]
        np.concatenate(data).astype("<i8").tofile(f)
    try:
        out = subprocess.run([PEER, f.name], capture_output=True, text=True, check=True).stdout.split("\n")
    finally:
        os.unlink(f.name)
    accepted, normals, ns = [], [], 0
    for line in out:
        if line.strip():
            k, a, b, c, t = (int(x) for x in line.split())
            accepted.append(k)
            normals.append((a, b, c))
            ns += t
    return accepted, normals, ns / 1e9


def same_direction(u: tuple[int, int, int], v: tuple[int, int, int]) -> bool:
    # DGtal reports the normal up to sign (last component positive).
    return u == v or u == tuple(-c for c in v)


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--radius", type=int, default=40)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    if not os.path.exists(PEER):
        sys.exit("build the peer first: bash benchmarks/dgtal/build.sh")
    r = args.radius
    rng = np.random.default_rng(2026)
    x, y, z = centred_grid(r)
    workloads = {
        "octahedron faces": segment_point_sets(np.abs(x) + np.abs(y) + np.abs(z) <= r, (-r - 1,) * 3),
        "ball patches": segment_point_sets(x * x + y * y + z * z <= r * r, (-r - 1,) * 3),
        "plane discs": plane_discs(rng, 20, r, moved=False),
        "plane discs + 1": plane_discs(rng, 20, r, moved=True),
    }
    print(f"digital plane recognition, r = {args.radius}, medians of {args.repeat} runs")
    print(
        f"{'point sets':<18}{'sets':>6}{'points':>9}{'same taken':>12}{'same normal':>13}"
        f"{'ours µs/pt':>12}{'DGtal µs/pt':>13}{'ours/DGtal':>12}{'our normal ms/set':>19}"
    )
    for name, sets in workloads.items():
        runs_o = [ours(sets) for _ in range(args.repeat)]
        runs_d = [dgtal(sets) for _ in range(args.repeat)]
        acc_o, nor_o, _, _ = runs_o[0]
        acc_d, nor_d, _ = runs_d[0]
        points = sum(len(s) for s in sets)
        t_o = median(r[2] for r in runs_o) / points * 1e6
        t_d = median(r[2] for r in runs_d) / points * 1e6
        t_n = median(r[3] for r in runs_o) / len(sets) * 1e3
        same = sum(a == b for a, b in zip(acc_o, acc_d, strict=True))
        same_n = sum(same_direction(a, b) for a, b in zip(nor_o, nor_d, strict=True))
        print(
            f"{name:<18}{len(sets):>6}{points:>9}{f'{same}/{len(sets)}':>12}{f'{same_n}/{len(sets)}':>13}"
            f"{t_o:>12.2f}{t_d:>13.3f}{t_o / t_d:>11.1f}×{t_n:>19.2f}"
        )
    segmentation_rows([8, 25, 50, 100, 200], args.repeat)


if __name__ == "__main__":
    main()
