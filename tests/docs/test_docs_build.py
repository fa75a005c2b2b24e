"""The API reference builds from the numpy docstrings without a warning, so it never rots (deliverable 5)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_api_reference_builds_without_warnings(tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "-q", "-b", "html", str(ROOT / "docs" / "api"), str(tmp_path)],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    html = (tmp_path / "index.html").read_text()
    for name in ("mrm.api.reconstruct", "mrm.api.polygonize", "PixelSet.from_image", "GeoRef", "user_guide"):
        assert name in html, name
