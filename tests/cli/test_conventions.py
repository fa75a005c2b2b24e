"""CLI conventions every subcommand follows (issue 12 deliverable 4, issue 11 item 7), via ``python -m mrm``.

Each test runs the real command in a subprocess and asserts what a user sees: the files written, the
bytes on stdout, one line on stderr and the exit status.
"""

from __future__ import annotations

import fcntl
import json
import os
import pty
import select
import shlex
import struct
import subprocess
import sys
import termios
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import mrm
from mrm.cli._common import cpu_count, jobs_count

PY = sys.executable


def mrm_run(*args: str, cwd: Path, stdin: bytes | None = None, **kw) -> subprocess.CompletedProcess[bytes]:
    return subprocess.run([PY, "-m", "mrm", *args], cwd=cwd, input=stdin, capture_output=True, **kw)


def sh(script: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["bash", "-c", script], cwd=cwd, capture_output=True, text=True)


def one_error_line(done: subprocess.CompletedProcess[bytes], command: str) -> str:
    err = done.stderr.decode()
    assert done.returncode == 2, err
    assert "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith(f"mrm {command}: error: "), err
    return lines[0]


L_PBM = b"P1\n3 2\n1 0 0\n1 1 1\n"  # an L: (0, 1) on top of the row (0, 0) (1, 0) (2, 0)


@pytest.fixture
def batch(tmp_path: Path) -> Path:
    d = tmp_path / "batch"
    d.mkdir()
    rng = np.random.default_rng(3)
    for k in range(5):
        img = rng.random((6, 7)) < 0.5
        img[0, 0] = True
        Image.fromarray(img).save(d / f"img{k}.png")
    return d


def test_version(tmp_path):
    done = mrm_run("--version", cwd=tmp_path)
    assert done.returncode == 0
    assert done.stdout.decode().strip() == f"mrm {mrm.__version__}"


@pytest.mark.parametrize(
    "command",
    [
        "--help",
        "info --help",
        "reconstruct batch/img0.png batch/img1.png batch/img2.png batch/img3.png batch/img4.png -o out/",
        "info batch --json",
    ],
)
def test_closed_stdout_exits_quietly(batch, command):
    script = f"{shlex.quote(PY)} -m mrm {command} 2>err.txt | head -c 1 >/dev/null; echo ${{PIPESTATUS[0]}}"
    done = sh(script, batch.parent)
    assert (batch.parent / "err.txt").read_text() == ""
    assert done.stdout.strip() in ("0", "141")  # finished before head closed, or stopped by the closed pipe


def test_stdin_and_stdout(tmp_path):
    (tmp_path / "l.pbm").write_bytes(L_PBM)
    assert mrm_run("reconstruct", "l.pbm", "-o", "l.geojson", cwd=tmp_path).returncode == 0
    piped = mrm_run("reconstruct", "-", "-o", "-", cwd=tmp_path, stdin=L_PBM)
    assert piped.returncode == 0, piped.stderr
    streamed, written = json.loads(piped.stdout), json.loads((tmp_path / "l.geojson").read_text())
    assert streamed["features"][0]["geometry"] == written["features"][0]["geometry"]
    assert b"pixels" in piped.stderr  # the summary table moved to stderr, off the data stream
    wkt = mrm_run("reconstruct", "-", "-o", "-", "--format", ".wkt", cwd=tmp_path, stdin=L_PBM)
    assert wkt.stdout.startswith(b"POLYGON")
    # a vector on stdin, pixels on stdout: a PNG that reads back as D(E)
    png = mrm_run(
        "discretize",
        "-",
        "-o",
        "-",
        "--model",
        "gauss",
        cwd=tmp_path,
        stdin=b"POLYGON ((0 0, 3 0, 3 2, 0 2, 0 0))",
    )
    assert png.returncode == 0, png.stderr
    (tmp_path / "d.png").write_bytes(png.stdout)
    assert mrm.read_pixels(tmp_path / "d.png") == mrm.PixelSet.box(0, 0, 2, 1)
    info = json.loads(mrm_run("info", "-", "--json", cwd=tmp_path, stdin=L_PBM).stdout)
    assert info["pixels"] == 4
    clash = mrm_run("reconstruct", "l.pbm", "-o", "-", "--json", cwd=tmp_path)
    one_error_line(clash, "reconstruct")


def test_directories_and_quoted_globs(batch):
    root = batch.parent
    done = mrm_run("reconstruct", "batch/img*.png", "-o", "globbed/", cwd=root)  # not expanded by a shell
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in (root / "globbed").iterdir()) == [f"img{k}.geojson" for k in range(5)]
    info = json.loads(mrm_run("info", "batch", "--json", "--jobs", "2", cwd=root).stdout)
    assert [Path(f["input"]).name for f in info["files"]] == [f"img{k}.png" for k in range(5)]
    expected = [len(mrm.read_pixels(batch / f"img{k}.png")) for k in range(5)]
    assert [f["pixels"] for f in info["files"]] == expected
    none = mrm_run("info", "batch/*.pbm", cwd=root)
    assert "no file matches" in one_error_line(none, "info")


