"""Run the timing command line (see synthesis.timing.cli)."""

import sys

from synthesis.timing.cli import main

if __name__ == "__main__":
    sys.exit(main())
