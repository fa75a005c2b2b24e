"""A user's script that calls the library type-checks under ``mypy --strict`` with precise types (issue 31).

Geometries are shapely's classes (precise with the ``types-shapely`` stubs of the test extra, docs/adr/0053),
models are ``Model | Literal[...]`` (a typo is a type error), results are the exported result classes, and
batches are object arrays. The library is read as an installed package is: its own errors are not the user's.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

GOOD = """
from __future__ import annotations

import numpy as np
import numpy.typing as npt
from shapely.geometry import MultiPolygon, Polygon, box

import mrm
from mrm.api import ObjectArray, Polygonal

img: npt.NDArray[np.bool_] = np.zeros((4, 4), bool)
img[1:3, 1:3] = True
poly: Polygon | MultiPolygon = mrm.reconstruct(img, "gauss")
area: float = poly.area
world: Polygonal = mrm.reconstruct(img, mrm.Model.GAUSS, transform=(10, 0, 5e5, 0, -10, 4.2e6))
ps: mrm.PixelSet = mrm.discretize(box(0, 0, 2, 2), "gauss")
from_dict: mrm.PixelSet = mrm.discretize({"type": "Point", "coordinates": [1, 2]})
many: ObjectArray = mrm.reconstruct([img, img], "standard")
parts: dict[int, Polygon | MultiPolygon] = mrm.polygonize(np.array([[1, 2]]))
d: mrm.HausdorffDistance = mrm.hausdorff(poly, box(0, 0, 1, 1))
b: mrm.BoundResult = mrm.bound("DSS 2, DSS 0.5", "gauss")
segments: list[mrm.Segment] = mrm.segment("0011", mode="maximal")
bigger: mrm.PixelSet = mrm.scale(ps, 2, model="supercover")
turned: mrm.PixelSet = mrm.rotate(ps, 30)
u: Polygonal = mrm.union(poly, box(0, 0, 1, 1), "gauss")
reveal_type(mrm.reconstruct(img))
reveal_type(mrm.simplify(box(0, 0, 9, 9), 0.5))
reveal_type(mrm.hausdorff([poly], poly))
reveal_type(mrm.corefine(poly, poly))
"""

BAD = """
import numpy as np
from shapely.geometry import box

import mrm

img = np.zeros((4, 4), bool)
mrm.reconstruct(img, "gaus")  # BAD: a misspelt model
mrm.segment("0011", mode="greed")  # BAD: a misspelt mode
name: str = mrm.reconstruct(img).area  # BAD: the area is a float
count: int = mrm.hausdorff(box(0, 0, 1, 1), img).value  # BAD: a HausdorffDistance's value is a float
mrm.discretize(42)  # BAD: not a geometry
"""

CONFIG = """
[mypy]
strict = True
[mypy-mrm.*]
# an installed library's own errors are not reported to its users
ignore_errors = True
"""


def test_a_users_script_is_mypy_strict_clean_with_precise_types(tmp_path):
    (tmp_path / "mrm").symlink_to(ROOT / "model", target_is_directory=True)  # model/ is the package mrm
    (tmp_path / "good.py").write_text(GOOD)
    (tmp_path / "bad.py").write_text(BAD)
    (tmp_path / "mypy.ini").write_text(CONFIG)
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "mypy",
            "--config-file",
            "mypy.ini",
            "--cache-dir",
            str(tmp_path / ".c"),
            "good.py",
            "bad.py",
        ],
        cwd=tmp_path,
        capture_output=True,
        text=True,
    )
    out = done.stdout
    errors = [line for line in out.splitlines() if ": error:" in line]
    assert not [e for e in errors if e.startswith("good.py")], out
    bad_lines = {i for i, line in enumerate(BAD.splitlines(), 1) if "# BAD" in line}
    flagged = {int(m.group(1)) for m in re.finditer(r"^bad\.py:(\d+): error", out, re.M)}
    assert flagged == bad_lines, out
    notes = [line.split("Revealed type is ", 1)[1] for line in out.splitlines() if "Revealed type" in line]
    assert len(notes) == 4, out
    assert "Polygon" in notes[0] and "MultiPolygon" in notes[0] and "Any" not in notes[0], notes
    assert "Polygon" in notes[1] and "Any" not in notes[1], notes
    assert "numpy.ndarray" in notes[2] and "object_" in notes[2], notes
    assert notes[3].startswith('"dict[str, ') and "Polygon" in notes[3], notes
