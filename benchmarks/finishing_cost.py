"""What each optional finishing step of R costs and gains: R with one step (or all four) left out.

R's phase 4 (``_kernels.finish_all``) snaps, verifies, prunes and merges every ring. These steps are what
make R exact. Four more steps only make it compact or tidy, and each is guarded by its own condition:

* ``relink``: four vertices relinked into three (``relink_ring``, rings of 6–48 vertices);
* ``small``: the 3-or-4-vertex search of small corridors (``small_polygon``);
* ``minlink``: the minimum-link ring (``minlink_ring``, ADR 0031);
* ``straighten``: every edge moved onto the simplest line its pieces allow (``straighten_ring``).

This script copies ``model/`` to a temporary folder as the ``mrm`` package and rewrites ``finish_all`` there,
so that the environment variable ``MRM_SKIP`` (a bit mask, read when the module is imported) leaves steps
out. Nothing changes in the package itself. Each variant compiles into a numba cache of its own, which takes
about a minute per variant, two at a time. The timing runs then take turns between the variants in fresh
processes, and the medians over the rounds are printed beside GDAL's polygonize
(``rasterio.features.shapes``) measured in the same processes, with the vertex counts against potrace's
polygon (turdsize 0, alphamax 0).

Run: ``.venv/bin/python benchmarks/finishing_cost.py`` (``--rounds N``, default 3).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: The optional steps, their bit in MRM_SKIP, and the line of finish_all that each guard begins with.
STEPS = {
    "relink": (1, "                if 6 <= px.size <= _RELINK_MAX and px.size > wb:\n"),
    "small": (2, "                if px.size > 3 and b - a <= _SMALL_POLY:\n"),
    "minlink": (4, "                if px.size > 4 and b - a > _SMALL_POLY and px.size > wb:\n"),
}
STRAIGHTEN = (
    8,
    "                px, py, pt, ps, pl = straighten_ring(px, py, pt, ps, pl, rc, p, q, g, kk)\n",
)

#: The variants: none left out, each step alone, all four.
VARIANTS = {
    "R": 0,
    "no relink": 1,
    "no small": 2,
    "no minlink": 4,
    "no straighten": 8,
    "none of the four": 15,
}

IMAGES = ("horse", "camera", "coins", "page", "text")
MODELS = ("standard", "gauss")


def patched_copy(dest: Path) -> None:
    """Copy model/ to dest/mrm with the four steps of finish_all guarded by MRM_SKIP."""
    shutil.copytree(ROOT / "model", dest / "mrm", ignore=shutil.ignore_patterns("__pycache__"))
    path = dest / "mrm" / "geometry" / "reconstruct" / "_kernels.py"
    src = path.read_text()
    for bit, line in STEPS.values():
        if src.count(line) != 1:
            raise SystemExit(f"finish_all changed: the guard {line.strip()!r} is not found once in {path}")
        src = src.replace(line, line.replace("if ", f"if not (_SKIP & {bit}) and ", 1))
    bit, line = STRAIGHTEN
    if src.count(line) != 1:
        raise SystemExit(f"finish_all changed: {line.strip()!r} is not found once in {path}")
    src = src.replace(line, f"                if not (_SKIP & {bit}):\n    " + line)
    anchor = "@njit(cache=True)\ndef finish_all("
    if src.count(anchor) != 1:
        raise SystemExit(f"finish_all not found in {path}")
    src = src.replace(anchor, "_SKIP = int(__import__('os').environ.get('MRM_SKIP', '0'))\n\n\n" + anchor)
    path.write_text(src)


CHILD = """
import json, sys
sys.argv.append("--quick")  # speed_inputs without the 4096² blobs, which are not timed here
sys.path.insert(0, {copy!r})
sys.path.insert(1, {bench!r})
import numpy as np, rasterio.features
from reconstruct import median_ms, speed_inputs
from mrm.geometry.reconstruct import reconstruct
from mrm.core.grids import PixelSet
from mrm.reps.summary import count_vertices
assert reconstruct.__code__.co_filename.startswith({copy!r})
for name, m in speed_inputs():
    image = name.split()[0]
    if image not in {images!r}:
        continue
    ps = PixelSet(m)
    m8 = np.ascontiguousarray(m.astype(np.uint8))
    gdal = median_ms(lambda: list(rasterio.features.shapes(m8, mask=m, connectivity=4)), {reps})
    for model in {models!r}:
        nv = count_vertices(reconstruct(ps, model))
        ms = median_ms(lambda: reconstruct(ps, model), {reps})
        print(json.dumps(dict(image=image, model=model, vertices=nv, ms=ms, gdal=gdal)), flush=True)
