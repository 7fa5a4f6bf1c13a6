"""``monitor``: decoded PDCP frames, live from a bus or from a capture file.

``monitor --bus URL [--log FILE] [--seconds N]`` listens (it never sends) until N seconds have
passed or Ctrl-C; ``monitor --replay FILE`` decodes a capture in any python-can log format.
``--log`` writes every frame (filters only change what is shown), so it also converts a replayed
capture to another format. The statistics go to stderr, so stdout holds only frames.

Every line has one time base, live and replayed alike: seconds since the first frame, six
decimals; stderr says so after the statistics, with when the first frame was.
"""

from __future__ import annotations

import argparse
import contextlib
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
ROTATE_MB = options.number(low=0.0, high=1e6, low_open=True, what="size (MB)")
_DIRECTIONS = {"to-ba": "device→BA", "from-ba": "BA→device", "data": "channel data"}
#: The time column, as the help and the closing lines say it.
TIME_BASE = "Times are seconds since the first frame"
#: Timestamps above this are seconds since 1970 (a live bus, most capture formats); below,
#: a capture's own clock (an ASC file's seconds since its start).
EPOCH_AFTER = 1e8


def time_base_line(t0: float | None) -> str | None:
    """The closing line that says what the time column counts from (None: no frame)."""
    if t0 is None:
        return None
    if t0 >= EPOCH_AFTER:
        import datetime as dt

        when = dt.datetime.fromtimestamp(t0, dt.UTC).strftime("%Y-%m-%d %H:%M:%S.%f UTC")
    else:
        when = f"{t0:.6f} s on the capture's clock"
    return f"{TIME_BASE} (the first at {when})"


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser(
        "monitor", help="decoded frames, live from a bus or from a capture",
        description="Decoded frames, live from a bus or from a capture. " + TIME_BASE + ".")
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--bus", metavar="URL", help="sim:NAME, can:INTERFACE:CHANNEL[@BITRATE] …")
    source.add_argument("--replay", metavar="FILE",
                        help="a capture (ASC, BLF, TRC, CSV, candump log, SQLite, gzipped "
                             "or not; MF4 with python-can's mf4 extra), read by its content")
    p.add_argument("--log", metavar="FILE", type=options.file_name,
                   help="also write every frame to this capture (replaced only once complete; "
                        "its node map is saved beside it)")
    p.add_argument("--rotate-mb", type=ROTATE_MB, metavar="N",
                   help="with --log: start a new file every N MB (python-can's rotation)")
    p.add_argument("--system", metavar="FILE",
                   help="a system file with node IDs: names the links of channel data")
    p.add_argument("--seconds", type=options.SECONDS, metavar="N",
                   help="stop after N seconds (live)")
    p.add_argument("--filter", action="append", default=[], metavar="KEY=VALUE",
                   help=FILTER_HELP)
    p.add_argument("--json", action="store_true", help="one JSON list of decoded frames")
    p.set_defaults(func=run)


def _node_in(nodes: set[int]) -> Callable[[Any], bool]:
    return lambda f: f.node_id in nodes


def _code_is(code: int) -> Callable[[Any], bool]:
    return lambda f: getattr(f.message, "CODE", None) == code


def _function_has(text: str) -> Callable[[Any], bool]:
    return lambda f: text in f.function.lower()


def _direction_is(direction: str) -> Callable[[Any], bool]:
    return lambda f: f.direction == direction


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
            tests.append(_node_in(nodes))
        elif key == "function" and value:
            if value.lower().startswith("0x"):
                try:
                    code = int(value, 16)
                except ValueError:
                    raise BadInput(f"--filter {spec}: not a function code") from None
                tests.append(_code_is(code))
            else:
                tests.append(_function_has(value.lower()))
        elif key == "direction" and value in _DIRECTIONS:
            tests.append(_direction_is(_DIRECTIONS[value]))
        else:
            raise BadInput(f"--filter {spec!r}: expected {FILTER_HELP.split(': ', 1)[1]}")
    if len(tests) == 1:
        return tests[0]

    def every(frame: Any) -> bool:
        for test in tests:
            if not test(frame):
                return False
        return True

    return every


class _ListenOnly:
    """A python-can bus the monitor can only read: sending raises (it never transmits)."""

    def __init__(self, bus: Any) -> None:
        self._bus = bus

    def recv(self, timeout: float) -> Any:
        return self._bus.recv(timeout=timeout)

    def send(self, *_args: Any, **_kw: Any) -> None:
        raise RuntimeError("the monitor never transmits")

    def shutdown(self) -> None:
        self._bus.shutdown()


#: Kernel receive buffer asked for a socket-based bus: a saturated bus (8,000 frames/s, a
#: kernel buffer entry of about 1 KB each) must not lose frames while the monitor waits for
#: a core on a busy machine — 16 MB hold about two seconds.
RECEIVE_BUFFER = 16 << 20
#: Linux's socket option (asm-generic/socket.h) that Python's socket module does not name.
SO_RCVBUFFORCE = 33


