"""``python -m mrm``: the headless subcommands (``python -m mrm scale …``).

The desktop application is ``python -m mrm.app`` (or ``mrm`` without a subcommand).
"""

import sys

from mrm.cli import main

sys.exit(main())
