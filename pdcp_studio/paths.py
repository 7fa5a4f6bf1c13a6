"""Where the shipped resources (profile trees, example systems, icons) live.

A source checkout or editable install has ``resources/`` beside the package; a frozen
desktop build has it under ``sys._MEIPASS``; a wheel installs it as data files under
``<prefix>/share/pdcp-studio``.
"""

from __future__ import annotations

import sys
from functools import cache
from pathlib import Path


@cache
def resources_dir() -> Path:
    candidates = [Path(__file__).resolve().parent.parent / "resources"]
    if hasattr(sys, "_MEIPASS"):
        candidates.insert(0, Path(sys._MEIPASS) / "resources")
    candidates.append(Path(sys.prefix) / "share" / "pdcp-studio")
    for c in candidates:
        if (c / "systems").is_dir():
            return c
    raise FileNotFoundError("PDCP Studio's resources folder is missing from this installation")


def systems_dir() -> Path:
    return resources_dir() / "systems"


def profiles_dir() -> Path:
    return resources_dir() / "profiles"
