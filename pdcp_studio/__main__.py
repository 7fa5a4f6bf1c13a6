"""``python -m pdcp_studio`` runs the command line."""

import sys

from pdcp_studio.cli.main import main

sys.exit(main())
