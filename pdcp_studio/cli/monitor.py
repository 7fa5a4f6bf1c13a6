"""``monitor``: decoded PDCP frames, live from a bus or from a capture file.

``monitor --bus URL [--log FILE] [--seconds N]`` listens (it never sends) until N seconds have
passed or Ctrl-C; ``monitor --replay FILE`` decodes a capture in any python-can log format.
``--log`` writes every frame (filters only change what is shown), so it also converts a replayed
capture to another format. The statistics go to stderr, so stdout holds only frames.
"""

from __future__ import annotations

import argparse
import json
import queue
import sys
import time
from collections.abc import Callable, Iterator
from contextlib import ExitStack, closing
from typing import Any

from pdcp_studio.cli import options
from pdcp_studio.cli.main import BadInput

#: How often a live loop wakes up to check its deadline.
POLL_S = 0.1
FILTER_HELP = (
    "show only matching frames (repeatable, all must match): node=N[,N…], "
    "function=TEXT (part of the name) or function=0xNN, direction=to-ba|from-ba|data, errors"
)
_DIRECTIONS = {"to-ba": "device→BA", "from-ba": "BA→device", "data": "channel data"}


def add_subparser(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser("monitor", help="decoded frames, live from a bus or from a capture")
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--bus", metavar="URL", help="sim:NAME, can:INTERFACE:CHANNEL[@BITRATE] …")
    source.add_argument("--replay", metavar="FILE",
                        help="a capture (.asc .blf .csv .log .trc .db, optionally .gz)")
    p.add_argument("--log", metavar="FILE", help="also write every frame to this capture")
    p.add_argument("--seconds", type=options.SECONDS, metavar="N",
                   help="stop after N seconds (live)")
    p.add_argument("--filter", action="append", default=[], metavar="KEY=VALUE",
                   help=FILTER_HELP)
    p.add_argument("--json", action="store_true", help="one JSON list of decoded frames")
    p.set_defaults(func=run)


def make_filter(specs: list[str]) -> Callable[[Any], bool]:
    """A predicate over DecodedFrame from ``--filter`` specs; BadInput names a bad one."""
    tests: list[Callable[[Any], bool]] = []
    for spec in specs:
        key, _, value = spec.partition("=")
        key, value = key.strip().lower(), value.strip()
        if key == "errors" and not value:
            tests.append(lambda f: f.error is not None or f.response == "failure")
        elif key == "node" and value:
            try:
                nodes = {int(v, 0) for v in value.split(",")}
            except ValueError:
                raise BadInput(f"--filter {spec}: node IDs must be integers") from None
            tests.append(lambda f, nodes=nodes: f.node_id in nodes)
        elif key == "function" and value:
            if value.lower().startswith("0x"):
                try:
                    code = int(value, 16)
                except ValueError:
                    raise BadInput(f"--filter {spec}: not a function code") from None
                tests.append(lambda f, code=code: getattr(f.message, "CODE", None) == code)
            else:
                text = value.lower()
                tests.append(lambda f, text=text: text in f.function.lower())
        elif key == "direction" and value in _DIRECTIONS:
            tests.append(lambda f, d=_DIRECTIONS[value]: f.direction == d)
        else:
            raise BadInput(f"--filter {spec!r}: expected {FILTER_HELP.split(': ', 1)[1]}")
    return lambda frame: all(test(frame) for test in tests)


def _can_frames(spec: Any, stop: Callable[[], bool]) -> Iterator[tuple[float, int, bytes, Any]]:
    """Frames of a python-can bus, opened only to listen (the monitor never sends)."""
    from pdcp_studio.bus.urls import open_spec

    bus = open_spec(spec)  # TransportError (exit 1) names the URL when the adapter is missing
    try:
        while not stop():
            msg = bus.recv(timeout=POLL_S)
            if msg is not None:
                yield msg.timestamp, msg.arbitration_id, bytes(msg.data), msg
    finally:
        bus.shutdown()


def learn_links(links: dict, system: Any) -> None:
    """Fill a FrameDecoder's link map from a system with node IDs: frames from an output's
    node ID are channel data on its links, not function codes."""
    links.clear()
    for ref, ch in system.channels():
        if ch.is_output and ch.node_id:
            links[ch.node_id] = (ref, tuple(system.inputs_fed_by(ref)))


def _session_frames(url: str, stop: Callable[[], bool],
                    links: dict | None = None) -> Iterator[tuple[float, int, bytes, Any]]:
    """Frames a bus session reports (sim:, serial:): its FrameSeen events.

    ``links`` (the decoder's link map) is kept current from the session's system, re-read
    whenever a device or link comes or goes.
    """
    from pdcp_studio.bus.events import DeviceJoined, DeviceLeft, FrameSeen, LinkMade, LinkRemoved

    try:
        from pdcp_studio.bus.session import open_session
    except ImportError as err:
        from pdcp_studio.errors import TransportError

        raise TransportError(f"--bus {url}: the bus session is not available ({err})") from err
    seen: queue.Queue[FrameSeen] = queue.Queue()
    session = open_session(url)
    try:
        # The session's callback only enqueues; decoding happens on this thread.
        wanted = (FrameSeen, DeviceJoined, DeviceLeft, LinkMade, LinkRemoved)
        session.subscribe(
            lambda ev: seen.put(ev) if isinstance(ev, wanted) else None)
        if links is not None:
            learn_links(links, session.system())
        while not stop():
            try:
                ev = seen.get(timeout=POLL_S)
            except queue.Empty:
                continue
            if not isinstance(ev, FrameSeen):
                if links is not None:
                    learn_links(links, session.system())
                continue
            yield ev.timestamp, ev.arbitration_id, bytes(ev.data), None
    finally:
        session.close()


def _replay_frames(path: str) -> Iterator[tuple[float, int, bytes, Any]]:
    from pdcp_studio.bus.monitor import read_capture

    for msg in read_capture(path):
        yield msg.timestamp, msg.arbitration_id, bytes(msg.data), msg


def run(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.monitor import CaptureError, FrameDecoder, Recorder

    show = make_filter(args.filter)
    if args.seconds is not None and args.seconds <= 0:
        raise BadInput(f"--seconds {args.seconds}: must be positive")
    links: dict = {}
    decoder = FrameDecoder(links)
    shown: list[dict[str, Any]] = []
    started = time.monotonic()

    def stop() -> bool:
        return args.seconds is not None and time.monotonic() - started >= args.seconds

    if args.replay:
        frames = _replay_frames(args.replay)
    else:
        from pdcp_studio.bus.urls import BusUrlError, parse_bus_url

        try:
            spec = parse_bus_url(args.bus)
        except BusUrlError as err:
            raise BadInput(str(err)) from err
        frames = (_can_frames(spec, stop) if spec.kind == "can"
                  else _session_frames(args.bus, stop, links))
    try:
        with ExitStack() as stack:
            stack.enter_context(closing(frames))  # shuts a live bus down on any exit
            recorder = stack.enter_context(Recorder(args.log)) if args.log else None
            try:
                for timestamp, arbitration_id, data, msg in frames:
                    if recorder is not None:
                        if msg is not None:
                            recorder.write_message(msg)
                        else:
                            recorder.write(arbitration_id, data, timestamp)
                    frame = (decoder.decode_message(msg) if msg is not None
                             else decoder.decode(arbitration_id, data, timestamp))
                    if not show(frame):
                        continue
                    if args.json:
                        shown.append(frame.as_json())
                    else:
                        print(frame.line, flush=True)
            except KeyboardInterrupt:
                pass  # Ctrl-C is how a live monitor ends; the capture is still closed
    except CaptureError as err:
        raise BadInput(str(err)) from err
    if args.json:
        json.dump(shown, sys.stdout, indent=1, ensure_ascii=False)
        sys.stdout.write("\n")
    elapsed = None if args.replay else time.monotonic() - started
    print(decoder.stats.summary(elapsed), file=sys.stderr)
    if args.log:
        print(f"wrote {args.log}", file=sys.stderr)
    return 0
