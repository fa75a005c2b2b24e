"""Benchmark: exact discretization (three models) against GDAL's rasterizer (rasterio.features.rasterize).

For random noisy star-shaped polygons of 50, 500 and 5000 vertices scaled to grids of 512², 2048² and 4096²,
prints the median time of each of our models and of GDAL (all_touched False and True) measured in the same
run, the ratio ours/GDAL, the peak memory traced by tracemalloc, and how many pixels GDAL's centre-sampling
result differs from our (exact) gauss result. The first call of each model (numba cache load, or compile
with a cold cache) is reported separately.

Run:  .venv/bin/python benchmarks/discretize.py [--repeats 7] [--quick]
"""

from __future__ import annotations

import argparse
import gc
import os
import statistics
import subprocess
import sys
import tempfile
import time
import tracemalloc
from collections.abc import Callable
from typing import Any

import numpy as np
import shapely
from rasterio.features import rasterize
from rasterio.transform import Affine

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from mrm.core.grids import PixelSet
from mrm.core.models import Model
from mrm.geometry.discretize import discretize

MODELS = Model.names()

PEER_OF = {"standard": False, "supercover": True, "gauss": False}  # GDAL all_touched closest to each model


#: Per-vertex radius noise of each shape family (relative to the mean radius).
NOISE = {"blob": 0.01, "urchin": 0.15}


def noisy_star(n: int, size: int, seed: int, snap: bool = False, family: str = "blob") -> shapely.Polygon:
    """A star-shaped polygon with ``n`` vertices filling ~98 % of a size² grid.

    Its radius is a smooth random curve plus independent per-vertex noise: ±1 % for a "blob" (a wobbly
    outline), ±15 % for an "urchin" (every vertex a spike: long edges whose boxes overlap, the hard case
    for scanline fills and for GEOS's validity check).
    """
    rng = np.random.default_rng(seed)
    ang = np.sort(rng.uniform(0.0, 2 * np.pi, n))
    smooth = sum(rng.uniform(0.02, 0.08) * np.sin(k * ang + rng.uniform(0, 6.3)) for k in (2, 3, 5, 7))
    radius = 0.75 + smooth + rng.uniform(-NOISE[family], NOISE[family], n)
    radius *= 0.49 * (size - 1) / radius.max()
    c = (size - 1) / 2
    pts = np.c_[c + radius * np.cos(ang), c + radius * np.sin(ang)]
    if snap:
        pts = np.round(pts)
    poly = shapely.Polygon(pts)
    if not poly.is_valid:  # rare (snapping can fold two close vertices): try another draw
        return noisy_star(n, size, seed + 7919, snap, family)
    return poly


def gdal(poly: shapely.Polygon, size: int, all_touched: bool) -> np.ndarray:
    """GDAL's raster of ``poly`` on our grid: pixel (x, y) centred at integers, row 0 = y = size − 1."""
    out = np.zeros((size, size), dtype=np.uint8)
    transform = Affine(1.0, 0.0, -0.5, 0.0, -1.0, size - 0.5)
    return rasterize([(poly, 1)], out=out, transform=transform, all_touched=all_touched)


def median_time(f: Callable[[], Any], repeats: int) -> float:
    times = []
    for _ in range(repeats):
        gc.collect()
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def peak_memory(f: Callable[[], Any]) -> int:
    gc.collect()
    tracemalloc.start()
    try:
        f()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def as_image(ps: PixelSet, size: int) -> np.ndarray:
    return ps.to_array((0, 0, size - 1, size - 1))[::-1]


COLD_SNIPPET = """
import time, numpy as np, shapely
t0 = time.perf_counter()
from mrm.geometry.discretize import discretize
t1 = time.perf_counter()
out = []
a = np.linspace(0, 6.28, 100, endpoint=False)
poly = shapely.Polygon(np.c_[20 * np.cos(a), 20 * np.sin(a)] + 0.1)  # >= 64 vertices: the sweep runs too
for m in ("standard", "supercover", "gauss"):
    t = time.perf_counter()
    discretize(poly, m)
    out.append(f"{m} {time.perf_counter() - t:.2f} s")
print(f"import {t1 - t0:.2f} s; first calls: " + ", ".join(out))
"""


