"""The install layout: one import package ``mrm`` mapped from the design card's three source folders."""

from __future__ import annotations

import pathlib
import tomllib

ROOT = pathlib.Path(__file__).resolve().parents[1]
FOLDERS = {"model": "mrm", "app": "mrm.app", "views": "mrm.views"}
#: Data folders shipped as packages (docs/adr/0011): the example projects and the user guide.
DATA = {"resources": "mrm.resources", "docs": "mrm.docs"}


def _declared() -> tuple[set[str], dict[str, str]]:
    cfg = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    return set(cfg["packages"]), dict(cfg["package-dir"])


def test_every_source_package_is_listed_for_the_wheel():
    """A sub-package left out of the list would be missing from an installed `mrm` (ModuleNotFoundError)."""
    packages, package_dir = _declared()
    assert package_dir == {name: folder for folder, name in {**FOLDERS, **DATA}.items()}
    found = set(DATA.values())
    for folder, name in FOLDERS.items():
        for init in (ROOT / folder).rglob("__init__.py"):
            rel = init.parent.relative_to(ROOT / folder).parts
            found.add(".".join((name, *rel)))
    assert found == packages, f"pyproject.toml lists {sorted(packages)}, the tree has {sorted(found)}"


def test_the_one_top_level_import_is_mrm_and_it_is_the_source_tree():
    import mrm
    import mrm.app
    import mrm.views

    assert pathlib.Path(mrm.__file__).resolve() == ROOT / "model" / "__init__.py"
    assert pathlib.Path(mrm.app.__file__).resolve() == ROOT / "app" / "__init__.py"
    assert pathlib.Path(mrm.views.__file__).resolve() == ROOT / "views" / "__init__.py"
