"""The benchmark scripts load: a name they import that the code no longer has fails here, not in a note.

``benchmarks/operations.py`` imported a helper that went with issue 27 and failed at its first line for many
sessions before anyone ran it. Each script is imported (not run: their ``main`` is guarded) in one child
interpreter, so their module-level set-up (``sys.path``, peers such as scikit-image) stays out of this one.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_every_benchmark_script_imports() -> None:
    scripts = sorted(p.stem for p in (ROOT / "benchmarks").glob("*.py") if p.stem != "__init__")
    assert len(scripts) >= 10
    code = (
        "import importlib, sys\n"
        "failed = []\n"
        f"for name in {scripts!r}:\n"
        "    try:\n"
        "        importlib.import_module('benchmarks.' + name)\n"
        "    except Exception as e:\n"
        "        failed.append(f'{name}: {type(e).__name__}: {e}')\n"
        "print('\\n'.join(failed))\n"
        "sys.exit(1 if failed else 0)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr[-2000:]
