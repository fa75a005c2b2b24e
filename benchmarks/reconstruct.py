"""Benchmark of the reversible continuation R against its peers: vertices, pixels wrong, speed.

Shapes: the horse silhouette, Otsu-thresholded camera, coins, page and text (scikit-image data), and disks
of radius 10 to 1000 centred at (1/7, 2/9). For each: the greedy standard-DSS count of the crack chains
(the yardstick), R's vertices under each model, and three peers — potrace's polygon (``potracer``,
turdsize 0, alphamax 0, one vertex per corner segment), OpenCV's approxPolyDP at 0.5 on its contours, GDAL's
staircase (rasterio.features.shapes) — with the number of pixels each one gets wrong when discretized back
with our exact D (|D(P) Δ A|) under every model.

Speed: R on the horse, camera, coins, page, text, 1024² 50 % noise and 4096² blobs against
rasterio.features.shapes on the same mask (medians of several runs, same process), with the time per boundary
step (crack linel); the time per step on the horse upscaled from 1024² to 8192²; the peak memory each adds
(fresh processes); and the first-call cost of the kernels in a fresh process: cold (empty numba cache) and
warm (cache on disk).

Run: ``.venv/bin/python benchmarks/reconstruct.py`` (``--quick`` skips the two largest disks and potrace on
big inputs; ``--rings`` adds the per-ring excess over the window bound; ``--starts`` what the minimum-link
windows reach from many starts per ring; ``--only memory`` (repeatable) runs
one section: vertices, speed, scaling, memory, labels, first-call; ``--help`` lists them).
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from mrm.core.grids import PixelSet
from mrm.core.models import Model
from mrm.geometry.discretize import discretize
from mrm.geometry.dss.segmentation import chain_points, greedy_segmentation
from mrm.geometry.reconstruct import reconstruct
from mrm.reps.region import region_of
from mrm.reps.summary import count_vertices

MODELS = Model.names()

QUICK = "--quick" in sys.argv


def median_ms(f: Any, repeats: int = 7) -> float:
    f()
    ts = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        ts.append(time.perf_counter() - t)
    return float(np.median(ts)) * 1e3


# ---------------------------------------------------------------------------------------------- shapes


def disk(r: float) -> PixelSet:
    n = int(r) + 3
    yy, xx = np.mgrid[-n : n + 1, -n : n + 1]
    return PixelSet((xx - 1 / 7) ** 2 + (yy - 2 / 9) ** 2 <= r * r, (-n, -n))


def shapes() -> list[tuple[str, PixelSet]]:
    import skimage.data
    from skimage.filters import threshold_otsu

    def otsu(img: np.ndarray) -> np.ndarray:
        return np.asarray(img > threshold_otsu(img))

    out = [
        ("horse", PixelSet(~skimage.data.horse()[::-1])),
        ("camera", PixelSet(otsu(skimage.data.camera())[::-1])),
        ("coins", PixelSet(otsu(skimage.data.coins())[::-1])),
        ("page", PixelSet(otsu(skimage.data.page())[::-1])),
        ("text", PixelSet(otsu(skimage.data.text())[::-1])),
    ]
    radii = (10, 20, 50, 100, 200) if QUICK else (10, 20, 50, 100, 200, 500, 1000)
    out += [(f"disk {r}", disk(r)) for r in radii]
    return out


def corner_count(ps: PixelSet) -> int:
    """Vertices of the staircase V(A): the turns of the crack rings (the gauss safety net)."""
    total = 0
    for ch in region_of(ps).boundary_chains:
        c = ch.code_array()
        total += int(np.count_nonzero(c != np.roll(c, 1)))
    return total


def greedy_count(ps: PixelSet) -> int:
    return sum(
        len(greedy_segmentation(chain_points(ch.start, ch.codes), closed=True))
        for ch in region_of(ps).boundary_chains
    )


# ---------------------------------------------------------------------------------------------- peers
# Every peer returns (geometry in plane coordinates, vertex count). Potrace's polygon is counted by its
# corners (one per curve segment); drawn as a polyline through its segments' end points too (edge midpoints)
# it has twice as many points.


def _polys_of(parts: list[Any]) -> Any:
    polys: list[Polygon] = []
    for g in parts:
        if g.is_empty:
            continue
        if isinstance(g, Polygon):
            polys.append(g)
        elif isinstance(g, MultiPolygon):
            polys.extend(g.geoms)
        elif hasattr(g, "geoms"):
            polys.extend(p for p in g.geoms if isinstance(p, Polygon))
    return MultiPolygon(polys) if polys else Polygon()


def peer_potrace(ps: PixelSet) -> tuple[Any, int]:
    import potrace

    # potracer traces the values below its black level: hand it the complement.
    bm = potrace.Bitmap(~np.asarray(ps.mask))
    curves = bm.trace(turdsize=0, alphamax=0.0, opticurve=False)
    x0, y0 = ps.origin
    rings = []
    n = 0
    for c in curves:
        pts = [(s.c.x, s.c.y) for s in c.segments]
        n += len(pts)
        if len(pts) >= 3:
            rings.append(Polygon([(x0 - 0.5 + u, y0 - 0.5 + v) for u, v in pts]))
    # nesting by parity (even-odd), as potrace's own renderers do
    geom = shapely.symmetric_difference_all([shapely.make_valid(r) for r in rings]) if rings else Polygon()
    return geom, n


def peer_opencv(ps: PixelSet, eps: float = 0.5) -> tuple[Any, int]:
    import cv2

    m = np.ascontiguousarray(ps.mask.astype(np.uint8))
    contours, hier = cv2.findContours(m, cv2.RETR_CCOMP, cv2.CHAIN_APPROX_NONE)
    x0, y0 = ps.origin
    approx = [
        cv2.approxPolyDP(c, eps, True)[:, 0, :].astype(np.float64) + np.array([x0, y0]) for c in contours
    ]
    n = sum(a.shape[0] for a in approx)
    polys = []
    if hier is not None:
        for i, h in enumerate(hier[0]):
            if h[3] != -1 or approx[i].shape[0] < 3:
                continue
            holes = []
            j = h[2]
            while j != -1:
                if approx[j].shape[0] >= 3:
                    holes.append(approx[j])
                j = hier[0][j][0]
            polys.append(shapely.make_valid(Polygon(approx[i], holes)))
    return _polys_of(polys), n


def peer_rasterio(ps: PixelSet) -> tuple[Any, int]:
    import rasterio.features

    m = ps.mask.astype(np.uint8)
    x0, y0 = ps.origin
    polys = []
    n = 0
    for geo, _v in rasterio.features.shapes(m, mask=ps.mask, connectivity=4):
        rings = [np.asarray(r, dtype=np.float64) + np.array([x0 - 0.5, y0 - 0.5]) for r in geo["coordinates"]]
        n += sum(r.shape[0] - 1 for r in rings)
        polys.append(shapely.make_valid(Polygon(rings[0], rings[1:])))
    return _polys_of(polys), n


def wrong(geom: Any, ps: PixelSet, model: str) -> int:
    if geom.is_empty:
        return len(ps)
    return len(discretize(geom, model) ^ ps)


# ---------------------------------------------------------------------------------------------- tables


def table(title: str, header: list[str], rows: list[list[Any]]) -> None:
    print(f"\n{title}")
    cells = [header] + [[f"{v:.3f}" if isinstance(v, float) else str(v) for v in r] for r in rows]
    widths = [max(len(c[i]) for c in cells) for i in range(len(header))]
    for k, c in enumerate(cells):
        print("  ".join(v.rjust(w) for v, w in zip(c, widths, strict=True)))
        if k == 0:
            print("  ".join("-" * w for w in widths))


def compactness(items: list[tuple[str, PixelSet]]) -> None:
    rows = []
    ratios: dict[str, list[float]] = {m: [] for m in MODELS}
    peer_rows = []
    potrace_rows = []
    for name, ps in items:
        g = greedy_count(ps)
        row: list[Any] = [name, len(ps), g]
        counts = {}
        for model in MODELS:
            r = reconstruct(ps, model)
            v = count_vertices(r)
            assert discretize(r, model) == ps, (name, model)
            ratios[model].append(v / g)
            counts[model] = v
            row += [v, v / g]
        row.append(row[-2] / corner_count(ps))
        rows.append(row)
        if not name.startswith("disk"):
            _geom, npt_ = peer_potrace(ps)
            potrace_rows.append([name, npt_, *[c for m in MODELS for c in (counts[m], counts[m] / npt_)]])
        big = len(ps) > 400_000
        peers = [("approxPolyDP 0.5", peer_opencv), ("rasterio/GDAL", peer_rasterio)]
        if not (QUICK and big) and len(ps) < 2_000_000:
            peers.insert(0, ("potrace alphamax=0", peer_potrace))
        for pname, fn in peers:
            geom, nv = fn(ps)
            peer_rows.append([name, pname, nv, nv / g, *[wrong(geom, ps, m) for m in MODELS]])
    table(
        "R: vertices per model against the greedy DSS count of the crack chains (0 pixels wrong, checked)",
        ["shape", "pixels", "greedy", *[c for m in MODELS for c in (m, "ratio")], "gauss/staircase"],
        rows,
    )
    print("median ratio to greedy: " + ", ".join(f"{m} {np.median(ratios[m]):.3f}" for m in MODELS))
    table(
        "R against potrace's polygon (turdsize 0, alphamax 0, one vertex per corner segment; target <= 1.10)",
        ["image", "potrace", *[c for m in MODELS for c in (m, "ratio")]],
        potrace_rows,
    )
    table(
        "peers: vertices and pixels wrong when discretized back with the exact D",
        ["shape", "peer", "vertices", "ratio", *[f"wrong {m}" for m in MODELS]],
        peer_rows,
    )


def excess_by_ring(items: list[tuple[str, PixelSet]]) -> None:
    """Where R's vertices exceed the window bound (fewest windows covering one lap, ADR 0022), per ring class.

    The bound is a lower bound for every ring of the corridor, so vertices minus bound is what any better
    vertex placement (e.g. a minimum-link path) could still gain, split into small corridors
    (<= 12 and <= 24 pieces, searched by ``small_polygon``), rings relinked (<= 48 vertices, ``_RELINK_MAX``)
    and the rest.
    """
    from mrm.geometry.reconstruct import reconstruct_detailed
    from mrm.geometry.reconstruct._small_search import window_bound

    classes = ("pieces <= 12", "pieces <= 24", "vertices <= 48", "vertices > 48")
    rows = []
    for name, ps in items:
        for model in MODELS:
            acc = {c: [0, 0, 0] for c in classes}
            for r in reconstruct_detailed(ps, model).rings:
                n, v = r.reach.size, len(r.vertices)
                bound = max(3, window_bound(np.ascontiguousarray(r.reach)))
                c = classes[0 if n <= 12 else 1 if n <= 24 else 2 if v <= 48 else 3]
                acc[c][0] += 1
                acc[c][1] += v
                acc[c][2] += v - bound
            total = sum(a[1] for a in acc.values())
            rows.append([name, model, total, *[f"{a[0]}: +{a[2]}" for a in acc.values()]])
    table(
        "R's vertices above the window bound, per ring class (rings: excess)",
        ["image", "model", "vertices", *classes],
        rows,
    )


def fewest_from_starts(items: list[tuple[str, PixelSet]], per_ring: int = 200) -> None:
    """How many vertices fewer than R the minimum-link windows reach from many starts, per image and model.

    For every ring of four pieces or more, the forward pass of the minimum-link search (Suri's windows,
    ``_minlink._forward``, without room, so optimistic: a proposal still has to snap and verify) from five
    points in each of up to ``per_ring`` pieces; the fewest windows any start needs, against R's vertices.
    R runs the search from one start (vertex 0 of its ring): this says what other starts could still gain.
    """
    from mrm.geometry import reconstruct as rmod
    from mrm.geometry.reconstruct import _minlink as ml

    spots = ((0.5, 0.5), (0.25, 0.25), (0.75, 0.75), (0.25, 0.75), (0.75, 0.25))
    rows = []
    for name, ps in items:
        for model in ("standard", "gauss"):  # supercover has the standard polygons
            run = rmod._run(ps, model, tables=True)
            cor = run.corridor
            pieces = np.diff(cor.poff)
            verts = np.diff(run.roff) - 1  # rings are closed
            searched = ours = fewest = gained = starts = 0
            for k in range(pieces.size):
                if cor.special[k] in (1, 2) or pieces[k] < 4:
                    continue
                a, b = int(cor.poff[k]), int(cor.poff[k + 1])
                rect, gdir, reach = cor.rect[a:b], cor.gdir[a:b], run.reach[a:b]
                sg = ml.shrunk_gates(cor.gp[a:b], cor.gq[a:b])
                best = 1 << 60
                for t in range(0, b - a, max(1, (b - a) // per_ring)):
                    for fx, fy in spots:
                        x = rect[t, 0] + fx * (rect[t, 1] - rect[t, 0])
                        y = rect[t, 2] + fy * (rect[t, 3] - rect[t, 2])
                        kend, _x, _y, last_t, _w = ml._forward(
                            float(x), float(y), t, rect, sg, 0.0, reach, gdir, int(verts[k]) + 2
                        )
                        starts += 1
                        if kend >= 0:
                            best = min(best, kend + 1 + (1 if last_t >= 0 else 0))
                if best < 1 << 60:
                    searched += 1
                    ours += int(verts[k])
                    fewest += min(best, int(verts[k]))
                    gained += int(verts[k] > best)
            total = int(verts.sum())
            rows.append([name, model, total, searched, ours, fewest, gained, total - ours + fewest, starts])
    table(
        "fewest vertices the minimum-link windows reach from many starts (optimistic) against R's",
        [
            "image",
            "model",
            "R",
            "rings searched",
            "R there",
            "fewest there",
            "rings with fewer",
            "R - gain",
            "starts",
        ],
        rows,
    )


def speed_inputs() -> list[tuple[str, np.ndarray]]:
    """The inputs of the speed table (masks, row 0 = lowest y)."""
    import skimage.data
    from skimage.filters import threshold_otsu
    from skimage.transform import resize

    def otsu(img: np.ndarray) -> np.ndarray:
        return np.asarray(img > threshold_otsu(img))[::-1]

    rng = np.random.default_rng(12345)
    out = [("horse 328x400", ~skimage.data.horse()[::-1])]
    out += [(n, otsu(getattr(skimage.data, n)())) for n in ("camera", "coins", "page", "text")]
    out.append(("noise 50% 1024^2", rng.random((1024, 1024)) < 0.5))
    if not QUICK:
        field = resize(rng.random((64, 64)), (4096, 4096), order=3, mode="reflect", anti_aliasing=False)
        out.append(("blobs 4096^2", field > 0.5))
    return out


def boundary_steps(m: np.ndarray) -> int:
    """Linels of the crack rings of a mask (the boundary steps R walks)."""
    from mrm.geometry.topology.cracks import trace_mask

    return int(trace_mask(np.ascontiguousarray(m.view(np.uint8))).codes.size)


def speed() -> None:
    import rasterio.features

    rows = []
    for name, m in speed_inputs():
        ps = PixelSet(m)
        m8 = np.ascontiguousarray(m.astype(np.uint8))
        reps = 3 if m.size > 2_000_000 else 7
        steps = boundary_steps(m)
        t_gdal = median_ms(
            lambda m8=m8, m=m: list(rasterio.features.shapes(m8, mask=m, connectivity=4)), reps
        )
        for model in MODELS:
            t = median_ms(lambda ps=ps, model=model: reconstruct(ps, model), reps)
            rows.append([name, model, t, t_gdal, t / t_gdal, 1e3 * t / steps])
    table(
        "speed (median ms, same process; target R / rasterio <= 1.0)",
        ["input", "model", "R ms", "rasterio.shapes ms", "R / rasterio", "R us/step"],
        rows,
    )


def scaling(sizes: tuple[int, ...] = (1024, 2048, 4096, 8192)) -> None:
    """Time per boundary step on the horse upscaled to n x n (target: within 1.3x from 1024² to 8192²)."""
    import rasterio.features
    import skimage.data
    from skimage.transform import resize

    horse = ~skimage.data.horse()[::-1]
    rows = []
    first: dict[str, float] = {}
    for size in sizes:
        m = resize(horse.astype(np.float32), (size, size), order=0, anti_aliasing=False) > 0.5
        steps = boundary_steps(m)
        ps = PixelSet(m)
        reps = 3 if size <= 2048 else 1
        m8 = np.ascontiguousarray(m.astype(np.uint8))
        t_gdal = median_ms(
            lambda m8=m8, m=m: list(rasterio.features.shapes(m8, mask=m, connectivity=4)), reps
        )
        for who in ("gdal", *MODELS):
            t = t_gdal if who == "gdal" else median_ms(lambda ps=ps, who=who: reconstruct(ps, who), reps)
            us = 1e3 * t / steps
            first.setdefault(who, us)
            rows.append([f"horse {size}^2", who, steps, t, us, us / first[who]])
        del ps, m, m8
    table(
        "time per boundary step, horse upscaled (median ms; target: us/step within 1.3x of 1024^2)",
        ["input", "who", "steps", "ms", "us/step", "vs 1024^2"],
        rows,
    )


_PEAK = """
import sys, numpy as np
sys.path.insert(0, {root!r})
from mrm.core.grids import PixelSet

