"""The first run of the command line on a fresh install: CPU of the cold runs, wall time of the later ones.

Issue 31, item 1. The package is installed non-editable (``pip install --no-deps .``) into a temporary venv,
so that numba's cache next to the installed kernels starts empty, as after a user's ``pip install``. The
dependencies are not downloaded again: the temporary venv sees the running interpreter's site-packages
through a ``.pth`` line placed after its own (``--full`` runs a complete ``pip install .`` instead, which
needs the package index or a wheel cache).

For each command (``reconstruct`` of a small binary PNG, ``discretize`` of a small polygon) the script empties
the installed package's numba cache, runs the command once cold — whole process, CPU = user + sys of the
child from ``resource.getrusage(RUSAGE_CHILDREN)`` — then ``--repeat`` more times warm (wall time), and
prints the medians with whether the first-run notice appeared on each run.

Run: ``.venv/bin/python benchmarks/first_run.py [--cold N] [--repeat N] [--only reconstruct] [--keep DIR]``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
NOTICE = "mrm: first run:"


def make_venv(where: Path, full: bool, tree: Path = ROOT) -> Path:
    """A venv with this tree installed non-editable; returns its python."""
    subprocess.run([sys.executable, "-m", "venv", str(where)], check=True)
    py = where / "bin" / "python"
    if not full:
        # The dependencies of the running interpreter, after the venv's own site-packages (a path listed in
        # a .pth file is appended to sys.path; the .pth files of that directory itself are not run, so an
        # editable install of this tree there is not seen).
        own = subprocess.run(
            [str(py), "-c", "import site; print(site.getsitepackages()[0])"],
            check=True,
            capture_output=True,
            text=True,
        ).stdout.strip()
        deps = [p for p in sys.path if p.endswith("site-packages") and Path(p).is_dir()]
        Path(own, "zz_first_run_deps.pth").write_text("\n".join(deps) + "\n", encoding="utf-8")
    # A copy of the tree without its venvs and caches, so that the build sees no compiled kernels.
    src = where / "src"
    shutil.copytree(
        tree,
        src,
        ignore=shutil.ignore_patterns(".venv", ".git", "__pycache__", "*.egg-info", "build", "dist"),
    )
    cmd = [str(py), "-m", "pip", "install", "-q", str(src)]
    if not full:
        cmd.insert(4, "--no-deps")
    subprocess.run(cmd, check=True)
    return py


def package_dir(py: Path) -> Path:
    out = subprocess.run(
        [str(py), "-c", "import mrm, os; print(os.path.dirname(mrm.__file__))"],
        check=True,
        capture_output=True,
        text=True,
        cwd="/",
    ).stdout.strip()
    return Path(out)


def clear_cache(pkg: Path) -> int:
    """Remove every numba cache file (and the warm-up stamp) of the installed package."""
    n = 0
    for pattern in ("*.nbi", "*.nbc", "mrm-kernels-warm.json"):
        for f in pkg.rglob(pattern):
            f.unlink()
            n += 1
    return n


def run(py: Path, argv: list[str], cwd: Path) -> tuple[float, float, bool, str]:
    """One whole process: (CPU seconds, wall seconds, notice printed, stderr)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    mrm = py.parent / "mrm"
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    p = subprocess.run([str(mrm), *argv], cwd=cwd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if p.returncode != 0:
        raise SystemExit(f"{argv}: exit {p.returncode}\n{p.stderr}")
    return cpu, wall, NOTICE in p.stderr, p.stderr


def inputs(where: Path) -> dict[str, list[str]]:
    import numpy as np
    from PIL import Image

    yy, xx = np.mgrid[0:64, 0:64]
    mask = ((xx - 30) ** 2 + (yy - 33) ** 2 < 400) & ~((xx - 30) ** 2 + (yy - 30) ** 2 < 60)
    mask |= (xx > 50) & (yy > 5) & (yy < 20)
    Image.fromarray(mask).save(where / "small.png")
    poly = {
        "type": "Polygon",
        "coordinates": [[[0.3, 0.2], [29.7, 3.1], [20.4, 27.9], [1.2, 19.3], [0.3, 0.2]]],
    }
    (where / "poly.geojson").write_text(json.dumps(poly), encoding="utf-8")
    return {
        "reconstruct": ["reconstruct", "small.png", "-o", "r.geojson"],
        "discretize": ["discretize", "poly.geojson", "-o", "d.png"],
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--cold", type=int, default=1, help="cold runs per command (the cache emptied before each)"
    )
    ap.add_argument("--repeat", type=int, default=5, help="warm runs per command")
    ap.add_argument("--only", action="append", choices=["reconstruct", "discretize"], default=None)
    ap.add_argument("--full", action="store_true", help="pip install . with its dependencies")
    ap.add_argument("--tree", type=Path, default=ROOT, help="the source tree to install (default: this one)")
    ap.add_argument("--keep", type=Path, default=None, help="keep the venv in this folder (reused if there)")
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="mrm-first-run-"))
    try:
        venv = args.keep if args.keep is not None else tmp / "venv"
        py = venv / "bin" / "python"
        if not py.exists():
            print(f"installing into {venv} …", flush=True)
            py = make_venv(venv, args.full, args.tree)
        pkg = package_dir(py)
        work = tmp / "work"
        work.mkdir()
        commands = inputs(work)
        for name in args.only or list(commands):
            argv = commands[name]
            colds = []
            for _ in range(args.cold):
                clear_cache(pkg)
                cpu, wall, said, _err = run(py, argv, work)
                colds.append((cpu, wall, said))
                print(f"{name} cold: {cpu:.1f} s CPU, {wall:.1f} s wall, notice: {said}", flush=True)
            warms = []
            for _ in range(args.repeat):
                cpu, wall, said, _err = run(py, argv, work)
                warms.append((cpu, wall, said))
            first = (
                f"first run median {statistics.median(c[0] for c in colds):.1f} s CPU "
                f"({statistics.median(c[1] for c in colds):.1f} s wall); "
                if colds
                else ""
            )
            print(
                f"{name}: {first}later runs median "
                f"{statistics.median(w[1] for w in warms):.2f} s wall, max {max(w[1] for w in warms):.2f} s "
                f"({statistics.median(w[0] for w in warms):.2f} s CPU); notice on a later run: "
                f"{any(w[2] for w in warms)}",
                flush=True,
            )
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
