"""The frozen program's entry point: the ``pdcp-studio`` command line (and app)."""

import sys

from pdcp_studio.cli.main import main

if __name__ == "__main__":
    sys.exit(main())
