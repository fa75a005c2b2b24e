"""Benchmark: the 3D region representation (components, cavities, Euler characteristic) against scipy.

Compares, on the same boolean volumes (default 512³):

- ours:   ``mrm.reps.region_3d.region_3d_of(mask)`` — the 6-connected components with voxel counts, boxes and
          Euler characteristics, the cavities (bounded 26-components of the complement) attached to them, so
          tunnels too (docs/design.md §11);
- scipy:  ``scipy.ndimage.label(mask, 6-connectivity)`` — the components only (a label volume);
- ours+surfaces (once, not in the ratio): the surfels grouped into one closed surface per component and
  cavity.

Volumes: "blobs" is smoothed noise thresholded (64³ uniform noise trilinearly upsampled ×8, > 0.5: about 300
components, 250 cavities, 24,000 tunnels); "fine blobs" the same from 128³ noise upsampled ×4.
Times are medians of ``--repeat`` runs in this process; numba compilation or cache loading is measured once,
apart.

Usage: ``.venv/bin/python benchmarks/region3d.py [--size 512] [--repeat 3] [--surfaces]``
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

from benchmarks.region import median_time  # noqa: E402


def make_volumes(n: int) -> dict[str, np.ndarray]:
    import scipy.ndimage as ndi

    rng = np.random.default_rng(12345)
    out = {}
    for name, f in (("blobs", 8), ("fine blobs", 4)):
        noise = rng.random((n // f,) * 3, dtype=np.float32)
        out[name] = ndi.zoom(noise, f, order=1) > 0.5
    return out


def warm_up() -> float:
    """First call of ours on a tiny volume: numba compilation or cache loading. Returns seconds."""
    from mrm.reps.region_3d import region_3d_of

    t = time.perf_counter()
    reg = region_3d_of(np.random.default_rng(0).random((6, 6, 6)) < 0.5)
    _ = reg.surfaces
    return time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--surfaces", action="store_true", help="also time the surfel surfaces once")
    args = ap.parse_args()

    import scipy.ndimage as ndi

    from mrm.reps.region_3d import region_3d_of

    s6 = ndi.generate_binary_structure(3, 1)
    print(f"first call of region_3d_of + surfaces (numba compile or cache load): {warm_up() * 1000:.0f} ms")
    print(f"times: median of {args.repeat} runs, seconds\n")
    head = (
        f"{'volume':<11} {'size':>5} {'comps':>6} {'cavs':>6} {'tunnels':>8} {'euler':>8} |"
        f" {'ours':>6} {'scipy':>6} | {'ratio':>6}"
    )
    if args.surfaces:
        head += f" | {'surfaces':>8} {'surfels':>10}"
    print(head)
    print("-" * len(head))
    for name, m in make_volumes(args.size).items():
        reg = region_3d_of(m)
        t_ours = median_time(region_3d_of, m, args.repeat)
        t_scipy = median_time(lambda a: ndi.label(a, s6), m, args.repeat)
        line = (
            f"{name:<11} {args.size:>5} {reg.n_components:>6} {reg.n_cavities:>6}"
            f" {reg.n_tunnels:>8} {reg.euler:>8} |"
            f" {t_ours:>6.2f} {t_scipy:>6.2f} | {t_ours / t_scipy:>6.2f}"
        )
        if args.surfaces:
            t = time.perf_counter()
            surf = reg.surfaces
            line += f" | {time.perf_counter() - t:>8.2f} {sum(len(s) for s in surf):>10}"
        print(line, flush=True)


if __name__ == "__main__":
    main()
