"""``can-bridge --serial PORT --bus can:…``: CAN frames between an SLCAN line and a bus.

The reference arbitrator firmware (``firmware/``) runs on QEMU's lm3s6965evb with its CAN
side on a UART speaking SLCAN text (``t1230A..\\r``); this command joins that UART (a
pseudo-terminal) to any python-can bus where simulated devices run — python-can's own
``slcan`` interface on one side, the ``can:`` URL's bus on the other, one thread each way.
``firmware/run-qemu.sh`` starts it. It runs until interrupted (or ``--seconds``).
"""

from __future__ import annotations

import argparse
import sys
import threading
import time

from pdcp_studio.bus.connection import EchoFilter


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("can-bridge",
                              help="bridge an SLCAN serial line (a firmware's CAN side) to a bus",
                              description=__doc__.split("\n\n")[0])
    p.add_argument("--serial", required=True, metavar="PORT",
                   help="the SLCAN serial port, e.g. /dev/pts/7 (QEMU's UART1)")
    p.add_argument("--bus", required=True, metavar="URL",
                   help="can:INTERFACE:CHANNEL[@BITRATE], e.g. can:udp_multicast:239.0.0.1")
    p.add_argument("--seconds", type=float, help="stop after this long (default: until Ctrl-C)")
    p.set_defaults(func=run)


def _pump(source: object, sink: object, stop: threading.Event, counter: list[int], *,
          sent: EchoFilter | None = None, echoes: EchoFilter | None = None) -> None:
    """Frames from ``source`` to ``sink`` until ``stop`` (standard data frames only).

    A bus that hears its own sends (udp_multicast) gives the firmware's frames back: those are
    remembered in ``sent`` when sent to it and dropped as ``echoes`` when they come back, or
    the firmware would hear its own beacons as another arbitrator's."""
    while not stop.is_set():
        try:
            msg = source.recv(0.1)  # type: ignore[attr-defined]
        except Exception:  # a closed port ends the bridge
            stop.set()
            return
        if msg is None or msg.is_error_frame or msg.is_remote_frame or msg.is_extended_id:
            continue
        key = (msg.arbitration_id, bytes(msg.data))
        if echoes is not None and echoes.is_echo(key, time.monotonic()):
            continue
        try:
            if sent is not None:
                sent.sent(key, time.monotonic())
            sink.send(msg)  # type: ignore[attr-defined]
            counter[0] += 1
        except Exception:  # a full or closed bus drops the frame, as CAN would
            continue


def run(args: argparse.Namespace) -> int:
    import can

    from pdcp_studio.bus.connection import _ECHOING
    from pdcp_studio.bus.session.urls import check_bus_url, open_spec
    from pdcp_studio.cli.main import BadInput

    spec = check_bus_url(args.bus)  # BusUrlError: exit 2, as from every command
    if spec.kind != "can":
        raise BadInput(f"--bus {args.bus}: can-bridge joins a can: bus (can:INTERFACE:CHANNEL)")
    if args.seconds is not None and args.seconds <= 0:
        raise BadInput(f"--seconds {args.seconds}: must be positive")
    # The bus first: the firmware starts listening for another arbitrator when its SLCAN line
    # is opened ("O"), so the bus must be heard by then.
    bus = open_spec(spec)
    try:
        line = can.Bus(interface="slcan", channel=args.serial, sleep_after_open=0,
                       bitrate=1_000_000)
    except Exception as err:  # python-can raises several kinds here
        bus.shutdown()
        print(f"pdcp-studio: cannot open {args.serial} as SLCAN: {err}", file=sys.stderr)
        return 1
    stop = threading.Event()
    counts = ([0], [0])
    own = EchoFilter() if type(bus).__name__ in _ECHOING else None
    threads = [threading.Thread(target=_pump, args=(line, bus, stop, counts[0]),
                                kwargs={"sent": own}, name="can-bridge serial→bus", daemon=True),
               threading.Thread(target=_pump, args=(bus, line, stop, counts[1]),
                                kwargs={"echoes": own}, name="can-bridge bus→serial",
                                daemon=True)]
    for t in threads:
        t.start()
    print(f"bridging {args.serial} (SLCAN) and {args.bus}", file=sys.stderr, flush=True)
    started = time.monotonic()
    try:
        while not stop.is_set() and (args.seconds is None
                                     or time.monotonic() - started < args.seconds):
            time.sleep(0.1)
    except KeyboardInterrupt:
        pass
    finally:
        stop.set()
        for t in threads:
            t.join(timeout=1.0)
        for end in (line, bus):
            try:
                end.shutdown()
            except Exception:  # closing what may already be gone
                pass
    print(f"bridged {counts[0][0]} frame(s) to the bus and {counts[1][0]} to {args.serial}",
          file=sys.stderr)
    return 0
