"""The package's layers (docs/adr/0041), checked by import-linter on every import, function-local ones too.

core → geometry (with the representations) → ops → document → io → warmup → cli | api | views → app: a module
imports the layers below its own only; ``views``, ``cli`` and ``api`` do not import each other; nothing of the
library or the command line imports Qt or the GUI; the core imports nothing heavy. The contracts are in
pyproject.toml (``[tool.importlinter]``).

The package is installed from three folders (model/ is ``mrm``, app/ is ``mrm.app``, views/ is ``mrm.views``,
ADR 0007), which import-linter cannot follow through the editable install: the check runs on a tree laid out
as the wheel installs it, made of links to the sources.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _installed_layout(tmp: Path) -> Path:
    pkg = tmp / "mrm"
    pkg.mkdir()
    for child in (ROOT / "model").iterdir():
        if child.name != "__pycache__":
            (pkg / child.name).symlink_to(child)
    for name, folder in (("app", "app"), ("views", "views"), ("resources", "resources")):
        (pkg / name).symlink_to(ROOT / folder)
    return tmp


def test_the_layers_hold(tmp_path: Path) -> None:
    tree = _installed_layout(tmp_path)
    lint = Path(sys.executable).with_name("lint-imports")
    env = {**os.environ, "PYTHONPATH": str(tree)}
    done = subprocess.run(
        [str(lint), str(ROOT / "pyproject.toml"), "--no-cache"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        env=env,
        timeout=600,
    )
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
    assert "Contracts: 3 kept, 0 broken." in done.stdout
