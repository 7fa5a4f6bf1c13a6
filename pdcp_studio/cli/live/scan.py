"""``pdcp-studio scan --bus URL [--json]``: everything on a live bus, as a system.

On a ``can:`` bus PDCP Studio is the arbitrator: it binds the devices it hears, runs start-up
with its own memory (``--memory FILE``, else an empty one), then scans (contracts §2). On a
``sim:`` bus the built-in prosthesis starts up first. ``--json`` prints a ``pdcp-system/1``
document with ``node_id`` on devices and output channels; otherwise a short listing.
Progress goes to stderr when it is a terminal.
"""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING, Any

from pdcp_studio.cli import options
from pdcp_studio.model.safe_text import shown

if TYPE_CHECKING:
    from pdcp_studio.bus.session.base import BusSession, ProgressFn
    from pdcp_studio.model.system import System

#: Seconds a can: bus gets to bind its devices and run start-up before the scan.
DEFAULT_SETTLE_S = 3.0


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("scan", help="read the whole bus: devices, channels, links",
                              description="Read every device's parameters and the links.")
    p.add_argument("--bus", required=True, metavar="URL",
                   help="sim:NAME, can:INTERFACE:CHANNEL[@BITRATE] or serial:PORT[@BAUD]")
    p.add_argument("--json", action="store_true", help="print a pdcp-system/1 document")
    p.add_argument("--memory", metavar="FILE",
                   help="the arbitrator's stored-configuration file (can: and sim: buses)")
    p.add_argument("--window", type=int, default=8, metavar="N",
                   help="devices read at the same time (default 8)")
    p.add_argument("--settle", type=options.WAIT_SECONDS, default=DEFAULT_SETTLE_S,
                   metavar="SECONDS",
                   help="time a can: bus gets to bind and start up (default 3)")
    p.set_defaults(func=run)


def open_bus_session(url: str, *, memory: str | None = None, settle: float | None = None,
                     **options: Any) -> BusSession:
    """``open_session`` for a command; a bad URL raises BusUrlError (exit 2, the same line
    from every command), other user errors BadInput."""
    from pdcp_studio.bus.session.opening import open_session
    from pdcp_studio.bus.session.urls import check_bus_url
    from pdcp_studio.cli.main import BadInput

    spec = check_bus_url(url)
    if memory is not None:
        if spec.kind == "serial":
            raise BadInput(f"--memory: the arbitrator behind {url} keeps its own memory")
        check_memory_path(memory)
        options["memory"] = memory
    if settle is not None and spec.kind in ("can", "serial"):
        options["settle_timeout"] = settle
    if spec.kind != "serial":
        options.setdefault("frame_events", False)  # nobody here shows frames: skip decoding
    return open_session(url, **options)


def check_memory_path(path: str) -> None:
    """``--memory FILE`` must be a readable memory image, or a new file in an existing folder.

    Checked before the bus opens, so a wrong path is bad input (exit 2) instead of an
    arbitrator that cannot read its memory and never settles.
    """
    from pathlib import Path

    from pdcp_studio.cli.main import BadInput

    memory = Path(path)
    if memory.is_dir():
        raise BadInput(f"--memory {path}: is a directory, not a memory file")
    if memory.exists():
        from pdcp_studio.bus.arbitrator.memory import memory_file_problem

        problem = memory_file_problem(memory)  # a memory image only: never a .pdcfg, garbage
        if problem is not None:
            raise BadInput(f"--memory {path}: {problem}")
    elif not memory.parent.is_dir():
        raise BadInput(f"--memory {path}: no folder {memory.parent}")


def stderr_progress(enabled: bool) -> ProgressFn | None:
    """A progress callback writing one updating line to stderr, or None."""
    if not enabled:
        return None

    def report(done: int, total: int, text: str) -> None:
        end = "\n" if done >= total else ""
        print(f"\r\033[K{done}/{total} {text}"[:200], end=end, file=sys.stderr, flush=True)

    return report


def sorted_system(system: System) -> System:
    """The same system with its devices in key order (a bus reports them as they joined)."""
    from pdcp_studio.model.system import System

    return System(sorted(system.devices.values(), key=lambda d: d.key), system.links)


def format_system(system: System) -> str:
    """A short listing of a scanned system, with node IDs and links: each part and channel
    by its one name (``cli/naming.py``), the numbers beside it in brackets."""
    from pdcp_studio.cli.naming import names_for

    system = sorted_system(system)
    names = names_for(system)
    lines = [f"{len(system.devices)} device(s), {len(system.links)} link(s)"]
    for dev in system.devices.values():
        state = "  (missing)" if not dev.present else ""
        node = f"node {dev.node_id}" if dev.node_id else "no node ID"
        lines.append(f"{names.part(dev.key)}{state}  [{dev.key}, {node}]")
        for ch in sorted(dev.channels.values(), key=lambda c: c.index):
            extra = f", node {ch.node_id}" if ch.is_output and ch.node_id else ""
            lines.append(f"  {ch.direction.value:<6} {names.channel_only(dev.ref(ch.index))}  "
                         f"[#{ch.index}, type 0x{ch.type:04X}, profile 0x{ch.profile:04X}"
                         f"{extra}]")
    for link in system.links:
        lines.append(f"link {names.link(link)}  [{link}]")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    from pdcp_studio.cli.main import BadInput
    from pdcp_studio.storage import system_file

    if not 1 <= args.window <= 254:
        raise BadInput(f"--window {args.window}: must be 1…254 (devices read at the same time)")
    session = open_bus_session(args.bus, memory=args.memory, settle=args.settle,
                               scan_window=args.window)
    try:
        system = session.scan(stderr_progress(sys.stderr.isatty()))
    finally:
        session.close()
    if args.json:
        sys.stdout.write(system_file.dumps(system, node_ids=True))
    else:
        print(shown(format_system(system), newlines=True))
    return 0
