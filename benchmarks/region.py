"""Benchmark: region extraction (components, holes, crack chains, label image) against GDAL and OpenCV.

Compares, on the same binary masks up to 4096²:

- ours:     ``mrm.reps.region.region_of(PixelSet(mask))`` — 4-components with pixel counts and boxes,
            holes with theirs, every crack ring as a Freeman chain;
- ours+lab: the same, then ``.labels``, the component label image (painted lazily from the chains);
- rasterio: ``rasterio.features.shapes(mask)`` (GDAL polygonize, 4-connected), generator fully consumed;
- cv2:      ``cv2.findContours(mask, RETR_CCOMP, CHAIN_APPROX_NONE)`` (8-connected objects, pixel-centre
            contours; the fastest peer, given for scale).

Times are medians of ``--repeat`` runs in this process (numba compilation/cache loading is measured once,
apart). Peak memory is measured in a fresh process per (method, mask): the peak resident set size while
running the method once minus the resident size just before (the peak is reset through
/proc/self/clear_refs; for ours a warm-up call on a tiny mask comes first so that compilation does not count).

Usage: ``.venv/bin/python benchmarks/region.py [--sizes 1024,4096] [--repeat 5] [--no-memory]``
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)


# ---------------------------------------------------------------------------------------------- masks


def _upscale(img: np.ndarray, n: int) -> np.ndarray:
    """Nearest-neighbour rescale of a boolean image to fit an n×n box, centred on an n×n canvas."""
    f = min(n / img.shape[0], n / img.shape[1])
    h, w = int(img.shape[0] * f), int(img.shape[1] * f)
    big = img[(np.arange(h) / f).astype(int)][:, (np.arange(w) / f).astype(int)]
    out = np.zeros((n, n), bool)
    r0, c0 = (n - h) // 2, (n - w) // 2
    out[r0 : r0 + h, c0 : c0 + w] = big
    return out


def make_masks(n: int) -> dict[str, np.ndarray]:
    import skimage.data
    from skimage.filters import threshold_otsu
    from skimage.transform import resize

    rng = np.random.default_rng(12345)
    y, x = np.ogrid[0:n, 0:n]
    disk = (x - n / 2) ** 2 + (y - n / 2) ** 2 < (0.45 * n) ** 2
    for _ in range(60):  # round holes, some with an island inside
        cx, cy = rng.uniform(0.25 * n, 0.75 * n, 2)
        r = rng.uniform(0.002, 0.02) * n
        d2 = (x - cx) ** 2 + (y - cy) ** 2
        disk &= d2 >= r * r
        if rng.random() < 0.3:
            disk |= d2 < (0.4 * r) ** 2
    horse = _upscale(~skimage.data.horse()[::-1], n)
    coins_img = skimage.data.coins()[::-1]
    coins = _upscale(coins_img > threshold_otsu(coins_img), n)
    field = resize(rng.random((64, 64)), (n, n), order=3, mode="reflect", anti_aliasing=False)
    blobs = field > 0.5
    noise = rng.random((n, n)) < 0.5
    return {"disk+holes": disk, "horse": horse, "coins-otsu": coins, "blobs": blobs, "noise": noise}


# ---------------------------------------------------------------------------------------------- methods


def method(name: str) -> tuple[Callable[[np.ndarray], object], Callable[[np.ndarray], object]]:
    """Return (prepare, run) for a method: prepare converts the mask outside the timing."""
    if name == "ours":
        from mrm.core.grids import PixelSet
        from mrm.reps.region import region_of

        return PixelSet, region_of  # type: ignore[return-value]
    if name == "ours+lab":
        from mrm.core.grids import PixelSet
        from mrm.reps.region import region_of

        return PixelSet, lambda ps: region_of(ps).labels  # type: ignore[return-value]
    if name == "rasterio":
        from rasterio.features import shapes

        def run_rio(u: np.ndarray) -> int:
            return sum(1 for _ in shapes(u))

        return lambda m: m.astype(np.uint8), run_rio
    if name == "cv2":
        import cv2

        def run_cv(u: np.ndarray) -> object:
            return cv2.findContours(u, cv2.RETR_CCOMP, cv2.CHAIN_APPROX_NONE)

        return lambda m: m.astype(np.uint8), run_cv
    raise ValueError(name)


METHODS = ("ours", "ours+lab", "rasterio", "cv2")


def warm_up() -> float:
    """First call of ours on a tiny mask: numba compilation or cache loading. Returns seconds."""
    prepare, run = method("ours+lab")
    t = time.perf_counter()
    run(prepare(np.random.default_rng(0).random((16, 16)) < 0.5))
    return time.perf_counter() - t


def _status_kib(field: str) -> int:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    raise KeyError(field)


def child(name: str, path: str) -> None:
    """Run one method once on a saved mask; print the peak RSS growth in MiB."""
    mask = np.load(path)
    prepare, run = method(name)
    if name.startswith("ours"):
        warm_up()
    arg = prepare(mask)
    try:
        with open("/proc/self/clear_refs", "w") as f:  # reset the peak RSS (VmHWM) to the current RSS
            f.write("5")
        base = _status_kib("VmRSS")
        run(arg)
        peak = _status_kib("VmHWM")
    except OSError:  # not Linux: the lifetime peak, which may hide a method using little memory
        base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        run(arg)
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    print((peak - base) / 1024.0)


def peak_memory(name: str, path: str) -> float:
    out = subprocess.run(
        [sys.executable, os.path.abspath(__file__), "--child", name, path],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "PYTHONPATH": ROOT},
    )
    return float(out.stdout.strip().splitlines()[-1])


def median_time(run: Callable[[object], object], arg: object, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        run(arg)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="1024,4096")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--no-memory", action="store_true")
    ap.add_argument("--skip-noise-above", type=int, default=2048, help="peers take minutes on big noise")
    ap.add_argument("--child", nargs=2, metavar=("METHOD", "NPY"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(*args.child)
        return

    from mrm.core.grids import PixelSet
    from mrm.reps.region import region_of

    print(f"first call of region_of + labels (numba compile or cache load): {warm_up() * 1000:.0f} ms")
    print(f"times: median of {args.repeat} runs; memory: peak RSS growth in a fresh process (MiB)\n")
    head = (
        f"{'mask':<11} {'size':>6} {'comps':>7} {'holes':>6} |"
        f" {'ours':>7} {'+lab':>7} {'rio':>7} {'cv2':>7} ms |"
        f" {'ours/rio':>8} {'+lab/rio':>8} {'ours/cv2':>8} |"
        f" {'ours':>5} {'+lab':>5} {'rio':>5} {'cv2':>5} MiB"
    )
    print(head)
    print("-" * len(head))
    tmp = tempfile.mkdtemp(prefix="mrm-bench-region-")
    for n in (int(s) for s in args.sizes.split(",")):
        for name, mask in make_masks(n).items():
            if name == "noise" and n > args.skip_noise_above:
                continue
            reg = region_of(PixelSet(mask))
            t = {}
            for m in METHODS:
                prepare, run = method(m)
                t[m] = median_time(run, prepare(mask), args.repeat)
            mem = {m: float("nan") for m in METHODS}
            if not args.no_memory:
                path = os.path.join(tmp, f"{name}-{n}.npy")
                np.save(path, mask)
                mem = {m: peak_memory(m, path) for m in METHODS}
                os.remove(path)
            print(
                f"{name:<11} {n:>6} {reg.n_components:>7} {reg.n_holes:>6} |"
                f" {t['ours'] * 1e3:>7.1f} {t['ours+lab'] * 1e3:>7.1f} {t['rasterio'] * 1e3:>7.1f}"
                f" {t['cv2'] * 1e3:>7.1f}    |"
                f" {t['ours'] / t['rasterio']:>8.3f} {t['ours+lab'] / t['rasterio']:>8.3f}"
                f" {t['ours'] / t['cv2']:>8.2f} |"
                f" {mem['ours']:>5.0f} {mem['ours+lab']:>5.0f} {mem['rasterio']:>5.0f} {mem['cv2']:>5.0f}",
                flush=True,
            )
    os.rmdir(tmp)


if __name__ == "__main__":
    main()