def test_discretize_several_inputs_into_a_folder(tmp_path):
    for k in range(3):
        (tmp_path / f"b{k}.wkt").write_text(f"POLYGON ((0 0, {k + 1} 0, {k + 1} 1, 0 1, 0 0))")
    done = mrm_run("discretize", ".", "-o", "px", "--model", "gauss", "--json", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    for k in range(3):
        assert mrm.read_pixels(tmp_path / "px" / f"b{k}.png") == mrm.PixelSet.box(0, 0, k, 0)


def test_jobs_is_capped_at_the_cpu_count():
    assert jobs_count("100000") == cpu_count()
    assert jobs_count("1") == 1


def test_results_are_streamed_as_each_file_finishes(tmp_path):
    (tmp_path / "a.pbm").write_bytes(L_PBM)
    rng = np.random.default_rng(0)
    Image.fromarray(rng.random((700, 700)) < 0.5).save(tmp_path / "z.png")  # seconds of work
    proc = subprocess.Popen(
        [PY, "-m", "mrm", "reconstruct", "a.pbm", "z.png", "-o", "out/"],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        first = proc.stdout.readline().decode()
        still_running = proc.poll() is None
    finally:
        proc.kill()
        proc.wait()
    assert first.startswith("a.pbm -> ")
    assert still_running, "the first file's line should come before the last file is done"


def _stderr_on_a_terminal(args: list[str], cwd: Path) -> tuple[int, bytes]:
    """Run ``python -m mrm ARGS`` with stderr on a pseudo-terminal of 100 columns; return (status, bytes)."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))
    proc = subprocess.Popen([PY, "-m", "mrm", *args], cwd=cwd, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    seen = b""
    try:
        while True:
            ready, _, _ = select.select([master], [], [], 0.2)
            if ready:
                try:
                    chunk = os.read(master, 65536)
                except OSError:  # EIO: the child closed the terminal
                    break
                if not chunk:
                    break
                seen += chunk
            elif proc.poll() is not None:
                break
    finally:
        os.close(master)
    return proc.wait(), seen


def _ends_cleared(seen: bytes) -> bool:
    """Whether a terminal's stderr ends with its last line blanked and the cursor back at its start."""
    return seen.endswith(b"\r") and seen[:-1].rsplit(b"\r", 1)[-1].strip() == b""


def test_progress_bar_only_on_a_terminal(tmp_path):
    rng = np.random.default_rng(1)
    Image.fromarray(rng.random((800, 800)) < 0.5).save(tmp_path / "n.png")  # several seconds of work
    quiet = mrm_run("reconstruct", "n.png", "-o", "n.geojson", cwd=tmp_path)
    assert quiet.returncode == 0 and quiet.stderr == b""  # no terminal: no bar
    status, seen = _stderr_on_a_terminal(["reconstruct", "n.png", "-o", "m.geojson"], tmp_path)
    assert status == 0
    assert b"reconstruct n.png" in seen and b"0/1" in seen  # tqdm's bar, drawn after its one-second delay
    assert _ends_cleared(seen)  # and wiped at the end, so the shell's prompt does not land on it
    status, seen = _stderr_on_a_terminal(["reconstruct", "n.png", "-o", "q.geojson", "--quiet"], tmp_path)
    assert status == 0 and seen == b""
    # A failure's message starts its own line: a bar drawn before it (a loaded machine can take a second
    # to get there) is cleared first, never left with the message glued to its end.
    status, seen = _stderr_on_a_terminal(["info", "n.png", "--limit", "10"], tmp_path)
    assert status == 2
    before, _, message = seen.partition(b"mrm info: error: ")
    assert message.startswith(b"n.png: the image is 800")
    assert before == b"" or _ends_cleared(before)


def test_invert_takes_the_dark_drawing(tmp_path):
    img = np.full((4, 5), 255, dtype=np.uint8)
    img[1:3, 1:4] = 0  # a black 3×2 bar on white, as a scanner gives it
    Image.fromarray(img).save(tmp_path / "ink.png")
    plain = json.loads(mrm_run("info", "ink.png", "--json", cwd=tmp_path).stdout)
    inked = json.loads(mrm_run("info", "ink.png", "--json", "--invert", cwd=tmp_path).stdout)
    assert plain["pixels"] == 20 - 6 and plain["holes"] == 1
    assert inked["pixels"] == 6 and inked["bbox"] == [1, 1, 3, 2] and inked["holes"] == 0
    thr = json.loads(mrm_run("info", "ink.png", "--json", "--threshold", "254", cwd=tmp_path).stdout)
    assert thr["pixels"] == 14


def test_missing_output_folders_are_created_alike(tmp_path):
    (tmp_path / "l.pbm").write_bytes(L_PBM)
    (tmp_path / "b.wkt").write_text("POLYGON ((0 0, 2 0, 2 2, 0 2, 0 0))")
    for args in (
        ("reconstruct", "l.pbm", "-o", "n1/a/l.geojson"),
        ("discretize", "b.wkt", "-o", "n2/a/b.png"),
        ("info", "l.pbm"),
        ("scale", "l.pbm", "--alpha", "2", "-o", "n3/a/s.png", "--no-measure"),
        ("union", "l.pbm", "b.wkt", "-o", "n4/a/u.geojson", "--no-measure"),
    ):
        done = mrm_run(*args, cwd=tmp_path)
        assert done.returncode == 0, (args, done.stderr)
        if "-o" in args:
            assert (tmp_path / args[args.index("-o") + 1]).is_file()


# ------------------------------------------------------------------------------- one line, exit status 2
def test_os_errors_are_one_line(tmp_path):
    (tmp_path / "l.pbm").write_bytes(L_PBM)
    os.symlink("loop.png", tmp_path / "loop.png")
    (tmp_path / "plain.txt").write_text("x")
    cases = {
        "symlink loop": ("reconstruct", "loop.png", "-o", "x.geojson"),
        "name too long": ("reconstruct", "l.pbm", "-o", "n" * 300 + ".geojson"),
        "path through a file": ("reconstruct", "l.pbm", "-o", "plain.txt/x.geojson"),
        "input through a file": ("info", "plain.txt/x.png"),
        "missing input": ("info", "nothere.png"),
        "directory as output": ("discretize", "-", "-o", "."),
    }
    for what, args in cases.items():
        done = mrm_run(*args, cwd=tmp_path, stdin=b"POINT (0 0)")
        line = one_error_line(done, args[0])
        assert len(line) < 500, what


def test_full_standard_output_is_one_line(tmp_path):
    (tmp_path / "l.pbm").write_bytes(L_PBM)
    done = sh(f"{shlex.quote(PY)} -m mrm reconstruct l.pbm -o - >/dev/full", tmp_path)
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert done.stderr.strip().splitlines()[-1] == "mrm reconstruct: error: No space left on device"


@pytest.mark.parametrize(
    ("options", "expected"), [("ro", "Read-only file system"), ("size=8k", "No space left")]
)
def test_read_only_and_full_file_systems(tmp_path, options, expected):
    rng = np.random.default_rng(2)
    Image.fromarray(rng.random((60, 60)) < 0.5).save(tmp_path / "n.png")
    (tmp_path / "mnt").mkdir()
    script = (
        f"mount -t tmpfs -o {options} none mnt && "
        f"{shlex.quote(PY)} -m mrm reconstruct n.png -o mnt/out.geojson"
    )
    done = subprocess.run(["unshare", "-m", "sh", "-c", script], cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 2, done.stderr
    assert "Traceback" not in done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mrm reconstruct: error: ") and expected in lines[0]


def test_bad_numbers_are_one_line(tmp_path):
    (tmp_path / "l.pbm").write_bytes(L_PBM)
    line = one_error_line(
        mrm_run("scale", "l.pbm", "--alpha", "2", "--center", "1e308,1e308", "-o", "s.png", cwd=tmp_path),
        "scale",
    )
    assert "center" in line and "between" in line  # the registry's declared range, named in the message
    assert not (tmp_path / "s.png").exists()  # refused before any work: nothing written
    line = one_error_line(mrm_run("segment", "--chain", "99999999999999999999,0,01", cwd=tmp_path), "segment")
    assert "out of range" in line
    one_error_line(mrm_run("rotate", "l.pbm", "--angle", "1e400", "-o", "r.png", cwd=tmp_path), "rotate")


def test_what_reconstruct_writes_reads_back(tmp_path, monkeypatch, capsys):
    from mrm.cli import reconstruct, run_cli

    rng = np.random.default_rng(4)
    Image.fromarray(rng.random((30, 30)) < 0.5).save(tmp_path / "n.png")
    out = tmp_path / "n.geojson"
    assert run_cli(["reconstruct", str(tmp_path / "n.png"), "-o", str(out), "--model", "gauss"]) == 0
    geom = mrm.read_geometry(out)
    assert mrm.discretize(geom, "gauss") == mrm.read_pixels(tmp_path / "n.png")
    # A result too big for the vector reader is refused before anything is written.
    monkeypatch.setattr(reconstruct, "MAX_VECTOR_FILE_BYTES", out.stat().st_size // 4)
    big = tmp_path / "big.geojson"
    assert run_cli(["reconstruct", str(tmp_path / "n.png"), "-o", str(big), "--model", "gauss"]) == 2
    assert "read back" in capsys.readouterr().err and not big.exists()
