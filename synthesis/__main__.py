"""Run the engine's command line (see synthesis.cli)."""

import sys

from synthesis.cli import main

# Guarded: render worker processes are spawned, and re-import the main module.
if __name__ == "__main__":
    sys.exit(main())
