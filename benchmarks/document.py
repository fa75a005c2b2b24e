"""Benchmark: the document model — project files, undo memory, edit-to-fresh latency.

1. **Save / load** of a project with 100 discrete objects holding 10 million pixels in total (discs of about
   100,000 pixels with random holes), as ``dumps`` + atomic write and ``read_project`` + ``to_document``
   (target ≤ 1 s each). Peer: ``np.savez`` / ``np.load`` of the same cropped masks (raw uncompressed arrays,
   no validation) — the cost of just moving the bits.
2. **Undo memory** after one 1,000-dab brush stroke (a disc of radius 8 dragged over a 2048² object),
   as the history counts it (``History.byte_size``) and as ``tracemalloc`` sees it, against the 1,000 mask
   copies a snapshot history would keep.
3. **Edit → four representations fresh** for a 500-vertex polygon spanning a 1024² grid: push a
   ``MoveVertex`` and compute the discrete (D), region and analytical representations (the Euclidean one is
   the source itself) — target ≤ 30 ms median. Peer: ``cv2.fillPoly`` of the same polygon on a 1024² grid
   (rasterisation only, pixel centres, not exact), and rasterio's ``rasterize`` when available.

Medians of ``--repeat`` runs; numba compilation is done in a warm-up outside the timings.

Usage: ``.venv/bin/python benchmarks/document.py [--repeat 5] [--only save,undo,edit]``
"""

from __future__ import annotations

import argparse
import gc
import os
import statistics
import sys
import tempfile
import time
import tracemalloc
from collections.abc import Callable
from pathlib import Path

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)

from shapely.geometry import Polygon  # noqa: E402

from mrm.core.grids import PixelSet  # noqa: E402
from mrm.document import Document  # noqa: E402
from mrm.document.commands import AddObject  # noqa: E402
from mrm.document.edits import MoveVertex, PaintPixels  # noqa: E402
from mrm.io.project import dumps, read_project, save_project  # noqa: E402


