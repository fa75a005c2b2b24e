#!/usr/bin/env bash
# Sets up everything MR Modeler needs on a fresh Debian machine (Python 3.11, root, no display):
# the Debian libraries Qt loads even offscreen, a virtual environment in .venv, and the project with
# its test and benchmark extras. Safe to run again: it skips what is already there.
set -euo pipefail
cd "$(dirname "$0")/.."

QT_DEBS="libegl1 libgl1 libxkbcommon0 libfontconfig1 libfreetype6 libglib2.0-0 libdbus-1-3 libx11-6 fonts-dejavu-core"
# What Qt's xcb platform plugin (libqxcb.so, a real X display) loads besides the above: `ldd` on the plugin
# and on libQt6XcbQpa lists these; without them `mrm` aborts with "could not load the Qt platform plugin xcb".
XCB_DEBS="libx11-xcb1 libxcb1 libxcb-cursor0 libxcb-icccm4 libxcb-image0 libxcb-keysyms1 libxcb-randr0
  libxcb-render0 libxcb-render-util0 libxcb-shape0 libxcb-shm0 libxcb-sync1 libxcb-util1 libxcb-xfixes0
  libxcb-xkb1 libxkbcommon-x11-0"
# A virtual X server and the tools the real-display start test uses (tests/app/test_real_display.py).
X_TEST_DEBS="xvfb xauth xdotool x11-apps"
# OpenGL for the 3D views (pyqtgraph.opengl): Mesa's GLX and its software rasterizer llvmpipe, which the
# 3D view tests use on their own Xvfb (tests/app/test_views_3d.py).
GL_DEBS="libglx-mesa0 libgl1-mesa-dri libglu1-mesa"
missing=""
for p in $QT_DEBS $XCB_DEBS $X_TEST_DEBS $GL_DEBS; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "setup: installing Debian packages:$missing"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

PY="${PYTHON:-python3.11}"
command -v "$PY" >/dev/null 2>&1 || PY=python3
if [ ! -x .venv/bin/python ]; then
  echo "setup: creating .venv with $PY"
  "$PY" -m venv .venv
fi
stamp=.venv/.mrm-installed
if [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
  echo "setup: installing the project and its extras into .venv"
  .venv/bin/python -m pip install -q --upgrade pip
  .venv/bin/python -m pip install -q -e '.[gui,geo,test,docs,bench,dev]'
  touch "$stamp"
fi

# Qt's xcb plugin must find every library it links (checked, not assumed: a new PySide6 may need more).
qxcb=$(.venv/bin/python -c "import os, PySide6; print(os.path.join(os.path.dirname(PySide6.__file__), 'Qt', 'plugins', 'platforms', 'libqxcb.so'))")
if [ -f "$qxcb" ] && ldd "$qxcb" | grep -q "not found"; then
  echo "setup: warning: the Qt xcb plugin still misses:$(ldd "$qxcb" | awk '/not found/ {printf " %s", $1}')" >&2
fi

# Compile the numba kernels once (cached on disk), so the first `mrm` paints a usable window at once.
.venv/bin/python -m mrm.warmup
