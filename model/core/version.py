"""The installed distribution's version: ``mrm --version``, ``mrm.__version__``, project files' generator."""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

__all__ = ["DISTRIBUTION", "installed_version"]

#: The name the package is installed under (``pip install mr-modeler``).
DISTRIBUTION = "mr-modeler"


def installed_version() -> str:
    """The installed version of MR Modeler, or ``0+unknown`` for a source tree that was never installed."""
    try:
        return version(DISTRIBUTION)
    except PackageNotFoundError:
        return "0+unknown"