def median_time(fn: Callable[[], object], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        gc.collect()
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def disc(r: float) -> np.ndarray:
    n = int(np.ceil(r))
    y, x = np.ogrid[-n : n + 1, -n : n + 1]
    return x * x + y * y <= r * r


# ---------------------------------------------------------------------------------------------- 1. files
def big_project(n_objects: int = 100, total: int = 10_000_000) -> Document:
    rng = np.random.default_rng(1)
    doc = Document()
    per = total / n_objects
    r = float(np.sqrt(per / np.pi))
    objs = []
    for k in range(n_objects):
        m = disc(r * 1.02)
        holes = rng.integers(0, m.shape[0], size=(30, 2))
        for cy, cx in holes:
            m[max(0, cy - 4) : cy + 4, max(0, cx - 4) : cx + 4] = False
        objs.append(doc.make_object(PixelSet(m, (int(k * 400), int(rng.integers(-5000, 5000)))), f"disc {k}"))
    doc.reset(objs)
    return doc


def bench_files(repeat: int) -> None:
    doc = big_project()
    pixels = sum(o.source.count for o in doc)
    print(f"[files] project: {len(doc)} objects, {pixels:,} pixels")
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "big.mrm"
        t_save = median_time(lambda: save_project(doc, path), repeat)
        size = path.stat().st_size
        t_dumps = median_time(lambda: dumps(doc), repeat)
        t_load = median_time(lambda: read_project(path).to_document(path), repeat)
        back = read_project(path).to_document(path)
        assert back.objects == doc.objects
        masks = {f"m{o.id}": np.asarray(o.source.mask) for o in doc}
        npz = Path(d) / "big.npz"
        t_np_save = median_time(lambda: np.savez(npz, **masks), repeat)
        t_np_load = median_time(lambda: {k: v for k, v in np.load(npz).items()}, repeat)
        npz_bytes = npz.stat().st_size
    print(f"  file size              {size / 1e6:8.2f} MB   (npz peer {npz_bytes / 1e6:.2f} MB)")
    print(f"  save (dumps+atomic)    {t_save * 1e3:8.1f} ms   target ≤ 1000 ms")
    print(f"    of which dumps       {t_dumps * 1e3:8.1f} ms")
    print(f"  load (parse+validate)  {t_load * 1e3:8.1f} ms   target ≤ 1000 ms")
    print(f"  peer np.savez          {t_np_save * 1e3:8.1f} ms   ratio ours/peer {t_save / t_np_save:6.2f}")
    print(f"  peer np.load           {t_np_load * 1e3:8.1f} ms   ratio ours/peer {t_load / t_np_load:6.2f}")


# ------------------------------------------------------------------------------------------- 2. undo memory
def bench_undo_memory() -> None:
    n = 2048
    doc = Document(max_undo_bytes=2**40)
    rng = np.random.default_rng(2)
    base = PixelSet(rng.random((n, n)) < 0.5, (0, 0))
    o = doc.make_object(base, "canvas")
    doc.push(AddObject(o))
    doc.history.clear()
    brush = disc(8.0)
    t = np.linspace(0, 6 * np.pi, 1000)
    xs = (n / 2 + 0.45 * n * np.cos(t) * np.cos(t / 3)).astype(int)
    ys = (n / 2 + 0.45 * n * np.sin(t)).astype(int)
    gc.collect()
    tracemalloc.start()
    before = tracemalloc.get_traced_memory()[0]
    t0 = time.perf_counter()
    with doc.history.macro("Brush stroke"):
        for x, y in zip(xs.tolist(), ys.tolist(), strict=True):
            doc.push(PaintPixels(o.id, PixelSet(brush, (x - 8, y - 8)), value=bool(x % 2)))
    elapsed = time.perf_counter() - t0
    gc.collect()
    after = tracemalloc.get_traced_memory()[0]
    tracemalloc.stop()
    counted = doc.history.byte_size()
    current = doc.get(o.id).source.mask.nbytes
    copies = 1000 * current
    print(f"[undo] 1,000-dab stroke on a {n}² object: {doc.history.count} undo step")
    print(f"  history (byte_size)    {counted / 1e6:8.3f} MB")
    print(
        f"  retained (tracemalloc) {(after - before - current) / 1e6:8.3f} MB "
        f"beyond the new mask of {current / 1e6:.2f} MB"
    )
    print(
        f"  snapshot peer          {copies / 1e9:8.3f} GB (1,000 mask copies)   "
        f"ratio ours/peer {counted / copies:.2e}"
    )
    print(f"  time per dab           {elapsed / 1000 * 1e3:8.2f} ms")
    doc.undo()
    assert doc.get(o.id).source == base
    print("  undo restores the canvas exactly: yes")


# ------------------------------------------------------------------------------------------ 3. edit latency
def star(n_vertices: int, size: int, phase: float = 0.0) -> Polygon:
    rng = np.random.default_rng(3)
    a = np.linspace(0, 2 * np.pi, n_vertices, endpoint=False) + phase
    r = size * (0.30 + 0.15 * rng.random(n_vertices))
    c = size / 2
    return Polygon(np.stack([c + r * np.cos(a), c + r * np.sin(a)], axis=1))


def bench_edit(repeat: int) -> None:
    from mrm.document.derive import REPS

    size = 1024
    poly = star(500, size)
    doc = Document()
    o = doc.make_object(poly, "star")
    doc.push(AddObject(o))
    available = []
    for what in REPS:  # warm-up: numba compilation and cache loading, outside the timings
        try:
            doc.derived(o.id).get(what)
            available.append(what)
        except ImportError as e:
            print(f"  ({what}: not available yet: {e})")
    coords = np.asarray(poly.exterior.coords)[:-1]
    k = [0]

    def edit() -> None:
        k[0] += 1
        i = 7
        x, y = coords[i]
        doc.push(MoveVertex(o.id, (0, 0, i), (x + 0.25 * (k[0] % 3), y + 0.125 * (k[0] % 5))))
        d = doc.derived(o.id)
        for what in available:
            d.get(what)

    steps = {}
    for what in available:

        def one(what: str = what) -> None:
            k[0] += 1
            x, y = coords[7]
            doc.push(MoveVertex(o.id, (0, 0, 7), (x + 0.25 * (k[0] % 3), y)))
            d = doc.derived(o.id)
            for w in available[: available.index(what) + 1]:
                d.get(w)

        steps[what] = median_time(one, repeat * 4)
    total = median_time(edit, repeat * 4)
    print(f"[edit] 500-vertex polygon on a {size}² grid, {doc.derived(o.id).get('discrete').count:,} pixels")
    prev = 0.0
    for what in available:
        print(f"  up to {what:<11}      {steps[what] * 1e3:8.2f} ms (+{(steps[what] - prev) * 1e3:.2f})")
        prev = steps[what]
    print(f"  edit → all fresh       {total * 1e3:8.2f} ms   target ≤ 30 ms   ({', '.join(available)})")
    try:
        import cv2

        img = np.zeros((size, size), np.uint8)
        pts = np.round(coords).astype(np.int32).reshape(-1, 1, 2)
        t_cv = median_time(lambda: cv2.fillPoly(img, [pts], 1), repeat * 4)
        print(
            f"  peer cv2.fillPoly      {t_cv * 1e3:8.2f} ms   ratio ours/peer {total / t_cv:6.1f} "
            "(rasterisation only)"
        )
    except ImportError:
        print("  peer cv2: not installed")
    try:
        from rasterio.features import rasterize
        from rasterio.transform import Affine

        tr = Affine(1, 0, -0.5, 0, 1, -0.5)
        t_rio = median_time(lambda: rasterize([poly], out_shape=(size, size), transform=tr), repeat * 4)
        print(
            f"  peer rasterio          {t_rio * 1e3:8.2f} ms   ratio ours/peer {total / t_rio:6.1f} "
            "(rasterisation only)"
        )
    except ImportError:
        print("  peer rasterio: not installed")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--only", default="files,undo,edit")
    args = ap.parse_args()
    only = set(args.only.split(","))
    if "files" in only:
        bench_files(args.repeat)
    if "undo" in only:
        bench_undo_memory()
    if "edit" in only:
        bench_edit(args.repeat)


if __name__ == "__main__":
    main()