def kb(key):
    for line in open("/proc/self/status"):
        if line.startswith(key):
            return int(line.split()[1])

def reset_peak():
    # Linux: writing 5 to clear_refs resets the peak resident size (VmHWM) to the current one
    with open("/proc/self/clear_refs", "w") as fh:
        fh.write("5")

m = np.load({path!r})
who = {who!r}
if who == "gdal":
    import rasterio.features
    m8 = np.ascontiguousarray(m.astype(np.uint8))
    list(rasterio.features.shapes(np.zeros((4, 4), np.uint8), connectivity=4))
    for _ in range({earlier}):
        list(rasterio.features.shapes(m8, mask=m, connectivity=4))
    reset_peak(); base = kb("VmRSS")
    list(rasterio.features.shapes(m8, mask=m, connectivity=4))
else:
    from mrm.geometry.reconstruct import reconstruct
    ps = PixelSet(m)
    # load the kernels first: single pixels, and two equal squares (a twin ring, ADR 0036)
    warm = np.zeros((5, 12), dtype=bool)
    warm[np.arange(5), np.arange(5)] = True
    warm[1:3, 6:8] = warm[1:3, 9:11] = True
    reconstruct(PixelSet(warm), who)
    for _ in range({earlier}):
        reconstruct(ps, who)
    reset_peak(); base = kb("VmRSS")
    reconstruct(ps, who)
