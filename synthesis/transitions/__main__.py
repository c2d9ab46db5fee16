"""Run the transitions command line (see synthesis.transitions.cli)."""

import sys

from synthesis.transitions.cli import main

if __name__ == "__main__":
    sys.exit(main())
