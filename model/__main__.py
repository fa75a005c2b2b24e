"""``python -m mrm``: the same as the ``mrm`` command (headless subcommands, or the GUI without one)."""

import sys

from mrm.cli import main

sys.exit(main())
