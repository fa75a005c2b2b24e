"""The layering (core → geometry → ops → document → io/cli/views → app): views never import mrm.app.

What a view needs of the application — the jobs its runner sends to worker processes, where a preference is
set — the window (in app/) hands it (issue 27, item 5).
"""

from __future__ import annotations

import ast
from pathlib import Path

VIEWS = Path(__file__).resolve().parents[1] / "views"


def _imports(path: Path) -> list[tuple[int, str]]:
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module:
            names = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        else:
            continue
        found += [(node.lineno, n) for n in names]
    return found


def test_no_view_module_imports_the_application_layer():
    files = sorted(VIEWS.glob("*.py"))
    assert files
    bad = [
        f"{p.name}:{line} imports {name}"
        for p in files
        for line, name in _imports(p)
        if name == "mrm.app" or name.startswith("mrm.app.")
    ]
    assert bad == []
