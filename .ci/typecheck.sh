#!/usr/bin/env bash
# mypy --strict on the Qt-free library. model/ is installed as the package `mrm` (pyproject package-dir), a
# mapping mypy cannot follow, so mypy reads it through a temporary folder where `mrm` is a link to model/.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
ln -s "$PWD/model" "$root/mrm"
cd "$root"
exec "$OLDPWD/.venv/bin/python" -m mypy --config-file "$OLDPWD/pyproject.toml" -p mrm "$@"