print(kb("VmHWM") - base)
"""


def peak_memory() -> None:
    """Peak resident memory added by one call (VmHWM after a reset, Linux), in a fresh process (MB).

    Twice: the first call on the mask in that process, and a second one. The first call also pays what a
    process pays once — malloc heaps growing to the working set, and for R the start of its worker thread
    and that thread's own heap — which a long-running application pays only once; both are printed.
    """
    root = str(Path(__file__).resolve().parents[1])
    rows = []
    names = ["camera", "noise 50% 1024^2"] + ([] if QUICK else ["blobs 4096^2"])
    inputs = dict(speed_inputs())
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            path = str(Path(tmp) / "mask.npy")
            np.save(path, np.ascontiguousarray(inputs[name]))
            got: dict[tuple[str, int], float] = {}
            for earlier in (0, 1):
                for who in ("gdal", *MODELS):
                    code = _PEAK.format(root=root, path=path, who=who, earlier=earlier)
                    out = subprocess.run(
                        [sys.executable, "-c", code], capture_output=True, text=True, check=True
                    )
                    got[who, earlier] = int(out.stdout.strip().splitlines()[-1]) / 1024
            for model in MODELS:
                row: list[Any] = [name, model]
                for e in (0, 1):
                    r, g = got[model, e], got["gdal", e]
                    row += [r, g, r / max(g, 1e-9)]
                rows.append(row)
    table(
        "peak memory added by the call (MB, VmHWM - VmRSS in a fresh process; target <= 1.5x GDAL)",
        ["input", "model", "R 1st call", "GDAL 1st", "ratio", "R 2nd call", "GDAL 2nd", "ratio"],
        rows,
    )


def label_maps() -> None:
    """mrm polygonize against GDAL polygonize (+ shapely.coverage_simplify) on a quantized image."""
    import rasterio.features
    import skimage.data

    from mrm.core.grids import LabelMap
    from mrm.geometry.reconstruct.polygonize import polygonize

    img = skimage.data.coins()[::-1][:128, :160]
    labels = (img // 64).astype(np.int32) + 1  # four grey levels, labels 1..4
    lm = LabelMap(labels)
    regions = polygonize(lm)
    t_ours = median_ms(lambda: polygonize(lm), 5) / 1e3  # after a first call (kernels loaded), as GDAL's
    ours_v = sum(count_vertices(r.geometry) for r in regions)

    def burnt(geoms: list[Any], values: list[int]) -> int:
        h, w = labels.shape
        from affine import Affine

        img2 = rasterio.features.rasterize(
            list(zip(geoms, values, strict=True)),
            out_shape=(h, w),
            transform=Affine(1.0, 0.0, -0.5, 0.0, -1.0, h - 0.5),
            dtype="int32",
        )[::-1]
        return int(np.count_nonzero(img2 != labels))

    feats = list(rasterio.features.shapes(labels, connectivity=4))
    t_gdal = median_ms(lambda: list(rasterio.features.shapes(labels, connectivity=4)), 5) / 1e3
    gdal_geoms = [
        Polygon(np.asarray(g["coordinates"][0]) - 0.5, [np.asarray(r) - 0.5 for r in g["coordinates"][1:]])
        for g, _v in feats
    ]
    gdal_vals = [int(v) for _g, v in feats]
    gdal_v = sum(count_vertices(g) for g in gdal_geoms)
    rows = [
        [
            "mrm polygonize (gauss)",
            len(regions),
            ours_v,
            burnt([r.geometry for r in regions], [r.label for r in regions]),
            t_ours * 1e3,
        ],
        ["GDAL polygonize", len(gdal_geoms), gdal_v, burnt(gdal_geoms, gdal_vals), t_gdal * 1e3],
    ]
    for tol in (0.5, 1.0):
        simp = list(shapely.coverage_simplify(np.array(gdal_geoms, dtype=object), tol))
        rows.append(
            [
                f"GDAL + coverage_simplify {tol}",
                len(simp),
                sum(count_vertices(g) for g in simp),
                burnt(simp, gdal_vals),
                float("nan"),
            ]
        )
    table(
        "label map: coins 128x160 quantized to 4 labels (pixels wrong: rasterize with the labels vs the map)",
        ["method", "regions", "vertices", "pixels wrong", "ms"],
        rows,
    )


def first_call() -> None:
    code = (
        "import time; t = time.perf_counter();"
        "import numpy as np;"
        "from mrm.geometry.reconstruct import reconstruct;"
        "from mrm.core.grids import PixelSet;"
        "ps = PixelSet(np.eye(7, dtype=bool) | np.eye(7, dtype=bool)[::-1]);"
        "[reconstruct(ps, m) for m in ('standard', 'gauss')];"
        "print(time.perf_counter() - t)"
    )
    root = Path(__file__).resolve().parents[1]
    rows = []
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache, PYTHONPATH=str(root))
        for label in ("cold (empty numba cache: compile)", "warm (cache on disk: load)"):
            out = subprocess.run(
                [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
            )
            rows.append([label, float(out.stdout.strip().splitlines()[-1])])
    table(
        "first call in a fresh process (import + first reconstruct under two models), seconds",
        ["case", "s"],
        rows,
    )


SECTIONS = ("vertices", "speed", "scaling", "memory", "labels", "first-call")


def main() -> None:
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--quick", action="store_true", help="skip the two largest disks and the biggest inputs"
    )
    parser.add_argument("--rings", action="store_true", help="add the per-ring excess over the window bound")
    parser.add_argument(
        "--starts",
        action="store_true",
        help="add the fewest vertices the minimum-link windows reach from many starts (about 20 s)",
    )
    parser.add_argument(
        "--only", choices=SECTIONS, action="append", help="run only this section (repeatable); all by default"
    )
    args = parser.parse_args()
    only = set(args.only or SECTIONS)
    print(f"load average at start: {os.getloadavg()[0]:.2f} (2-core machine shared with others)")
    if "vertices" in only:
        compactness(shapes())
        if args.rings:
            excess_by_ring([s for s in shapes() if not s[0].startswith("disk")])
        if args.starts:
            fewest_from_starts([s for s in shapes() if not s[0].startswith("disk")])
    if "speed" in only:
        speed()
    if "scaling" in only and not QUICK:
        scaling()
    if "memory" in only:
        peak_memory()
    if "labels" in only:
        label_maps()
    if "first-call" in only:
        first_call()


if __name__ == "__main__":
    main()
