"""Entry point of the ``mrm`` command: the desktop application without a subcommand, headless otherwise.

This module is the composition root's front door and imports no Qt itself, so ``mrm scale …`` works without
the ``gui`` extra: subcommands, ``--version`` and (without Qt) ``--help`` go to :mod:`mrm.cli`; anything else
starts the application (:func:`mrm.app.gui.run_gui`), which needs PySide6 and pyqtgraph.
"""

from __future__ import annotations

import importlib.util
import sys

from mrm.cli import EXIT_BROKEN_PIPE, build_parser, run_headless, silence_stdout

__all__ = ["main"]


def _gui_available() -> bool:
    return all(importlib.util.find_spec(m) is not None for m in ("PySide6", "pyqtgraph"))


def main(argv: list[str] | None = None) -> int:
    """The ``mrm`` command: a subcommand, ``--version``, or the desktop application (``gui`` extra)."""
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        status = run_headless(args)
        if status is not None:
            return status
        if not _gui_available():
            if args[:1] in (["-h"], ["--help"], ["--help-commands"]):
                build_parser().print_help()
                sys.stdout.flush()
                return 0
            print(
                "mrm: the desktop application needs the gui extra: pip install 'mr-modeler[gui]'. "
                "The headless subcommands work without it: mrm --help",
                file=sys.stderr,
            )
            return 2
        # Qt is imported only here, when the application really starts (the headless paths above never load
        # it: the gui extra is optional).
        from mrm.app.gui import run_gui

        status: int = run_gui(args)
        sys.stdout.flush()
        return status
    except BrokenPipeError:
        silence_stdout()
        return EXIT_BROKEN_PIPE


if __name__ == "__main__":
    sys.exit(main())
