"""Option types checked at parse time: every duration, rate, count and size is finite and in range.

argparse turns an ``ArgumentTypeError`` into exit status 2 and one stderr line that names the
option (``argument --seconds: 'nan' is not a finite number``), which is what contracts §2 asks
of bad input. ``float("nan")``, ``float("inf")`` and ``-1`` are all valid floats, so a plain
``type=float`` lets a run last forever or end before it starts; these types refuse them.

Use: ``p.add_argument("--seconds", type=options.SECONDS, …)``. Every type is a small callable
with a readable ``__name__`` (argparse shows it when a value does not parse at all).
"""

from __future__ import annotations

import argparse
import math
import os
from collections.abc import Callable

#: Longer than any fitting session, short enough that deadline arithmetic stays exact.
MAX_SECONDS = 1e7  # about 115 days


def number(kind: type[float] | type[int] = float, *, low: float, high: float,
           low_open: bool = False, what: str = "number") -> Callable[[str], float]:
    """A parse-time type: ``kind(text)`` that is finite and within low…high.

    ``low_open`` excludes ``low`` itself (``> 0`` for a time that must pass).
    """

    def parse(text: str) -> float:
        try:
            value: float = kind(text)
        except (TypeError, ValueError):
            raise argparse.ArgumentTypeError(
                f"{text!r} is not {'an integer' if kind is int else 'a number'}") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
        below = value <= low if low_open else value < low
        if below or value > high:
            bound = f"more than {low:g}" if low_open else f"at least {low:g}"
            raise argparse.ArgumentTypeError(
                f"{text!r}: {what} must be {bound} and at most {high:g}")
        return value

    parse.__name__ = what
    return parse


def file_name(text: str) -> str:
    """A file to write: not empty (an empty name is bad input, not an OS error)."""
    if not text.strip():
        raise argparse.ArgumentTypeError("an empty file name")
    if "\0" in text:
        raise argparse.ArgumentTypeError("a file name cannot contain a NUL character")
    if os.path.isdir(text):
        raise argparse.ArgumentTypeError(f"{text} is a folder; give a file name in it")
    return text


file_name.__name__ = "file name"

#: A run's length: ``--seconds`` (0: start, then stop at once — what a smoke test wants).
SECONDS = number(low=0.0, high=MAX_SECONDS, what="seconds")
#: A wait that may be zero: ``--startup-quiet``, ``--settle``.
WAIT_SECONDS = number(low=0.0, high=3600.0, what="seconds")
#: A data rate in Hz; 0 means no data (a CAN bus carries at most ~8,000 frames/s).
RATE_HZ = number(low=0.0, high=1000.0, what="rate (Hz)")
