"""``gui [FILE] [--bus URL] [--screenshot PNG]``: the desktop app (also bare ``pdcp-studio``).

Qt is imported only in ``run``, so the rest of the CLI never pays for it. A FILE that does
not load is bad input (exit 2, naming where); a screenshot that cannot be made is exit 1.
"""

from __future__ import annotations

import argparse
import os
import sys
import time

from pdcp_studio.cli.main import BadInput

_STARTED = time.perf_counter()


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser(
        "gui", help="open the desktop app on a file or a bus",
        description="Open the desktop app on a system file (.json), a stored configuration "
                    "(.pdcfg) or a live bus; without either, on the start page (the guided "
                    "tasks, Connect, Open, the recent files and the simulated prosthesis "
                    "sim:transradial to practise on).")
    p.add_argument("file", nargs="?", metavar="FILE",
                   help="a pdcp-system/1 file, a stored configuration (.pdcfg) or a capture "
                        "(any format monitor --replay reads, told by its content), shown in "
                        "the trace")
    p.add_argument("--bus", metavar="URL",
                   help="a bus URL: sim:NAME, can:INTERFACE:CHANNEL[@BITRATE], serial:PORT")
    p.add_argument("--screenshot", metavar="PNG",
                   help="render the main window once loaded and laid out, save it, exit")
    p.add_argument("--size", metavar="WxH", default=None,
                   help="window size, e.g. 1400x860 (for screenshots)")
    p.add_argument("--lang", metavar="LANG", default=argparse.SUPPRESS,
                   help="the app's language, e.g. de or en (default: the system's)")
    from pdcp_studio.cli.live.change_road import add_archive_argument

    add_archive_argument(p)
    p.set_defaults(func=run)


def _size(text: str | None) -> tuple[int, int] | None:
    if not text:
        return None
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise BadInput(f"--size {text!r}: expected WIDTHxHEIGHT, e.g. 1400x860") from None
    if not (200 <= w <= 8000 and 200 <= h <= 8000):
        raise BadInput(f"--size {text}: each side must be 200…8000 pixels")
    return w, h


def is_capture(path: str) -> bool:
    """``path`` holds a capture, told by its content as ``monitor --replay`` tells it (an
    empty file by its name); a system file, a configuration or anything else is not."""
    from pdcp_studio.bus.trace.files.capture import CAPTURE_SUFFIXES
    from pdcp_studio.bus.trace.files.reader import SNIFF_BYTES, sniff

    if path.lower().endswith((".json", ".pdcfg")) or not os.path.isfile(path):
        return False  # (a pipe is never opened here: the document's opening refuses it)
    try:
        with open(path, "rb") as file:
            head = file.read(SNIFF_BYTES)
    except OSError:
        return False  # the document's opening says why
    if head.startswith(b"\x1f\x8b"):
        return True  # gzip: the reader opens it (a capture, or says why not)
    fmt = sniff(head)
    if fmt == "empty":
        name = os.path.basename(path).lower().removesuffix(".gz")
        return name.endswith((*CAPTURE_SUFFIXES, ".mf4"))
    return fmt is not None


def run(args: argparse.Namespace) -> int:
    if args.file and args.bus:
        raise BadInput("give a FILE or --bus, not both")
    capture = None
    if args.file and is_capture(args.file):
        capture, args.file = args.file, None
    size = _size(args.size)
    if args.bus:
        from pdcp_studio.bus.session.urls import check_bus_url

        check_bus_url(args.bus)  # BusUrlError: exit 2, as from every command
    from pdcp_studio.app import qt_prereqs

    why = qt_prereqs.problem(screenshot=bool(args.screenshot))
    if why is not None:
        print(f"pdcp-studio: {why}", file=sys.stderr)
        return 1
    if args.screenshot and qt_prereqs.needs_offscreen():
        os.environ["QT_QPA_PLATFORM"] = "offscreen"  # no window here: render off screen
    if getattr(args, "archive", None):  # the app's archive for this session (sign_in.py)
        from pdcp_studio.storage.archive.open import ENV_ARCHIVE

        os.environ[ENV_ARCHIVE] = args.archive
    from pdcp_studio.app.application import run_app

    return run_app(args.file, args.bus, args.screenshot, size=size, started=_STARTED,
                   lang=getattr(args, "lang", None), capture=capture)
