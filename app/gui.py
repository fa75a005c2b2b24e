"""GUI start-up (issue 6). Until the main window lands, ``mrm`` without a subcommand says so."""

from __future__ import annotations

import sys


def run_gui(args: list[str]) -> int:
    """Start the desktop application."""
    print("mrm: the desktop application is not built yet; see `mrm --help` for the headless commands",
          file=sys.stderr)
    return 2
