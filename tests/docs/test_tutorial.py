"""docs/tutorial.md's code runs, in order, as a reader would paste it (issue 12 deliverable 5)."""

from __future__ import annotations

import os
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_tutorial_code_runs(tmp_path, capsys):
    text = (ROOT / "docs" / "tutorial.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) >= 5
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        namespace: dict[str, object] = {"__name__": "tutorial"}
        for k, block in enumerate(blocks):
            exec(compile(block, f"docs/tutorial.md block {k + 1}", "exec"), namespace)
    finally:
        os.chdir(here)
    out = capsys.readouterr().out
    assert "measured" in out and "<= bound" in out
    # every output the page shows (```text blocks) is what its code printed, line for line
    printed = out.splitlines()
    for shown in re.findall(r"```text\n(.*?)```", text, flags=re.S):
        for line in shown.splitlines():
            assert line in printed, f"docs/tutorial.md shows {line!r}, the code printed {printed}"
    from PIL import Image

    for figure in ("dss.png", "voxels.png"):  # the figures were drawn
        with Image.open(tmp_path / figure) as im:
            assert im.size == (400, 400)