"""


def child(copy: Path, cache: Path, skip: int, images: tuple[str, ...], reps: int) -> dict:
    """The arguments of subprocess.run / Popen for one fresh process of one variant."""
    code = CHILD.format(
        copy=str(copy), bench=str(ROOT / "benchmarks"), images=images, models=MODELS, reps=reps
    )
    env = dict(os.environ, MRM_SKIP=str(skip), NUMBA_CACHE_DIR=str(cache))
    return dict(args=[sys.executable, "-c", code], env=env)


def run_variant(copy: Path, cache: Path, skip: int, reps: int) -> list[dict]:
    """One fresh process of one variant: a row per image and model."""
    out = subprocess.run(**child(copy, cache, skip, IMAGES, reps), capture_output=True, text=True, check=True)
    return [json.loads(line) for line in out.stdout.splitlines() if line.startswith("{")]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3, help="timing runs of each variant, taking turns")
    ap.add_argument("--reps", type=int, default=15, help="calls per median in each run")
    args = ap.parse_args()
    sys.path.insert(0, str(ROOT / "benchmarks"))
    sys.argv.append("--quick")  # speed_inputs without the 4096² blobs
    from reconstruct import peer_potrace, speed_inputs, table

    from mrm.core.grids import PixelSet

    potrace = {
        n.split()[0]: peer_potrace(PixelSet(m))[1] for n, m in speed_inputs() if n.split()[0] in IMAGES
    }
    with tempfile.TemporaryDirectory(prefix="mrm-finishing-") as tmp:
        copy = Path(tmp) / "src"
        patched_copy(copy)
        caches = {v: Path(tmp) / f"cache{skip}" for v, skip in VARIANTS.items()}
        # compile every variant (one run on the horse fills its cache), two at a time
        items = list(VARIANTS.items())
        for i in range(0, len(items), 2):
            procs = [
                subprocess.Popen(**child(copy, caches[v], skip, ("horse",), 1), stdout=subprocess.DEVNULL)
                for v, skip in items[i : i + 2]
            ]
            for p in procs:
                if p.wait() != 0:
                    raise SystemExit("a variant failed to compile")
        rows: dict[tuple[str, str, str], list[dict]] = {}
        for _ in range(args.rounds):
            for v, skip in VARIANTS.items():
                for r in run_variant(copy, caches[v], skip, args.reps):
                    rows.setdefault((v, r["image"], r["model"]), []).append(r)
    for model in MODELS:
        cells = []
        for image in IMAGES:
            row = [image, potrace[image]]
            for v in VARIANTS:
                rs = rows[(v, image, model)]
                nv = rs[0]["vertices"]
                ms = statistics.median(r["ms"] for r in rs)
                ratio = statistics.median(r["ms"] / r["gdal"] for r in rs)
                row.append(f"{nv} ({nv / potrace[image]:.3f}) · {ms:.2f} ({ratio:.2f})")
            cells.append(row)
        table(
            f"{model}: R with optional finishing steps left out, medians of {args.rounds} alternating runs "
            "(vertices (÷ potrace) · R ms (÷ GDAL polygonize, same process))",
            ["image", "potrace", *VARIANTS],
            cells,
        )


if __name__ == "__main__":
    main()
