"""Where PDCP Studio's files are: the shipped resources and the user's own data.

The shipped resources (profile trees, example systems, stored configurations, icons) are
package data of :mod:`pdcp_studio.resources` — in the source tree that package is the
top-level ``resources/`` folder, which ``pdcp_studio/resources`` links to. They are read
through :mod:`importlib.resources`, so a source checkout, an editable install, a wheel, a
``pip install --user`` and the frozen desktop build all find them the same way.

What a user adds (their own and their vendors' profile trees and catalogues) and what the
app keeps (the fitting history) live in the user's data folder (``platformdirs``: on Linux
``$XDG_DATA_HOME/pdcp-studio``, usually ``~/.local/share/pdcp-studio``), beside — never
inside — the shipped resources, which an installation may not let anyone write.
"""

from __future__ import annotations

import os
from functools import cache
from importlib import resources
from pathlib import Path

APP_NAME = "pdcp-studio"
RESOURCES_PACKAGE = "pdcp_studio.resources"


@cache
def resources_dir() -> Path:
    """The shipped resources folder (a real directory in every supported install)."""
    try:
        root = resources.files(RESOURCES_PACKAGE)
    except ModuleNotFoundError:
        root = None
    if root is not None:
        path = Path(str(root))
        if (path / "systems").is_dir():
            return path
    raise FileNotFoundError(
        "PDCP Studio's resources (pdcp_studio/resources: example systems, profile trees) "
        "are missing from this installation; reinstall PDCP Studio")


def systems_dir() -> Path:
    """Shipped example systems (the built-in simulated prostheses)."""
    return resources_dir() / "systems"


def profiles_dir() -> Path:
    """Shipped profile trees."""
    return resources_dir() / "profiles"


def configs_dir() -> Path:
    """Shipped stored-configuration examples (``.pdcfg``)."""
    return resources_dir() / "configs"


def catalogs_dir() -> Path:
    """Shipped device catalogues (VID/PID → vendor, product, kind, icon)."""
    return resources_dir() / "catalog"


def icon_path() -> Path:
    """The application icon (SVG)."""
    return resources_dir() / "icons" / "pdcp-studio.svg"


#: What platformdirs finds the user's data folder from: the folder is looked up once per
#: value of these (a look-up costs ~0.3 ms, and start-up asks ~30 times: every catalogue
#: look-up checks the user's catalogues folder), and again when one changes (a test's home).
_DATA_DIR_ENV = ("XDG_DATA_HOME", "HOME", "APPDATA", "LOCALAPPDATA", "USERPROFILE")


def user_data_dir() -> Path:
    """The user's data folder for PDCP Studio (not created here)."""
    return _user_data_dir(*(os.environ.get(name) for name in _DATA_DIR_ENV))


@cache
def _user_data_dir(*_environment: str | None) -> Path:
    import platformdirs

    return platformdirs.user_data_path(APP_NAME, appauthor=False)


def user_profiles_dir() -> Path:
    """Where a user's and their vendors' profile trees go (``*.json``, merged after the
    shipped ones)."""
    return user_data_dir() / "profiles"


def user_catalogs_dir() -> Path:
    """Where a user's device catalogues go (beside their profile trees)."""
    return user_data_dir() / "catalogs"


def history_path() -> Path:
    """The fitting-history archive: ``$PDCP_STUDIO_HISTORY`` when set, else a file in the
    ``history.sqlite`` in the user's data folder (contracts §2); the archive
    (``storage/history.py``) and ``doctor`` both ask here."""
    env = os.environ.get("PDCP_STUDIO_HISTORY")
    return Path(env) if env else user_data_dir() / "history.sqlite"
