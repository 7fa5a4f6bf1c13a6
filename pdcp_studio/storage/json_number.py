"""The contracts' JSON number: an integer or a ``"0x…"`` string, shared by the JSON loaders."""

from __future__ import annotations

import re
from typing import Any

_HEX = re.compile(r"0[xX][0-9A-Fa-f]+")


def parse_number(value: Any, lo: int, hi: int, *, expected: str = "an integer") -> int:
    """``value`` as an int within lo…hi, else ValueError saying why (no path: callers add it).

    A bare ``"2200"`` is refused, not read as decimal: it was most likely meant as hex.
    """
    if isinstance(value, str):
        if not _HEX.fullmatch(value):
            raise ValueError(f"{value!r} is not a number (an integer or \"0x…\")")
        value = int(value, 16)
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"expected {expected}, got {value!r}")
    if not lo <= value <= hi:
        raise ValueError(f"{value} is out of range {lo}…{hi}")
    return value
