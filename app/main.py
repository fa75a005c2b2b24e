"""Entry point of the ``mrm`` command: the GUI without arguments, headless subcommands otherwise.

The dispatch lives in :func:`mrm.cli.main` so that the command works without the ``gui`` extra (Qt).
"""

from __future__ import annotations

import sys

from mrm.cli import main

__all__ = ["main"]

if __name__ == "__main__":
    sys.exit(main())
