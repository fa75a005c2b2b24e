"""The headless ``mrm`` subcommands (DESIGN §9).

Each subcommand lives in its own module of this package and defines::

    NAME: str                       # the subcommand, e.g. "discretize"
    HELP: str                       # one line for ``mrm --help``
    def add_arguments(parser): ...  # its own options (the common ones are added here)
    def run(args) -> dict | None:   # does the work; returns the --json summary (or None)

Modules are discovered automatically, so adding a subcommand never edits this file. Every input error is
an :class:`mrm.errors.MRMError`: it is printed as ``mrm NAME: error: message`` on stderr with exit status 2,
never as a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import json
import pkgutil
import sys
from types import ModuleType
from typing import Any

from mrm.errors import MRMError

#: The discretization models, in the order the CLI lists them.
MODEL_CHOICES = ("standard", "supercover", "gauss")


def _command_modules() -> dict[str, ModuleType]:
    mods: dict[str, ModuleType] = {}
    for info in pkgutil.iter_modules(__path__):
        if info.name.startswith("_"):
            continue
        mod = importlib.import_module(f"{__name__}.{info.name}")
        name = getattr(mod, "NAME", None)
        if isinstance(name, str):
            mods[name] = mod
    return dict(sorted(mods.items()))


def _subcommand_names() -> tuple[str, ...]:
    return tuple(
        info.name.replace("_", "-")
        for info in pkgutil.iter_modules(__path__)
        if not info.name.startswith("_")
    )


#: Names of the subcommands (module names; a module's NAME matches its file name).
SUBCOMMANDS: tuple[str, ...] = _subcommand_names()


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser whose usage errors exit with status 2 and a one-line message (argparse's default)."""


def build_parser() -> argparse.ArgumentParser:
    """Return the parser of every subcommand, each with ``--model`` and ``--json``."""
    parser = _Parser(prog="mrm", description="MR Modeler: multi-representation 2D discrete geometry.")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, mod in _command_modules().items():
        p = sub.add_parser(name, help=getattr(mod, "HELP", ""), description=getattr(mod, "HELP", ""))
        p.add_argument(
            "--model",
            choices=MODEL_CHOICES,
            default=None,
            help="discretization model (default: the project's, or 'standard')",
        )
        p.add_argument("--json", action="store_true", help="print a machine-readable summary on stdout")
        mod.add_arguments(p)
        p.set_defaults(_module=mod)
    return parser


def _json_default(o: Any) -> Any:
    import numpy as np

    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, np.floating):
        return float(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


#: Subcommands that never call a compiled kernel (no first-run notice for them).
NO_KERNELS = frozenset({"bounds"})


def run_cli(argv: list[str]) -> int:
    """Parse ``argv`` (without the program name), run the subcommand, return the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "_module", None) is None:
        parser.print_help()
        return 2
    if args.command not in NO_KERNELS:
        from mrm.warmup import announce_if_cold

        announce_if_cold()  # one line before numba compiles for a minute on a fresh install
    try:
        summary = args._module.run(args)
    except MRMError as e:
        print(f"mrm {args.command}: error: {e}", file=sys.stderr)
        return 2
    except (FileNotFoundError, IsADirectoryError, PermissionError) as e:
        print(f"mrm {args.command}: error: {e.strerror}: {e.filename}", file=sys.stderr)
        return 2
    if args.json and summary is not None:
        try:
            print(json.dumps(summary, default=_json_default), flush=True)
        except BrokenPipeError:
            # `mrm ... --json | head` closed the pipe early: not an error of the command. Point stdout at
            # devnull so the interpreter's final flush does not print a traceback either.
            import os

            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    return 0


def main() -> int:
    """Console entry for running the subcommands without the GUI package."""
    return run_cli(sys.argv[1:])