def _enlarge_receive_buffer(bus: Any) -> int:
    """Best effort for python-can's udp_multicast bus (a datagram socket): the default
    ~200 KB holds only a few dozen milliseconds of a saturated bus, and a datagram that does
    not fit is dropped by the kernel. Asks beyond the system's maximum where allowed
    (``SO_RCVBUFFORCE``, Linux, privileged), else up to it. Returns the size granted (0:
    not a socket bus)."""
    import socket

    sock = getattr(getattr(bus, "_multicast", None), "_socket", None)
    if sock is None:
        return 0
    force = getattr(socket, "SO_RCVBUFFORCE", SO_RCVBUFFORCE if sys.platform == "linux" else None)
    for option in (force, socket.SO_RCVBUF):
        if option is not None:
            with contextlib.suppress(OSError):
                sock.setsockopt(socket.SOL_SOCKET, option, RECEIVE_BUFFER)
                break
    return int(sock.getsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF))


def _can_frames(spec: Any, stop: Callable[[], bool]) -> Iterator[Any]:
    """Frames of a python-can bus, opened only to listen (listen-only where the interface
    has it; the monitor never sends)."""
    from pdcp_studio.bus.session.urls import listen_only_options, open_spec

    raw = open_spec(spec, **listen_only_options(spec))  # TransportError names the URL
    _enlarge_receive_buffer(raw)
    bus = _ListenOnly(raw)
    recv = raw.recv  # read directly: the wrapper only guards sending
    yield None  # open: the listening time starts now
    try:
        tick = time.monotonic() + POLL_S
        while True:
            msg = recv(POLL_S)
            if msg is not None:
                yield msg
                if time.monotonic() < tick:
                    continue  # a busy bus: a quiet moment is told at most every POLL_S
            # A quiet poll, or POLL_S of a busy bus: the caller flushes; the deadline.
            tick = time.monotonic() + POLL_S
            yield None
            if stop():
                break
    finally:
        bus.shutdown()


def learn_links(links: dict[int, Any], system: Any) -> None:
    """Fill a FrameDecoder's link map from a system with node IDs: frames from an output's
    node ID are channel data on its links, not function codes."""
    links.clear()
    for ref, ch in system.channels():
        if ch.is_output and ch.node_id:
            links[ch.node_id] = (ref, tuple(system.inputs_fed_by(ref)))


def _session_frames(url: str, stop: Callable[[], bool],
                    decoder: Any = None) -> Iterator[Any]:
    """Frames a bus session reports (sim:, serial:): its FrameSeen events.

    The ``decoder``'s link map is kept current from the session's system, re-read whenever
    a device or link comes or goes (then a ``None`` tells the consumer to look again).
    """
    import can

    from pdcp_studio.bus.events import DeviceJoined, DeviceLeft, FrameSeen, LinkMade, LinkRemoved

    try:
        from pdcp_studio.bus.session.opening import open_session
    except ImportError as err:
        from pdcp_studio.errors import TransportError

        raise TransportError(f"--bus {url}: the bus session is not available ({err})") from err
    from pdcp_studio.bus.hostlink.client import ChannelCounts

    seen: queue.Queue[Any] = queue.Queue()
    session = open_session(url)
    try:
        # The session's callback only enqueues; decoding happens on this thread. Over the
        # host link channel data arrives as counts per output (ChannelCounts), not frames.
        wanted = (FrameSeen, DeviceJoined, DeviceLeft, LinkMade, LinkRemoved, ChannelCounts)
        session.subscribe(
            lambda ev: seen.put(ev) if isinstance(ev, wanted) else None)
        if decoder is not None:
            learn_links(decoder.links, session.system())
            decoder.relearn()
        yield None  # open: the listening time starts now
        while not stop():
            try:
                ev = seen.get(timeout=POLL_S)
            except queue.Empty:
                yield None
                continue
            if isinstance(ev, ChannelCounts):
                yield ev
                continue
            if not isinstance(ev, FrameSeen):
                if decoder is not None:
                    learn_links(decoder.links, session.system())
                    decoder.relearn()
                    yield None
                continue
            yield can.Message(timestamp=ev.timestamp, arbitration_id=ev.arbitration_id,
                              data=bytes(ev.data), is_extended_id=False)
    finally:
        session.close()


def _replay_frames(path: str, decoder: Any) -> Any:
    """A capture opened for decoding (``CaptureReplay``: its frames, its reader, where its
    node map came from); CaptureError if it is unreadable."""
    from pdcp_studio.bus.trace.files.replay import CaptureReplay

    return CaptureReplay(path, decoder)


