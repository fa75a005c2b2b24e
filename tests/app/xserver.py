"""A private Xvfb for the tests that need a real X server (the real-display test, the 3D views)."""

from __future__ import annotations

import fcntl
import os
import shutil
import signal
import subprocess
import tempfile
from pathlib import Path

#: Held while one Xvfb starts. Two servers started at once by two pytest-xdist workers can both pick the same
#: free display: the second unlinks the first's socket file, binds its own, fails to lock the display and
#: exits, and the first is left without a socket ("could not connect to display :1", seen once in CI).
START_LOCK = Path(tempfile.gettempdir()) / "mrm-tests-xvfb-start.lock"


def tool(name: str) -> str:
    """The path of a program .ci/setup.sh installs (a clear failure when it is missing)."""
    path = shutil.which(name)
    assert path is not None, f"{name} is missing: run `bash .ci/setup.sh` (installs xvfb, xdotool, x11-apps)"
    return path


def start_xvfb(
    tmp_path: Path, *, size: str = "1440x900x24", glx: bool = False
) -> tuple[subprocess.Popen[bytes], str]:
    """Start Xvfb on a free display number; return the process and ``:N``.

    ``glx=True`` enables the GLX extension explicitly (Mesa's llvmpipe renders OpenGL in software).
    """
    r, w = os.pipe()
    args = [tool("Xvfb"), "-displayfd", str(w), "-screen", "0", size, "-nolisten", "tcp"]
    if glx:
        args += ["+extension", "GLX"]
    with open(START_LOCK, "w") as lock:
        # one start at a time: the number is written once the server holds its display's lock file
        fcntl.flock(lock, fcntl.LOCK_EX)
        proc = subprocess.Popen(
            args,
            pass_fds=(w,),
            stdout=subprocess.DEVNULL,
            stderr=open(tmp_path / "xvfb.log", "wb"),  # noqa: SIM115 - lives as long as the server
        )
        os.close(w)
        with os.fdopen(r) as f:
            number = f.readline().strip()
    assert number, f"Xvfb did not start: {(tmp_path / 'xvfb.log').read_text()}"
    return proc, f":{number}"


def stop(proc: subprocess.Popen[bytes]) -> None:
    """Stop a server started by :func:`start_xvfb`.

    Under the start lock too: a stopping Xvfb removes its display's lock file before it lets go of its
    sockets, and a server started in between took the same number and found it "already running" (the
    real-display test, once in CI, while the 3D views' server was stopping on another worker).
    """
    if proc.poll() is None:
        with open(START_LOCK, "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            proc.send_signal(signal.SIGTERM)
            try:
                proc.wait(10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(10)
