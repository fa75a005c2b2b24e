"""Entry point of the ``mrm`` command: the GUI without arguments, headless subcommands otherwise."""

from __future__ import annotations

import sys


def main(argv: list[str] | None = None) -> int:
    """Run ``mrm``; subcommands are handled by :mod:`mrm.cli` without importing Qt."""
    args = list(sys.argv[1:] if argv is None else argv)
    from mrm.cli import SUBCOMMANDS, run_cli

    if args and args[0] in SUBCOMMANDS:
        return run_cli(args)
    from mrm.app.gui import run_gui

    return run_gui(args)


if __name__ == "__main__":
    sys.exit(main())
