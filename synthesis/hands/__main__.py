"""Run the hands command line (see synthesis.hands.cli)."""

import sys

from synthesis.hands.cli import main

if __name__ == "__main__":
    sys.exit(main())
