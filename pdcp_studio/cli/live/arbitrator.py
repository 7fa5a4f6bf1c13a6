"""``pdcp-studio arbitrator --bus can:IFACE:CHANNEL [--memory FILE] [--host-serial PORT]
[--no-autoconfigure]``.

A headless bus arbitrator for a real (or a multicast) bus: it binds and sets up the devices,
runs start-up with its memory and the hot-swap duty cycle, and logs joins, leaves, links and
plans to stdout, one line each, until Ctrl-C (or ``--seconds``). With ``--host-serial`` it
also serves the host link on that serial port, so a PC can reach it as ``serial:PORT``.

One arbitrator per bus (reference §5): another arbitrator heard while listening (its beacons,
never one frame) keeps this one off the bus — one line on stderr, exit 1. One that appears
later makes it stop writing at once and say so; it stays up, serves its host link read-only
(writes and transactions refused in words) and takes the bus back when the other's beacons
have been gone for five beacon intervals (2.5 s) and a random wait of up to as many again,
saying that too.
"""

from __future__ import annotations

import argparse
import signal
import sys
import threading
import time
from typing import Any

from pdcp_studio.cli import options
from pdcp_studio.model.safe_text import shown


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser(
        "arbitrator",
        help="run a headless PDCP bus arbitrator on a CAN bus",
        description="Bind, set up and link the devices on a CAN bus; log what happens.",
    )
    parser.add_argument("--bus", required=True, metavar="URL",
                        help="can:INTERFACE:CHANNEL[@BITRATE], e.g. can:socketcan:can0")
    parser.add_argument("--memory", metavar="FILE",
                        help="the arbitrator's non-volatile memory (created if missing)")
    parser.add_argument("--host-serial", metavar="PORT",
                        help="also serve the host link on this serial port ('pty' for a new "
                             "pseudo-terminal)")
    parser.add_argument("--no-profile-layer", action="store_true",
                        help="bind and set up only; no start-up or duty cycle")
    parser.add_argument("--no-autoconfigure", action="store_true",
                        help="start-up and the duty cycle implement the stored configuration "
                             "and find replacements but never autoconfigure (kept in memory; "
                             "without the flag the stored policy holds)")
    parser.add_argument("--seconds", type=options.SECONDS, metavar="N",
                        help="stop after N seconds instead of waiting for Ctrl-C")
    parser.add_argument("--startup-quiet", type=options.WAIT_SECONDS, metavar="S",
                        help="seconds without bind requests before start-up runs")
    parser.set_defaults(func=run)


def describe(event: Any) -> str | None:
    """One log line for an event (None for per-frame traffic)."""
    from pdcp_studio.bus import events as ev

    if isinstance(event, ev.DeviceJoined):
        return f"joined {event.key}"
    if isinstance(event, ev.DeviceLeft):  # why on a line of its own (the first is the event)
        return f"left {event.key}" + (f"\n  why: {event.why}" if event.why else "")
    if isinstance(event, ev.LinkMade):
        return f"link made {event.link}"
    if isinstance(event, ev.LinkRemoved):
        return f"link removed {event.link}"
    if isinstance(event, ev.BusError):
        return f"error {event.message}"
    if isinstance(event, ev.BusState):  # a yield on start is the error line on stderr
        if event.state == "yielded" and "read-only" not in event.message:
            return None
        return f"{ev.BUS_STATE_TEXT.get(event.state, event.state)}: {event.message}"
    if isinstance(event, ev.TerminalsUnconnected):
        return f"policy {event.why}"
    if isinstance(event, ev.PlanApplied):
        plan = event.plan
        lines = [f"plan {plan.mode}: {len(plan.added)} added, {len(plan.removed)} removed, "
                 f"{len(plan.final_links)} links"]
        lines += [f"  {a.op.value} {a.link} ({a.reason})" for a in plan.actions]
        result = getattr(event, "result", None)
        if event.own and result is not None and plan.actions:  # what held it, and verified
            held = ", ".join(str(k) for k in result.held) or "nobody (no part moves)"
            lines.append(f"  on its own: held {held}; read back "
                         + ("verified" if result.verified else "NOT as written"))
        return "\n".join(lines)
    return None


def run(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.session.urls import check_bus_url
    from pdcp_studio.cli.main import EXIT_BAD_INPUT, EXIT_FAILURE, BadInput

    spec = check_bus_url(args.bus)  # BusUrlError: exit 2, as from every command
    if spec.kind != "can":
        raise BadInput(f"--bus {args.bus}: the arbitrator runs on a can: bus "
                       "(can:INTERFACE:CHANNEL[@BITRATE])")
    if args.memory is not None:
        from pdcp_studio.cli.live.scan import check_memory_path

        check_memory_path(args.memory)
    server_cls = None
    if args.host_serial:
        try:
            from pdcp_studio.bus.hostlink.server import HostLinkServer
        except ImportError as err:
            print(f"pdcp-studio: --host-serial needs the host-link server, which this "
                  f"installation lacks ({err})", file=sys.stderr)
            return EXIT_BAD_INPUT
        server_cls = HostLinkServer

    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.cli.live.arbitrator_log import ArbitratorLog

    # One line per event (names escaped), each said once, errors at most 5 lines a second.
    log = ArbitratorLog(describe)

    from pdcp_studio.bus.arbitrator.claim import LISTEN_S

    options: dict[str, Any] = {"memory": args.memory, "name": "arbitrator",
                               "profile_layer": not args.no_profile_layer,
                               "listen_s": LISTEN_S, "take_back": True}
    if args.no_autoconfigure:
        options["autoconfigure"] = False
    if args.host_serial:
        options["frame_events"] = True  # the host link's monitor passes the bus's frames on
    if args.startup_quiet is not None:
        options["startup_quiet_s"] = args.startup_quiet
    stop = threading.Event()
    main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGTERM, lambda *_: stop.set()) if main_thread else None
    from pdcp_studio.bus.reopen import open_reopening

    log.install()  # warnings: said once (not again beside their event), rate-bounded
    try:
        bus = open_reopening(spec)  # a pulled adapter is reopened; the outage is said once
    except BaseException:
        log.uninstall()
        raise
    try:
        arbitrator = Arbitrator(bus, **options)
    except BaseException:
        bus.shutdown()
        log.uninstall()
        raise
    server = None
    code = 0
    try:
        arbitrator.subscribe(log.on_event)
        if server_cls is not None:
            server = server_cls(arbitrator, args.host_serial)
            where = server.slave_path or args.host_serial
            print(f"host link on {where}", flush=True)
        print(shown(f"arbitrator on {spec.url}"
                    + (f", memory {args.memory}" if args.memory else "")), flush=True)
        if not arbitrator.read_policy().autoconfigure:
            print("policy: autoconfigure off (start-up and the duty cycle link nothing new)",
                  flush=True)
        deadline = None if args.seconds is None else time.monotonic() + args.seconds
        while not stop.is_set():
            if arbitrator.yielded and not arbitrator.read_only:  # another arbitrator was on
                code = EXIT_FAILURE  # the bus before this one wrote (reference §5)
                break
            if deadline is not None and time.monotonic() >= deadline:
                break
            log.pump(0.1)
    except KeyboardInterrupt:
        pass
    finally:
        if server is not None:
            server.close()
        arbitrator.close()
        if main_thread:
            signal.signal(signal.SIGTERM, previous)
        log.pump(0, final=True)
        log.uninstall()
    if code:
        print(f"pdcp-studio: error: {spec.url}: {arbitrator.bus_message}", file=sys.stderr)
    print("arbitrator stopped", flush=True)
    return code
