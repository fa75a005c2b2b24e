"""The real ``mrm`` on a real X server (Xvfb, installed by .ci/setup.sh): the xcb plugin, a painted window.

Everything else in tests/app runs offscreen; this test is the one that catches a missing X11 library (the
issue's "xcb-cursor0 … is needed to load the Qt xcb platform plugin", exit 134) and a window that stays black.
It starts its own Xvfb, starts ``mrm`` on the bundled example with fresh settings, waits for the window to be
mapped with the example's name in its title, and reads the screen back with ``xwd`` (what the X server shows,
not what Qt thinks it drew).
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from mrm.app.gui import default_example
from tests.app.xserver import start_xvfb, stop, tool

TIMEOUT = 120.0  # generous: a loaded CI machine; the figure itself is printed, never asserted


def read_xwd(data: bytes) -> np.ndarray:
    """Decode an ``xwd`` dump of a TrueColor screen (24 or 32 bits per pixel) into (h, w, 3) uint8."""
    hdr = np.frombuffer(data[:100], dtype=">u4")
    header_size, width, height = int(hdr[0]), int(hdr[4]), int(hdr[5])
    byte_order, bits_per_pixel, bytes_per_line = int(hdr[7]), int(hdr[11]), int(hdr[12])
    ncolors = int(hdr[19])
    assert bits_per_pixel in (24, 32), f"expected a 24/32-bit screen dump, got {bits_per_pixel} bits"
    step = bits_per_pixel // 8
    start = header_size + 12 * ncolors
    raw = np.frombuffer(data[start : start + bytes_per_line * height], dtype=np.uint8)
    px = raw.reshape(height, bytes_per_line)[:, : step * width].reshape(height, width, step)
    # byte_order 0 = LSBFirst: B, G, R (, pad) in memory; MSBFirst: (pad,) R, G, B.
    return px[:, :, [2, 1, 0]] if byte_order == 0 else px[:, :, [step - 3, step - 2, step - 1]]


def _colours(rgb: np.ndarray) -> int:
    """How many distinct colours a screen shows (packed to one integer per pixel: fast)."""
    packed = (rgb[..., 0].astype(np.uint32) << 16) | (rgb[..., 1].astype(np.uint32) << 8) | rgb[..., 2]
    return len(np.unique(packed))


def _mrm_command() -> list[str]:
    script = Path(sys.executable).with_name("mrm")
    return [str(script)] if script.exists() else [sys.executable, "-m", "mrm.app"]


@pytest.fixture
def xserver(tmp_path: Path):  # type: ignore[no-untyped-def]
    proc, display = start_xvfb(tmp_path)
    yield display
    stop(proc)


def test_mrm_starts_on_a_real_x_server_and_paints_its_window(xserver: str, tmp_path: Path) -> None:
    example = default_example()
    assert example is not None
    env = {k: v for k, v in os.environ.items() if k not in ("QT_QPA_PLATFORM", "WAYLAND_DISPLAY")}
    env.update(DISPLAY=xserver, HOME=str(tmp_path / "home"), XDG_CONFIG_HOME=str(tmp_path / "config"))
    env.update(XDG_RUNTIME_DIR=str(tmp_path / "run"))
    (tmp_path / "run").mkdir(mode=0o700)
    log = open(tmp_path / "mrm.log", "wb")  # noqa: SIM115 - closed below
    t0 = time.monotonic()
    app = subprocess.Popen(_mrm_command(), env=env, stdout=log, stderr=subprocess.STDOUT)
    try:
        title = ""
        shot = None
        deadline = t0 + TIMEOUT
        while time.monotonic() < deadline:
            log_text = (tmp_path / "mrm.log").read_text()
            assert app.poll() is None, f"mrm exited with {app.returncode}: {log_text}"
            found = subprocess.run(
                [tool("xdotool"), "search", "--onlyvisible", "--name", "MR Modeler"],
                env=env,
                capture_output=True,
                text=True,
            )
            wids = found.stdout.split()
            if wids:
                title = subprocess.run(
                    [tool("xdotool"), "getwindowname", wids[0]], env=env, capture_output=True, text=True
                ).stdout.strip()
                if example.name in title:
                    dump = subprocess.run(
                        [tool("xwd"), "-root", "-silent"], env=env, capture_output=True, check=True
                    ).stdout
                    shot = read_xwd(dump)
                    colours = _colours(shot)
                    if colours > 50:  # a painted window: text, plots, objects (black or blank: a handful)
                        break
            time.sleep(0.05)
        elapsed = time.monotonic() - t0
        print(f"\nmrm window mapped, titled and painted on {xserver} after {elapsed:.2f} s ({title!r})")
        assert example.name in title, f"no window titled with {example.name} after {TIMEOUT} s: {title!r}"
        # The first start opens an untitled copy of the example: Ctrl+S never rewrites the installed file.
        assert title.startswith("Untitled"), title
        assert shot is not None
        # Most of the screen is the window's light background, not an unpainted black window.
        dark = (shot.max(axis=2) < 30).mean()
        assert dark < 0.5, f"{dark:.0%} of the screen is black"
        assert _colours(shot) > 50
    finally:
        stop(app)
        log.close()
