"""What the main window's parts share: the default bus, file filters.

Its own module, free of Qt, so that :mod:`main_window`, its controllers and the command
line can all import these without importing each other.
"""

from __future__ import annotations

DEFAULT_BUS = "sim:transradial"
OFFLINE_SYSTEM = "transradial.json"
FILE_FILTERS = ("PDCP files (*.json *.pdcfg);;System files (*.json);;"
                "Stored configurations (*.pdcfg);;All files (*)")
