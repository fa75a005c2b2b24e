"""The installed distribution's version: ``mrm --version``, ``mrm.__version__``, project files' generator.

The distribution is ``mr-modeler`` (a name no other project on the Python Package Index holds); the import
package and the command are ``mrm``, as the design card fixes them. An unrelated distribution named ``mrm``
(version 0.1.0, 2019: an ``mrm/app.py`` and an ``mrm`` script) exists on the index and claims both names, so
installing it beside MR Modeler overwrites files of ours (docs/adr/0054); :func:`foreign_owner` lets
``mrm --version`` say so.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, distribution, version

__all__ = ["DISTRIBUTION", "FOREIGN_DISTRIBUTION", "foreign_owner", "installed_version"]

#: The name the package is installed under (``pip install .`` from a clone, or the built wheel).
DISTRIBUTION = "mr-modeler"

#: The unrelated distribution on the Python Package Index whose files land in our ``mrm`` package.
FOREIGN_DISTRIBUTION = "mrm"


def installed_version() -> str:
    """The installed version of MR Modeler, or ``0+unknown`` for a source tree that was never installed."""
    try:
        return version(DISTRIBUTION)
    except PackageNotFoundError:
        return "0+unknown"


def foreign_owner() -> str | None:
    """``name version`` of the unrelated distribution installed over the ``mrm`` package, or None.

    Only the one known distribution is looked up by name: listing which distribution owns every top-level
    package reads every installed ``RECORD`` (more than a second in a full environment), too slow for
    ``mrm --version``.
    """
    try:
        foreign = distribution(FOREIGN_DISTRIBUTION)
    except PackageNotFoundError:
        return None
    return f"{FOREIGN_DISTRIBUTION} {foreign.version}"
