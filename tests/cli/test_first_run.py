"""Issue 31, item 1: the first-run notice appears exactly when numba compiles, never on a warm run.

Before, the command line printed "about a minute" whenever the warm-up stamp was missing: after a bare
``pip install`` on every run, warm or not, even with ``--quiet``, because only ``python -m mrm.warmup`` wrote
the stamp. Now the notice follows numba's own compile events (a cached kernel loads without one).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numba
import pytest

from mrm import warmup
from mrm.cli import run_cli

NOTICE = "mrm: first run: compiling the geometry kernels"


@pytest.fixture
def no_stamp(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Path:
    """A stamp location of this test only, with no stamp in it: what a bare ``pip install`` leaves."""
    stamp = tmp_path / "numba-cache" / warmup.STAMP_NAME
    monkeypatch.setattr(warmup, "stamp_path", lambda: stamp)
    return stamp


@pytest.fixture
def compiling_segment(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """``mrm segment`` that first calls a kernel no cache holds (a new one each test): a real compile."""
    from mrm.cli import segment

    @numba.njit(cache=False)
    def fresh(n: int) -> int:
        return n * 3 + 1

    calls: list[int] = []
    real = segment.run

    def run(args: object) -> object:
        calls.append(fresh(len(calls)))
        return real(args)

    monkeypatch.setattr(segment, "run", run)
    return calls


SEGMENT = ["segment", "--chain", "0,0,0001011", "--json"]


def test_a_warm_run_prints_no_notice_although_the_stamp_is_missing(no_stamp, capsys):
    """After a pip install nothing wrote the stamp; a run whose kernels are cached must stay silent."""
    assert not no_stamp.exists()
    assert run_cli(SEGMENT) == 0  # loads (or compiles) the kernels once in this process
    capsys.readouterr()
    assert run_cli(SEGMENT) == 0
    assert capsys.readouterr().err == ""


def test_the_notice_is_one_line_on_stderr_exactly_when_a_kernel_compiles(compiling_segment, capsys):
    assert run_cli(SEGMENT) == 0
    out, err = capsys.readouterr()
    assert compiling_segment == [1]
    assert err.splitlines() == [warmup.first_run_message("segment")]
    assert NOTICE not in out  # the JSON summary on stdout stays clean
    assert run_cli(SEGMENT) == 0  # compiled now: the same run again says nothing
    assert capsys.readouterr().err == ""


def test_quiet_silences_the_notice(compiling_segment, capsys):
    assert run_cli([*SEGMENT, "--quiet"]) == 0
    assert capsys.readouterr().err == ""
    assert compiling_segment == [1]  # it did compile


def test_the_notice_quotes_an_estimate_of_the_command():
    assert "about 150 s of CPU" in warmup.first_run_message("reconstruct")  # not "about a minute"
    assert "minute" not in warmup.first_run_message("discretize")
    assert "a few minutes" in warmup.first_run_message(None)


def test_watch_compiles_counts_and_unregisters():
    @numba.njit(cache=False)
    def twice(x: float) -> float:
        return 2 * x

    with warmup.watch_compiles("x", quiet=True) as seen:
        twice(1.0)
        twice(2.0)  # compiled once per signature
    assert seen.compiled == 1 and not seen.announced
    with warmup.watch_compiles("x", quiet=True) as seen:
        twice(3)  # a new signature after the block: the old listener is gone, this one counts it
    assert seen.compiled == 1


def test_a_cold_cache_announces_once_and_the_next_run_is_silent(tmp_path: Path):
    """A real cold cache in a child process (an empty ``NUMBA_CACHE_DIR``): the first run compiles and says
    so once; the second finds numba's cache filled by the first and says nothing, with no stamp anywhere."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    cmd = [sys.executable, "-m", "mrm.app.main", "segment", "--chain", "0,0,01", "--json"]
    first = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=900, check=False)
    assert first.returncode == 0, first.stderr
    notices = [ln for ln in first.stderr.splitlines() if ln.startswith(NOTICE)]
    assert len(notices) == 1, first.stderr
    assert not (tmp_path / "cache" / warmup.STAMP_NAME).exists()
    second = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=900, check=False)
    assert second.returncode == 0 and second.stderr == "", second.stderr
    assert second.stdout == first.stdout


def test_discretize_without_json_loads_no_region_or_segment_kernel(tmp_path: Path):
    """The first ``mrm discretize`` compiled the labelling, crack and segmentation kernels for its table
    (20 of its 28 s of CPU on a fresh install). Without ``--json`` it now calls none of them; ``--json``
    keeps every documented key. Checked in a child process, which starts with no module loaded."""
    src = tmp_path / "p.geojson"
    src.write_text('{"type": "Polygon", "coordinates": [[[0.5, 0.5], [7.5, 1.5], [3.5, 6.5], [0.5, 0.5]]]}')
    code = (
        "import sys\n"
        "from mrm.cli import run_cli\n"
        f"status = run_cli(['discretize', {str(src)!r}, '-o', {str(tmp_path / 'o.png')!r}] + sys.argv[1:])\n"
        "loaded = [m for m in ('mrm.geometry.dss._kernels', 'mrm.geometry.topology.cracks',"
        " 'mrm.geometry.topology.labeling', 'mrm.reps.region') if m in sys.modules"
        " and any(getattr(f, 'signatures', None) for f in vars(sys.modules[m]).values())]\n"
        "print('LOADED', status, loaded)\n"
    )
    text = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "LOADED 0 []" in text.stdout, text.stdout + text.stderr
    assert "pixels" in text.stdout and "vertices" in text.stdout
    full = subprocess.run([sys.executable, "-c", code, "--json"], capture_output=True, text=True, check=True)
    assert "LOADED 0 [" in full.stdout and "LOADED 0 []" not in full.stdout  # --json: the region and segments
    summary = json.loads(full.stdout.splitlines()[0])
    assert {"components", "holes", "euler", "boundary_chains", "segments", "vertices"} <= set(summary)


