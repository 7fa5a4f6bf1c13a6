"""Bus URLs (contracts §3) and opening the python-can bus a URL names.

``sim:NAME`` · ``can:INTERFACE:CHANNEL[@BITRATE][?OPTION=VALUE&…]`` · ``serial:PORT[@BAUD]``.
The ``?…`` suffix (an extension of contracts §3) passes keyword options to the python-can
interface, e.g. ``can:udp_multicast:239.74.163.2?port=43200`` so that separate test runs on
one host do not hear each other; values are read as python-can reads its own configuration
(``can.util.cast_from_string``: ints, floats, ``true``/``false`` booleans). python-can is
imported only when a URL is checked or opened, so parsing one stays cheap; what python-can
raises when a bus does not open becomes one line with the fix (``bus/session/can_interfaces.py``).

slcan adapters: ``@BITRATE`` is the CAN bitrate (PDCP: 1000000); the serial line's speed is
python-can's ``tty_baudrate`` option, ``can:slcan:/dev/ttyACM0@1000000?tty_baudrate=115200``
(``docs/bus-urls.md``).
"""

from __future__ import annotations

import itertools
import logging
import os
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from pdcp_studio.errors import PdcpError, TransportError

if TYPE_CHECKING:
    import can

log = logging.getLogger(__name__)

#: PDCP runs at 1 Mbit/s (reference §1); the host link's default baud (contracts §3).
DEFAULT_BITRATE = 1_000_000
DEFAULT_BAUD = 128_000

_NAME = re.compile(r"^[A-Za-z0-9_.\-]+$")
_virtual_counter = itertools.count(1)


class BusUrlError(PdcpError):
    """A ``--bus`` URL does not parse (the CLI maps it to exit status 2)."""


@dataclass(frozen=True)
class BusSpec:
    """A parsed bus URL. ``kind`` is ``sim``, ``can`` or ``serial``."""

    url: str
    kind: Literal["sim", "can", "serial"]
    name: str = ""  # sim: the prosthesis name
    interface: str = ""  # can: the python-can interface
    channel: str = ""  # can: the channel
    bitrate: int | None = None  # can: only when given
    port: str = ""  # serial: the pyserial port or URL
    baud: int = DEFAULT_BAUD
    options: tuple[tuple[str, Any], ...] = ()  # can: interface keyword options from "?…"


def _rate(text: str, url: str, what: str) -> int:
    try:
        value = int(text, 10)
    except ValueError:
        raise BusUrlError(f"bus URL {url!r}: {what} {text!r} is not a number") from None
    if value <= 0:
        raise BusUrlError(f"bus URL {url!r}: {what} {value} must be positive")
    return value


def _options(query: str, url: str) -> tuple[tuple[str, Any], ...]:
    if not query:
        return ()
    out: list[tuple[str, Any]] = []
    for part in query.split("&"):
        key, sep, text = part.partition("=")
        if not sep or not re.match(r"^[A-Za-z_][A-Za-z0-9_]*$", key):
            raise BusUrlError(f"bus URL {url!r}: option {part!r} is not NAME=VALUE")
        from can.util import cast_from_string  # as python-can's own configuration reads them

        out.append((key, cast_from_string(text)))
    return tuple(out)


def parse_bus_url(url: str) -> BusSpec:
    """Parse a bus URL; BusUrlError says what is wrong and shows the accepted forms."""
    forms = "sim:NAME, can:INTERFACE:CHANNEL[@BITRATE] or serial:PORT[@BAUD]"
    if not isinstance(url, str) or ":" not in url:
        raise BusUrlError(f"bus URL {url!r} is not one of {forms}")
    scheme, rest = url.split(":", 1)
    if scheme == "sim":
        if not rest or not _NAME.match(rest):
            raise BusUrlError(f"bus URL {url!r}: sim needs a prosthesis name (sim:thesis-test1)")
        return BusSpec(url, "sim", name=rest)
    if scheme == "can":
        rest, _, query = rest.partition("?")
        options = _options(query, url)
        interface, sep, channel = rest.partition(":")
        if not sep or not interface or not channel:
            raise BusUrlError(f"bus URL {url!r}: expected can:INTERFACE:CHANNEL[@BITRATE]")
        bitrate = None
        if "@" in channel:
            channel, text = channel.rsplit("@", 1)
            bitrate = _rate(text, url, "bitrate")
        if not channel:
            raise BusUrlError(f"bus URL {url!r}: the channel is empty")
        for key, _value in options:
            if key in ("bitrate", "channel", "interface", "url"):  # set by the URL itself
                raise BusUrlError(f"bus URL {url!r}: option {key!r} is given by the URL "
                                  "itself (can:INTERFACE:CHANNEL[@BITRATE])")
        return BusSpec(url, "can", interface=interface, channel=channel, bitrate=bitrate,
                       options=options)
    if scheme == "serial":
        port, baud = rest, DEFAULT_BAUD
        head, at, tail = rest.rpartition("@")
        # ``@BAUD`` ends the URL; an ``@`` followed by ``/`` or ``:`` belongs to a pyserial URL.
        if at and not any(c in tail for c in "/:"):
            port, baud = head, _rate(tail, url, "baud rate")
        if not port:
            raise BusUrlError(f"bus URL {url!r}: serial needs a port (serial:/dev/ttyUSB0)")
        return BusSpec(url, "serial", port=port, baud=baud)
    raise BusUrlError(f"bus URL {url!r}: unknown scheme {scheme!r}; use {forms}")


def unique_virtual_channel(prefix: str = "pdcp-sim") -> str:
    """A virtual channel name no other session in this process uses (style: one per test)."""
    return f"{prefix}-{os.getpid()}-{next(_virtual_counter)}"