def first_call_report() -> None:
    root = os.path.join(os.path.dirname(__file__), "..")
    env = dict(os.environ, PYTHONPATH=root)
    warm = subprocess.run(
        [sys.executable, "-c", COLD_SNIPPET], env=env, capture_output=True, text=True, cwd=root
    )
    with tempfile.TemporaryDirectory() as cache:
        env["NUMBA_CACHE_DIR"] = cache
        cold = subprocess.run(
            [sys.executable, "-c", COLD_SNIPPET], env=env, capture_output=True, text=True, cwd=root
        )
    print(f"first call, numba cache warm : {warm.stdout.strip() or warm.stderr.strip()[-300:]}")
    print(f"first call, numba cache cold : {cold.stdout.strip() or cold.stderr.strip()[-300:]}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--quick", action="store_true", help="only the 512² and 2048² grids")
    args = parser.parse_args()
    repeats = max(5, args.repeats)

    first_call_report()
    sizes = (512, 2048) if args.quick else (512, 2048, 4096)
    cases = [(fam, n, s, False) for fam in NOISE for s in sizes for n in (50, 500, 5000)]
    cases.append(("blob", 500, sizes[-1], True))  # vertices snapped to pixel centres: ties everywhere
    cases.append(("urchin", 500, sizes[-1], True))

    head = (
        f"{'shape':>6} {'vertices':>8} {'grid':>6} {'snap':>4} | {'GDAL':>7} {'GDAL-AT':>7} | "
        f"{'standard':>8} {'ratio':>5} | {'supercov':>8} {'ratio':>5} | {'gauss':>7} {'ratio':>5} | "
        f"{'peak MB ours/GDAL':>17} | {'gauss≠GDAL':>10} {'sup≠GDAL-AT':>11}"
    )
    print(f"\nmedian of {repeats} runs, milliseconds; ratio = ours / GDAL (all_touched=True for supercover)")
    print(head)
    print("-" * len(head))
    worst = 0.0
    for family, n, size, snap in cases:
        poly = noisy_star(n, size, seed=n + size, snap=snap, family=family)
        t_gdal = {
            at: median_time(lambda at=at, p=poly, s=size: gdal(p, s, at), repeats) for at in (False, True)
        }
        ours = {m: median_time(lambda m=m, p=poly: discretize(p, m), repeats) for m in MODELS}
        mem_ours = max(peak_memory(lambda m=m, p=poly: discretize(p, m)) for m in MODELS)
        mem_gdal = peak_memory(lambda p=poly, s=size: gdal(p, s, False))
        gauss_img = as_image(discretize(poly, "gauss"), size)
        sup_img = as_image(discretize(poly, "supercover"), size)
        diff_gauss = int(np.count_nonzero(gauss_img != gdal(poly, size, False).astype(bool)))
        diff_sup = int(np.count_nonzero(sup_img != gdal(poly, size, True).astype(bool)))
        cells = []
        for m in MODELS:
            ratio = ours[m] / t_gdal[PEER_OF[m]]
            worst = max(worst, ratio)
            cells.append(f"{ours[m] * 1e3:8.2f} {ratio:5.2f}")
        print(
            f"{family:>6} {n:>8} {size:>5}² {'yes' if snap else 'no':>4} | "
            f"{t_gdal[False] * 1e3:7.2f} {t_gdal[True] * 1e3:7.2f} | "
            + " | ".join(cells)
            + f" | {mem_ours / 2**20:7.1f} / {mem_gdal / 2**20:7.1f} | {diff_gauss:>10} {diff_sup:>11}"
        )
    print(f"\nworst ratio ours/GDAL: {worst:.2f} (target ≤ 2)")


if __name__ == "__main__":
    main()