def _png(path: Path, width: int, height: int, *, labels: bool = False) -> Path:
    """A picture with two discs, a hole and a pixel touching another by its corner (several rings)."""
    import numpy as np
    from PIL import Image

    yy, xx = np.mgrid[0:height, 0:width]
    img = ((xx - width * 0.45) ** 2 + (yy - height * 0.45) ** 2 < (0.3 * min(width, height)) ** 2).astype(
        np.uint8
    )
    img[(xx - width * 0.45) ** 2 + (yy - height * 0.45) ** 2 < (0.1 * min(width, height)) ** 2] = 0
    img[2:5, 2:6] = 2 if labels else 1
    img[5, 6] = 3 if labels else 1
    Image.fromarray(img if labels else img * 255).save(path)
    return path


def _cold_env(tmp_path: Path) -> dict[str, str]:
    (tmp_path / "cold").mkdir(exist_ok=True)
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_DISABLE_JIT"}
    return dict(env, NUMBA_CACHE_DIR=str(tmp_path / "cold"))


@pytest.mark.parametrize(
    ("command", "labels", "out"),
    [("reconstruct", False, "r.geojson"), ("polygonize", True, "p.geojson"), ("info", False, None)],
)
def test_a_small_raster_on_a_cold_cache_runs_interpreted_with_the_compiled_result(
    tmp_path: Path, command: str, labels: bool, out: str | None
):
    """A fresh install's first ``mrm reconstruct`` of a small PNG compiled for 130-143 s of CPU. On a cold
    cache a small raster now runs the same kernels interpreted: nothing compiles (no notice, no cache file),
    and the output is byte for byte the one the compiled kernels give (the warm cache of this suite)."""
    src = _png(tmp_path / "in.png", 96, 80, labels=labels)
    cold_out, warm_out = tmp_path / f"cold-{out}", tmp_path / f"warm-{out}"
    runs = {}
    for name, env, dest in (("cold", _cold_env(tmp_path), cold_out), ("warm", dict(os.environ), warm_out)):
        cmd = [
            sys.executable,
            "-m",
            "mrm.app.main",
            command,
            str(src),
            *(["-o", str(dest)] if out else []),
            "--json",
        ]
        runs[name] = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=600, check=False)
        assert runs[name].returncode == 0, runs[name].stderr
    assert runs["cold"].stderr == ""  # no first-run notice: nothing compiled
    assert not list((tmp_path / "cold").rglob("*.nbi"))
    drop = ("seconds", "input", "output")
    cold, warm = (json.loads(runs[n].stdout) for n in ("cold", "warm"))
    assert {k: v for k, v in cold.items() if k not in drop} == {
        k: v for k, v in warm.items() if k not in drop
    }
    if out:
        assert cold_out.read_bytes() == warm_out.read_bytes()


def _decides(tmp_path: Path, *args: str, env: dict[str, str] | None = None) -> bool:
    code = "import sys; from mrm.cli._interpreted import interpret_small_inputs as f; print(f(sys.argv[1:]))"
    done = subprocess.run(
        [sys.executable, "-c", code, *args],
        env=env or _cold_env(tmp_path),
        capture_output=True,
        text=True,
        check=True,
    )
    return done.stdout.strip() == "True"


def test_only_small_rasters_on_a_cold_cache_run_interpreted(tmp_path: Path):
    small = _png(tmp_path / "small.png", 256, 256)
    big = _png(tmp_path / "big.png", 257, 256)
    assert _decides(tmp_path, "reconstruct", str(small), "-o", str(tmp_path / "x.geojson"))
    assert _decides(tmp_path, "polygonize", str(small), "--output", str(big))  # the output is not measured
    assert not _decides(tmp_path, "reconstruct", str(big), "-o", "x.geojson")  # compiles, with the notice
    import numpy as np
    from PIL import Image

    noise = np.random.default_rng(5).random((256, 256)) < 0.5  # 65,000 cracks: 33 s interpreted
    Image.fromarray((noise * 255).astype(np.uint8)).save(tmp_path / "noise.png")
    assert not _decides(tmp_path, "reconstruct", str(tmp_path / "noise.png"), "-o", "x.geojson")
    Image.fromarray((noise[:90, :90] * 255).astype(np.uint8)).save(tmp_path / "noise90.png")  # 8,000 cracks
    assert _decides(tmp_path, "reconstruct", str(tmp_path / "noise90.png"), "-o", "x.geojson")
    assert not _decides(tmp_path, "reconstruct", str(small), str(big), "-o", "out")
    assert not _decides(tmp_path, "reconstruct", str(tmp_path), "-o", "out")  # a folder of inputs
    assert not _decides(tmp_path, "discretize", str(small), "-o", "x.png")  # not an R command
    (tmp_path / "v.npz").write_bytes(b"")
    assert not _decides(tmp_path, "reconstruct", str(tmp_path / "v.npz"), "-o", "x.obj")  # voxels
    warm = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "NUMBA_DISABLE_JIT")}
    assert not _decides(
        tmp_path, "reconstruct", str(small), "-o", "x.geojson", env=warm
    )  # this suite's cache
    own = dict(_cold_env(tmp_path), NUMBA_DISABLE_JIT="0")
    assert not _decides(tmp_path, "reconstruct", str(small), "-o", "x.geojson", env=own)  # the user's choice
