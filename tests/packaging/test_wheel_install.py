"""The wheel, installed as a user would, outside the repository and without Qt (issue 12, deliverable 2).

Builds the wheel and the sdist from this tree, installs the wheel with its core dependencies only into a
fresh virtual environment in a temporary folder, and runs the installed ``mrm`` there: ``--version``,
``info`` on a bundled example, a ``reconstruct``, the bare command (which must ask for the gui extra), and
the package data (examples, user guide, licence). pip may reuse its download cache.
"""

from __future__ import annotations

import json
import os
import shutil
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
    # As a user's shell runs it: PYTHONDONTWRITEBYTECODE (set on some machines) makes setuptools warn that
    # it skips byte-compiling, which says nothing about the project.
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    done = subprocess.run(
        [sys.executable, "-m", "build", "--outdir", str(out), str(ROOT)],
        check=True,
        capture_output=True,
        text=True,
        env=env,
    )
    (out / "build.log").write_text(done.stdout + done.stderr)
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

    version = _run(installed, "mrm", "--version", cwd=tmp_path)
    assert version.stdout.strip() == "mrm 0.1.0" and version.stderr == ""

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


def test_the_build_prints_no_warning(dist: Path):
    log = (dist / "build.log").read_text()
    warnings = [line for line in log.splitlines() if "warning" in line.lower() or "would be ignored" in line]
    assert warnings == []


def _tracked_files() -> set[str]:
    if (ROOT / ".git").exists():
        listed = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True)
        return set(listed.stdout.split())
    # an unpacked sdist: its own files, less what the build adds
    skip = {"PKG-INFO", "setup.cfg"}
    return {
        str(p.relative_to(ROOT))
        for p in ROOT.rglob("*")
        if p.is_file()
        and p.name not in skip
        and not any(
            part in ("__pycache__", ".venv", "dist", "build") or part.endswith(".egg-info")
            for part in p.relative_to(ROOT).parts
        )
    }


def test_the_sdist_holds_exactly_the_tracked_files(dist: Path):
    with tarfile.open(next(dist.glob("*.tar.gz"))) as tar:
        names = {m.name.split("/", 1)[1] for m in tar.getmembers() if m.isfile()}
    added_by_build = {"PKG-INFO", "setup.cfg"} | {n for n in names if ".egg-info/" in n}
    assert names - added_by_build == _tracked_files() - {".gitignore"}


def test_the_index_page_metadata_is_complete(dist: Path):
    with zipfile.ZipFile(next(dist.glob("*.whl"))) as whl:
        meta = whl.read(next(n for n in whl.namelist() if n.endswith(".dist-info/METADATA"))).decode()
    fields = [line.split(": ", 1) for line in meta.split("\n\n", 1)[0].splitlines() if ": " in line]
    values: dict[str, list[str]] = {}
    for key, value in fields:
        values.setdefault(key, []).append(value)
    assert values["Name"] == ["mr-modeler"]
    assert "3D" in values["Summary"][0]
    assert values["License-Expression"] == ["MIT"]
    assert "Typing :: Typed" in values["Classifier"]
    assert "Topic :: Scientific/Engineering :: GIS" in values["Classifier"]
    assert any(url.startswith("Paper, https://doi.org/") for url in values["Project-URL"])
    assert "voxels" in values["Keywords"][0]


def test_the_readme_install_commands_name_what_the_build_makes(dist: Path):
    import tomllib

    readme = (ROOT / "README.md").read_text()
    section = readme.split("## Installing", 1)[1].split("\n## ", 1)[0]
    extras = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"])
    wheel = next(dist.glob("*.whl")).name
    targets = [
        line.split("pip install", 1)[1].split("#")[0].strip().strip("'")
        for line in section.splitlines()
        if line.startswith("pip install")
    ]
    assert targets, "the README gives no install command"
    for target in targets:
        where, _, named = target.partition("[")
        assert where in (".", f"dist/{wheel}"), target
        assert set(named.rstrip("]").split(",")) - {""} <= extras, target
    assert "." in [t.partition("[")[0] for t in targets] and f"dist/{wheel}" in [
        t.partition("[")[0] for t in targets
    ]


def test_version_warns_when_the_unrelated_mrm_distribution_is_installed_too(installed: Path, tmp_path: Path):
    site = Path(
        _run(
            installed,
            "python",
            "-c",
            "import sysconfig; print(sysconfig.get_paths()['purelib'])",
            cwd=tmp_path,
        ).stdout.strip()
    )
    foreign = (
        site / "mrm-0.1.0.dist-info"
    )  # what `pip install mrm` (the 2019 project) leaves beside its files
    foreign.mkdir()
    try:
        (foreign / "METADATA").write_text("Metadata-Version: 2.1\nName: mrm\nVersion: 0.1.0\n")
        done = _run(installed, "mrm", "--version", cwd=tmp_path)
    finally:
        shutil.rmtree(foreign)
    assert done.stdout.strip() == "mrm 0.1.0"
    assert "unrelated distribution 'mrm 0.1.0'" in done.stderr and "mr-modeler" in done.stderr
