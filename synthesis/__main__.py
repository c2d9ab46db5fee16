"""Run the engine's command line (see synthesis.cli)."""

import sys

from synthesis.cli import main

sys.exit(main())