def known_interfaces() -> list[str]:
    """The interface names python-can has (its backends, plugins included), sorted."""
    from can.interfaces import VALID_INTERFACES

    return sorted(VALID_INTERFACES)


def check_bus_url(url: str) -> BusSpec:
    """Parse ``url`` and check what can be checked without opening it: a ``can:`` interface
    python-can has, a ``sim:`` prosthesis that exists. BusUrlError says what was expected.

    Every command that takes ``--bus`` calls this (through ``open_session`` or directly), so a
    bad URL gives the same one line, exit 2, everywhere.
    """
    spec = parse_bus_url(url)
    if spec.kind == "can":
        from pdcp_studio.bus.session.can_interfaces import check_channel, unknown_interface

        if spec.interface not in known_interfaces():
            raise unknown_interface(url, spec.interface)
        options = dict(spec.options)
        if spec.bitrate is not None and spec.interface not in _NO_BITRATE:
            options["bitrate"] = spec.bitrate
        check_channel(url, spec.interface, spec.channel, options)
    if spec.kind == "serial":
        from pdcp_studio.bus.session.serial_ports import unknown_protocol

        if why := unknown_protocol(spec.port):
            raise BusUrlError(f"bus URL {url!r}: {why}")
    if spec.kind == "sim":
        from pdcp_studio.bus.sim.rigs import UnknownProsthesisError, resolve_prosthesis

        try:
            resolve_prosthesis(spec.name)
        except UnknownProsthesisError as err:
            raise BusUrlError(f"bus URL {url!r}: {err}") from None
    return spec


def bitrate_warning(spec: BusSpec) -> str:
    """A sentence when a ``can:`` URL asks for a bitrate other than PDCP's ('' if not)."""
    if spec.kind != "can" or spec.bitrate is None or spec.bitrate == DEFAULT_BITRATE:
        return ""
    if spec.interface in _NO_BITRATE:
        return ""
    return (f"{spec.url}: bitrate {spec.bitrate} bit/s is not PDCP's {DEFAULT_BITRATE} bit/s "
            "(reference §1); PDCP devices will not be heard")


#: python-can options that make an interface listen only (it never acknowledges nor sends).
LISTEN_ONLY: dict[str, dict[str, Any]] = {
    "slcan": {"listen_only": True},
    "vector": {"listen_only": True},
    "kvaser": {"driver_mode": False},  # canlib's DRIVER_MODE_SILENT
}


def listen_only_options(spec: BusSpec) -> dict[str, Any]:
    """The options that open ``spec``'s interface listen-only, where python-can has them
    (a passive monitor must not even acknowledge frames)."""
    if spec.interface == "pcan":
        import can

        return {"state": can.BusState.PASSIVE}
    return dict(LISTEN_ONLY.get(spec.interface, {}))


#: Interfaces without a CAN bitrate of their own (simulated buses).
_NO_BITRATE = ("virtual", "udp_multicast")


class _Collect(logging.Handler):
    """Keeps python-can's log records while a bus opens (its drivers log what they miss,
    which the one-line error already says)."""

    def __init__(self) -> None:
        super().__init__()
        self.records: list[logging.LogRecord] = []
        self._logger = logging.getLogger("can")
        self._propagate = True

    def emit(self, record: logging.LogRecord) -> None:
        self.records.append(record)

    def __enter__(self) -> _Collect:
        self._propagate = self._logger.propagate
        self._logger.addHandler(self)
        self._logger.propagate = False
        return self

    def __exit__(self, *exc: object) -> None:
        self._logger.removeHandler(self)
        self._logger.propagate = self._propagate


def open_can_bus(interface: str, channel: str, *, bitrate: int | None = None,
                 url: str = "", **options: Any) -> can.BusABC:
    """Open a python-can bus. What python-can raises becomes one line naming the URL
    (``bus/session/can_interfaces.py``): BusUrlError for an interface, channel or option python-can
    does not have or refuses; DriverMissingError or AdapterMissingError (TransportError) with
    the fix when the driver or the adapter is missing."""
    from pdcp_studio.bus.session.can_interfaces import explain_open_error

    shown = url or f"can:{interface}:{channel}"
    kwargs: dict[str, Any] = dict(options)
    if bitrate is not None and interface not in _NO_BITRATE:
        kwargs["bitrate"] = bitrate
    with _Collect() as said:
        try:
            import can

            return can.Bus(interface=interface, channel=channel, **kwargs)
        except Exception as err:
            error = explain_open_error(shown, interface, channel, err)
            log.debug("%s: python-can raised", shown, exc_info=True)
            # Drop the traceback now: it holds the half-built bus, whose destructor would
            # otherwise complain on stderr later, outside this collector.
            err.__traceback__ = None
            del err
        finally:
            for record in said.records:  # kept for a debug log, not shown to the user
                log.debug("python-can: %s", record.getMessage())
    raise error


def open_spec(spec: BusSpec, **options: Any) -> can.BusABC:
    """Open the python-can bus of a ``can:`` spec (a warning when its bitrate is not PDCP's)."""
    if spec.kind != "can":
        raise TransportError(f"{spec.url}: not a can: bus")
    check_bus_url(spec.url)  # what python-can would refuse: the same line as every command
    warning = bitrate_warning(spec)
    if warning:
        log.warning("%s", warning)
    merged = {**dict(spec.options), **options}
    return open_can_bus(spec.interface, spec.channel, bitrate=spec.bitrate or DEFAULT_BITRATE,
                        url=spec.url, **merged)
