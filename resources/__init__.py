"""Files shipped inside the ``mrm`` package: the example projects and the user guide.

The folder ``resources/`` of the source tree is the package ``mrm.resources`` and ``docs/`` is ``mrm.docs``
(pyproject.toml), so a wheel carries them and these functions find them with :mod:`importlib.resources`
in a source checkout, an editable install and an installed wheel alike.
"""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path

__all__ = ["default_example", "docs_dir", "example_projects", "examples_dir", "user_guide"]

#: The example opened by a bare ``mrm`` (the first existing one).
DEFAULT_EXAMPLES = ("fig12-dss-combinations.mrm", "fig12.mrm", "four-representations.mrm")


def _path(package: str, *parts: str) -> Path:
    # Wheels install as plain folders, so the resource is a real file (not inside a zip).
    return Path(str(files(package).joinpath(*parts)))


def examples_dir() -> Path:
    """The folder of the bundled example projects (``.mrm``)."""
    return _path("mrm.resources", "examples")


def example_projects() -> list[Path]:
    """Every bundled example project, sorted by name."""
    d = examples_dir()
    return sorted(d.glob("*.mrm")) if d.is_dir() else []


def default_example() -> Path | None:
    """The example project a bare ``mrm`` opens (None when none is installed)."""
    for name in DEFAULT_EXAMPLES:
        p = examples_dir() / name
        if p.is_file():
            return p
    found = example_projects()
    return found[0] if found else None


def docs_dir() -> Path:
    """The folder of the user guide and its pages (``docs/`` of the source tree)."""
    return _path("mrm.docs")


def user_guide() -> Path:
    """The user guide, ``user-guide.md`` (Markdown; its pictures are in ``img/`` beside it)."""
    return docs_dir() / "user-guide.md"
