"""Which files are captures, for a drop, the recent files and Open…: one list, the
reader's (``bus.trace.files.capture.CAPTURE_SUFFIXES``, gzipped too), and MF4, which python-can
reads only with its ``mf4`` extra (asammdf): offered all the same, the trace then names
what is missing rather than the file being refused without a word. The reader tells the
format by content; the name only decides where a dropped file goes."""

from __future__ import annotations

import importlib.util
from pathlib import Path

from pdcp_studio.app.i18n import translate
from pdcp_studio.bus.trace.files.capture import CAPTURE_SUFFIXES

MF4_SUFFIX = ".mf4"
#: Every name a capture may have (without ``.gz``).
SUFFIXES = (*CAPTURE_SUFFIXES, MF4_SUFFIX)


def mf4_readable() -> bool:
    """python-can's mf4 extra (asammdf) is installed."""
    return importlib.util.find_spec("asammdf") is not None


def is_capture_name(path: str | Path) -> bool:
    """``path`` is named as a capture (``.asc``, ``.blf``, …, or one of them ``.gz``)."""
    name = Path(path).name.lower().removesuffix(".gz")
    return name.endswith(SUFFIXES)


def open_filter() -> str:
    """Open…'s file types: the captures the reader reads (MF4 named as missing when its
    extra is not installed), then any file (the reader tells by content)."""
    globs = " ".join(f"*{s} *{s}.gz" for s in CAPTURE_SUFFIXES)
    captures = translate("MonitorDock", "Captures ({globs})").format(globs=f"{globs} *.mf4")
    mf4 = (translate("MonitorDock", "ASAM MDF4 (*.mf4)") if mf4_readable() else translate(
        "MonitorDock", "ASAM MDF4, needs python-can's mf4 extra, not installed (*.mf4)"))
    return ";;".join((captures, mf4, translate("MonitorDock", "All files (*)")))