def _load_system_links(links: dict[int, Any], path: str) -> None:
    from pdcp_studio.storage.system_file import load_path

    learn_links(links, load_path(path))


def run(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.trace.decoder import FrameDecoder
    from pdcp_studio.bus.trace.files.capture import PARTIAL_SUFFIX, CaptureError, CaptureWriteError
    from pdcp_studio.bus.trace.files.recorder import Recorder
    from pdcp_studio.bus.trace.pump import TracePump

    show = make_filter(args.filter) if args.filter else None
    if args.seconds is not None and args.seconds <= 0:
        raise BadInput(f"--seconds {args.seconds}: must be positive")
    if args.rotate_mb is not None and not args.log:
        raise BadInput("--rotate-mb: only with --log FILE")
    links: dict[int, Any] = {}
    live = not args.replay
    decoder = FrameDecoder(links)
    # A capture or a shared CAN bus may carry another bus's frames: none is shown as a PDCP
    # message unless it fits one in context (a session's bus carries only PDCP's).
    decoder.context_checked = bool(args.replay) or args.bus.startswith("can:")
    if args.system:
        _load_system_links(links, args.system)
    clock = {"started": time.monotonic(), "open": False}

    def stop() -> bool:
        elapsed = time.monotonic() - clock["started"]
        return args.seconds is not None and elapsed >= args.seconds

    frames: Iterator[Any] | None = None  # a replay is opened below, its errors handled there
    if not args.replay:
        from pdcp_studio.bus.session.urls import BusUrlError, parse_bus_url

        try:
            spec = parse_bus_url(args.bus)
        except BusUrlError as err:
            raise BadInput(str(err)) from err
        if spec.kind == "can":
            decoder.passive = True  # it joins a running bus and learns from what it hears
            if not args.system:  # and infers devices and channels it never saw set up
                decoder.learn_from_traffic()
            frames = _can_frames(spec, stop)
        else:
            frames = _session_frames(args.bus, stop, decoder)
    out = sys.stdout
    limiter = UndecodableFrames(sys.stderr) if live else None
    reports: Any = ()  # kinds of report a live session sends besides frames
    if live:
        from pdcp_studio.bus.hostlink.client import ChannelCounts

        reports = ChannelCounts

    counted = ChannelDataCounts()
    reader: Any = None
    # Where the node map comes from, when not from the capture itself: the system file
    # given, or a session's own system (sim:, serial:).
    map_source: str | None = args.system or (
        None if args.replay or args.bus.startswith("can:") else f"the session on {args.bus}")
    pump: TracePump | None = None
    cut_short = False  # Ctrl-C before --seconds had passed
    try:
        with ExitStack() as stack:
            if frames is None:
                opened = _replay_frames(args.replay, decoder)
                stack.callback(opened.close)
                frames, reader = opened.frames, opened.reader
                map_source = opened.node_map_source or map_source
            else:
                stack.enter_context(closing(frames))  # type: ignore[type-var]  # shuts a bus
            recorder = stack.enter_context(Recorder(
                args.log, rotate_bytes=int((args.rotate_mb or 0) * 1e6),
                node_map=decoder.node_map)) if args.log else None
            pump = TracePump(decoder, out, json=args.json, show=show, recorder=recorder,
                             on_error=None if limiter is None else limiter.note,
                             flush_each_chunk=live)

            def other(item: Any) -> None:
                """A quiet moment on a live bus (None; the first: the bus just opened), or
                channel data counted by the arbitrator."""
                if item is None:
                    if not clock["open"]:
                        clock.update(started=time.monotonic(), open=True)
                    out.flush()
                    if limiter is not None:
                        limiter.tick()
                elif isinstance(item, reports):
                    line = counted.add(item)
                    if line and not args.json and show is None:
                        out.write(line + "\n")

            try:
                pump.run(frames, other)
            except KeyboardInterrupt:
                # Ctrl-C is how a live monitor without --seconds ends: its capture is
                # complete. A replay before its end, or a live one before --seconds have
                # passed, is interrupted: FILE stays as it was (contracts §2) and the
                # frames so far stay in FILE.partial.
                cut_short = bool(args.replay) or (args.seconds is not None and not stop())
                if cut_short and recorder is not None:
                    recorder.abandon()
            pump.flush()
    except CaptureError as err:
        if pump is not None:
            pump.flush()  # the frames read before the fault
            if pump.json is not None and pump.json.count:
                pump.close(_summary_json(decoder, None, reader, map_source, None))
        if isinstance(err, CaptureWriteError):
            raise  # a failure (exit 1) naming the capture, not bad input
        raise BadInput(str(err)) from err
    elapsed = None if args.replay else time.monotonic() - clock["started"]
    if pump is not None:
        pump.close(_summary_json(decoder, elapsed, reader, map_source,
                                 recorder.not_written() if recorder is not None else None))
    out.flush()
    if limiter is not None:
        limiter.tick(final=True)
    print(decoder.stats.summary(elapsed), file=sys.stderr)
    for line in _closing_lines(decoder, reader, map_source):
        print(line, file=sys.stderr)
    base = None if args.json else time_base_line(decoder.t0)
    if base is not None:
        print(base, file=sys.stderr)
    if counted.total:
        print(counted.summary(), file=sys.stderr)
    if cut_short:
        when = ("before the end of the capture" if args.replay else
                f"after {time.monotonic() - clock['started']:.1f} of {args.seconds:g} seconds")
        kept = (f"; {args.log} is as it was, the frames so far are in "
                f"{args.log}{PARTIAL_SUFFIX}" if args.log else "")
        print(f"pdcp-studio: monitor interrupted {when}{kept}", file=sys.stderr)
        return 1
    lost = recorder.not_written() if recorder is not None else None
    if args.log:
        print(f"wrote {args.log}" + (f", but {lost}" if lost else ""), file=sys.stderr)
    if reader is not None and reader.truncated:
        print(f"pdcp-studio: {reader.damage} (read up to there: {reader.frames:,} frames)",
              file=sys.stderr)
        return 2
    return 1 if lost else 0


def _closing_lines(decoder: Any, reader: Any, map_source: str | None) -> list[str]:
    stats = decoder.stats
    verdict = stats.verdict_word()
    lines = [f"verdict: {verdict}"]
    from pdcp_studio.bus.trace.files.replay import node_map_words

    words = node_map_words(decoder, map_source)
    if words:
        lines.append(words)
    if reader is not None:
        lines.append(f"capture: {reader.name}, {reader.format_name}"
                     + (f", truncated: {reader.damage}" if reader.truncated else ""))
    return lines


def _summary_json(decoder: Any, elapsed: float | None, reader: Any, map_source: str | None,
                  not_written: str | None) -> dict[str, Any]:
    """The ``summary`` of ``--json`` (contracts §2)."""
    from pdcp_studio.bus.trace.files.replay import node_map_words

    summary: dict[str, Any] = decoder.stats.as_json(elapsed)
    summary["node_map"] = node_map_words(decoder, map_source)
    if reader is not None:
        summary.update(format=reader.format, truncated=reader.truncated, damage=reader.damage)
    else:
        summary.update(truncated=False, damage=None)
    if not_written:
        summary["not_written"] = not_written
    return summary


class ChannelDataCounts:
    """Channel data the arbitrator counted for us (the host link carries counts, not the
    frames: a busy CAN bus does not fit a 128000-baud line). One line per report."""

    def __init__(self) -> None:
        self.total = 0
        self.by_output: dict[Any, int] = {}

    def add(self, report: Any) -> str:
        n = sum(report.counts.values()) or sum(report.by_node.values())
        self.total += n
        for ref, k in report.counts.items():
            self.by_output[ref] = self.by_output.get(ref, 0) + k
        if not n:
            return ""
        parts = [f"{ref} {k}" for ref, k in sorted(report.counts.items(), key=repr) if k]
        return (f"channel data counted by the arbitrator over {report.seconds:g} s: "
                f"{n} frame(s)" + (f" ({', '.join(parts)})" if parts else ""))

    def summary(self) -> str:
        return (f"{self.total} channel data frame(s) counted by the arbitrator on "
                f"{len(self.by_output)} output(s) (the host link carries counts, not frames)")


#: Kinds of undecodable frames told apart on stderr (a hostile bus could bring many more).
MAX_UNDECODABLE_KINDS = 64


class UndecodableFrames:
    """Undecodable frames on stderr, through the one repeat limiter (``bus/log_limit.py``):
    the first of each reason in full, then at most one a second with a count of the rest (a
    hostile bus at 4 kHz writes a line a second, not 4,000). The trace and the statistics
    still show and count every frame."""

    def __init__(self, stream: Any) -> None:
        import logging

        from pdcp_studio.bus.log_limit import LimitedLog

        logger = logging.Logger("pdcp_studio.monitor")  # private: not the global tree
        handler = logging.StreamHandler(stream)
        handler.setFormatter(logging.Formatter("%(message)s"))
        logger.addHandler(handler)
        self.log = LimitedLog(logger)
        self._kinds: set[str] = set()

    def note(self, frame: Any) -> None:
        reason = frame.error.split(":")[0]
        if reason not in self._kinds:
            if len(self._kinds) >= MAX_UNDECODABLE_KINDS:
                reason = "other reasons"
            self._kinds.add(reason)
        self.log.warning(f"undecodable frames ({reason})", "undecodable frame %s: %s",
                         frame.fields, frame.error)

    def tick(self, final: bool = False) -> None:
        self.log.flush(final)
