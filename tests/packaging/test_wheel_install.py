"""The wheel, installed as a user would, outside the repository and without Qt (issue 12, deliverable 2).

Builds the wheel and the sdist from this tree, installs the wheel with its core dependencies only into a
fresh virtual environment in a temporary folder, and runs the installed ``mrm`` there: ``--version``,
``info`` on a bundled example, a ``reconstruct``, the bare command (which must ask for the gui extra), and
the package data (examples, user guide, licence). pip may reuse its download cache.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tarfile
import venv
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def dist(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("dist")
    subprocess.run(
        [sys.executable, "-m", "build", "--outdir", str(out), str(ROOT)],
        check=True,
        capture_output=True,
        text=True,
    )
    return out


@pytest.fixture(scope="module")
def installed(dist: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A fresh venv holding the wheel and its core dependencies; returns its bin/ folder."""
    env_dir = tmp_path_factory.mktemp("venv")
    assert ROOT not in env_dir.parents
    venv.EnvBuilder(with_pip=True, clear=True).create(env_dir)
    bindir = env_dir / "bin"
    wheel = next(dist.glob("*.whl"))
    subprocess.run(
        [str(bindir / "python"), "-m", "pip", "install", "-q", str(wheel)],
        check=True,
        capture_output=True,
        text=True,
    )
    return bindir


def _run(bindir: Path, *args: str, cwd: Path, check: bool = True) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["PATH"] = f"{bindir}{os.pathsep}{env.get('PATH', '')}"
    # What is checked here is what the wheel carries and how it starts, not the kernels (the rest of the suite
    # runs them compiled): compiling them cold in the fresh venv would cost minutes of CI for nothing more.
    env["NUMBA_DISABLE_JIT"] = "1"
    return subprocess.run(
        [str(bindir / args[0]), *args[1:]], cwd=cwd, env=env, capture_output=True, text=True, check=check
    )


def test_wheel_holds_one_package_the_examples_the_guide_and_the_licence(dist: Path):
    with zipfile.ZipFile(next(dist.glob("*.whl"))) as whl:
        names = whl.namelist()
    tops = {n.split("/")[0] for n in names if not n.split("/")[0].endswith(".dist-info")}
    assert tops == {"mrm"}
    assert "mrm/py.typed" in names
    assert "mrm/resources/examples/fig12-dss-combinations.mrm" in names
    assert "mrm/docs/user-guide.md" in names
    assert "mrm/docs/img/mrm-window.png" in names
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
    assert not any(n.endswith(".py") and "/examples/" in n for n in names)
    # nothing a run left behind: a warm-up stamp would tell a fresh install its kernels are compiled
    assert not any("__pycache__" in n for n in names)


def test_sdist_holds_the_tests_the_resources_and_the_docs(dist: Path):
    with tarfile.open(next(dist.glob("*.tar.gz"))) as tar:
        names = tar.getnames()
    root = names[0].split("/")[0]
    for member in (
        "LICENSE",
        "tests/conftest.py",
        "tests/packaging/test_wheel_install.py",
        "resources/examples/diamond.mrm",
        "docs/user-guide.md",
        "docs/img/mrm-window.png",
    ):
        assert f"{root}/{member}" in names, member


def test_installed_mrm_runs_without_qt(installed: Path, tmp_path: Path):
    site = _run(installed, "python", "-c", "import mrm, sys; print(mrm.__file__)", cwd=tmp_path).stdout
    assert ROOT not in Path(site.strip()).parents  # the installed copy, not this tree
    freeze = _run(installed, "python", "-m", "pip", "list", "--format=json", cwd=tmp_path).stdout
    names = {p["name"].lower() for p in json.loads(freeze)}
    assert "mr-modeler" in names and not names & {"pyside6", "pyside6-essentials", "pyqtgraph"}

    assert _run(installed, "mrm", "--version", cwd=tmp_path).stdout.strip() == "mrm 0.1.0"

    example = _run(
        installed,
        "python",
        "-c",
        "import mrm.resources as r; from mrm.app.gui import default_example as d; "
        "assert d() == r.default_example(); print(r.examples_dir() / 'diamond.mrm'); "
        "print(r.user_guide())",
        cwd=tmp_path,
    ).stdout.split()
    diamond, guide = Path(example[0]), Path(example[1])
    assert diamond.is_file() and guide.is_file() and "MR Modeler" in guide.read_text()
    info = json.loads(_run(installed, "mrm", "info", str(diamond), "--json", cwd=tmp_path).stdout)
    assert info["pixels"] == 313 and info["components"] == 1  # the digital diamond |x| + |y| ≤ 12

    (tmp_path / "l.pbm").write_text("P1\n3 2\n1 0 0\n1 1 1\n")
    done = _run(installed, "mrm", "reconstruct", "l.pbm", "-o", "out/l.geojson", "--json", cwd=tmp_path)
    assert json.loads(done.stdout)["pixels"] == 4
    fc = json.loads((tmp_path / "out" / "l.geojson").read_text())
    assert fc["features"][0]["geometry"]["type"] == "Polygon"

    bare = _run(installed, "mrm", cwd=tmp_path, check=False)
    assert bare.returncode == 2 and "pip install 'mr-modeler[gui]'" in bare.stderr
