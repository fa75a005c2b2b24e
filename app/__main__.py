import sys

from mrm.app.main import main

sys.exit(main())
