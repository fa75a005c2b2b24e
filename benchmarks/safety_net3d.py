"""Benchmark: speed and memory of the 3D safety net R(A) = V(A) eroded by ¼, against marching cubes.

The safety net (``mrm.geometry.reconstruct.safety_net_3d.safety_net_3d``) is the first step of the 3D
reconstruction R; its peer is ``skimage.measure.marching_cubes`` of the mask padded by one voxel, as float32,
at level 0.5 (the padding and the float32 copy included, as in ``benchmarks/reconstruct3d.py``). Shapes: for
each size N (``--sizes``), a ball of radius N/2 − 2 in an N³ box and seeded random blobs
(``reconstruct3d.blobs``).

Times are medians of ``--repeat`` warm runs in this process (after one warm call per row); memory is the
tracemalloc peak of one call (numpy and numba arrays are traced). The ratios are to marching cubes measured in
the same run.

Usage: ``.venv/bin/python benchmarks/safety_net3d.py [--sizes 64 128 256] [--repeat 3] [--seed 0]``
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)

from benchmarks.discretize import median_time, peak_memory  # noqa: E402
from benchmarks.reconstruct3d import blobs, marching_cubes, surfels, table  # noqa: E402


def shapes(n: int, seed: int) -> list[tuple[str, np.ndarray]]:
    """A ball of radius n/2 − 2 centred in an n³ box and the seeded blobs of an n³ box."""
    c = (n - 1) / 2
    rb = n / 2 - 2
    z, y, x = np.ogrid[0:n, 0:n, 0:n]
    ball = np.ascontiguousarray((x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2 <= rb * rb)
    return [(f"ball r={rb:g} in {n}³", ball), (f"blobs {n}³ seed {seed}", blobs(n, seed))]


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[64, 128, 256])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0, help="seed of the random blobs")
    args = ap.parse_args()
    from mrm.geometry.reconstruct.safety_net_3d import safety_net_3d

    cube = np.ones((3, 3, 3), dtype=bool)
    t0 = time.perf_counter()
    safety_net_3d(cube)
    print(f"first call on a 3³ cube (numba compilation or cache loading): {time.perf_counter() - t0:.3f} s\n")
    rows = []
    for n in args.sizes:
        for name, mask in shapes(n, args.seed):
            net = safety_net_3d(mask)  # the warm call
            t_net = median_time(lambda mask=mask: safety_net_3d(mask), args.repeat)
            _, mc_t = marching_cubes(mask)
            t_mc = median_time(lambda mask=mask: marching_cubes(mask), args.repeat)
            m_net = peak_memory(lambda mask=mask: safety_net_3d(mask))
            m_mc = peak_memory(lambda mask=mask: marching_cubes(mask))
            rows.append(
                [name, f"{surfels(mask):,}", f"{len(net.triangles):,}", f"{len(mc_t):,}",
                 f"{t_net:.3f}", f"{t_mc:.3f}", f"{t_net / t_mc:.2f}",
                 f"{m_net / 2**20:,.1f}", f"{m_mc / 2**20:,.1f}", f"{m_net / m_mc:.2f}"]
            )  # fmt: skip
    table(
        ["shape", "surfels", "net tris", "MC tris", "net s", "MC s", "time ÷ MC", "net peak MiB",
         "MC peak MiB", "mem ÷ MC"],
        rows,
    )  # fmt: skip


if __name__ == "__main__":
    main()
