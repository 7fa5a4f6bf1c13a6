"""What the main window's parts share: the default bus, file filters, optional leaf modules.

Its own module so that :mod:`main_window` and the mixins it is built from can all import
these without importing each other.
"""

from __future__ import annotations

import importlib
from typing import Any

DEFAULT_BUS = "sim:transradial"
OFFLINE_SYSTEM = "transradial.json"
FILE_FILTERS = ("PDCP files (*.json *.pdcfg);;System files (*.json);;"
                "Stored configurations (*.pdcfg);;All files (*)")


def optional_module(name: str) -> Any:
    """A leaf module of the app that this build may not have yet (None if absent)."""
    try:
        return importlib.import_module(f"pdcp_studio.app.{name}")
    except ModuleNotFoundError as err:
        if err.name == f"pdcp_studio.app.{name}":
            return None
        raise
