#!/usr/bin/env bash
# Builds the DGtal peer of benchmarks/planes.py (a benchmark-only step: nothing in the product or the tests
# needs it). DGtal's headers and static libraries come from its PyPI wheel (`dgtal`, installed into .venv by
# `pip install -e '.[bench3d]'` or here), Boost's headers from Debian's libboost-dev, the compiler is g++.
# Output: benchmarks/dgtal/build/plane_compare.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$(dirname "$here")")"
py="$root/.venv/bin/python"
if ! "$py" -c "import dgtal" 2>/dev/null; then
  "$py" -m pip install -q 'dgtal>=2.2'
fi
missing=""
for p in g++ libboost-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi
# The wheel keeps include/ and lib64/ beside its package folder, in site-packages.
site="$("$py" -c "import dgtal, os; print(os.path.dirname(os.path.dirname(dgtal.__file__)))")"
mkdir -p "$here/build"
g++ -O2 -std=c++17 -DNDEBUG -I"$site/include" "$here/plane_compare.cpp" -o "$here/build/plane_compare" \
  -L"$site/lib64" -lDGtal
echo "built $here/build/plane_compare"
