"""Bus URLs (contracts §3) and opening the python-can bus a URL names.

``sim:NAME`` · ``can:INTERFACE:CHANNEL[@BITRATE][?OPTION=VALUE&…]`` · ``serial:PORT[@BAUD]``.
The ``?…`` suffix (an extension of contracts §3) passes keyword options to the python-can
interface, e.g. ``can:udp_multicast:239.74.163.2?port=43200`` so that separate test runs on
one host do not hear each other; numbers become ints, ``true``/``false`` booleans. python-can is
imported only inside :func:`open_can_bus`, so parsing a URL (the CLI validating ``--bus``) stays
cheap, and a missing vendor driver fails with a TransportError naming the URL, not a traceback.
"""

from __future__ import annotations

import itertools
import os
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from pdcp_studio.errors import PdcpError, TransportError

if TYPE_CHECKING:
    import can

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
        value: Any = text
        if re.match(r"^-?\d+$", text):
            value = int(text)
        elif text.lower() in ("true", "false"):
            value = text.lower() == "true"
        out.append((key, value))
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
        return BusSpec(url, "can", interface=interface, channel=channel, bitrate=bitrate,
                       options=options)
    if scheme == "serial":
        port, baud = rest, DEFAULT_BAUD
        match = re.match(r"^(.*)@(\d+)$", rest)
        if match:
            port, baud = match.group(1), _rate(match.group(2), url, "baud rate")
        if not port:
            raise BusUrlError(f"bus URL {url!r}: serial needs a port (serial:/dev/ttyUSB0)")
        return BusSpec(url, "serial", port=port, baud=baud)
    raise BusUrlError(f"bus URL {url!r}: unknown scheme {scheme!r}; use {forms}")


def unique_virtual_channel(prefix: str = "pdcp-sim") -> str:
    """A virtual channel name no other session in this process uses (style: one per test)."""
    return f"{prefix}-{os.getpid()}-{next(_virtual_counter)}"


def open_can_bus(interface: str, channel: str, *, bitrate: int | None = None,
                 url: str = "", **options: Any) -> can.BusABC:
    """Open a python-can bus; TransportError naming the URL if the adapter or driver is missing."""
    import can

    shown = url or f"can:{interface}:{channel}"
    kwargs: dict[str, Any] = dict(options)
    if bitrate is not None and interface not in ("virtual", "udp_multicast"):
        kwargs["bitrate"] = bitrate
    try:
        return can.Bus(interface=interface, channel=channel, **kwargs)
    except NotImplementedError as err:
        raise TransportError(
            f"{shown}: python-can has no interface {interface!r} ({err})"
        ) from err
    except can.CanInterfaceNotImplementedError as err:
        raise TransportError(
            f"{shown}: the driver for {interface!r} is not installed or not usable: {err}"
        ) from err
    except (can.CanError, OSError, ValueError, ImportError) as err:
        raise TransportError(f"{shown}: cannot open the bus: {err}") from err


def open_spec(spec: BusSpec, **options: Any) -> can.BusABC:
    """Open the python-can bus of a ``can:`` spec."""
    if spec.kind != "can":
        raise TransportError(f"{spec.url}: not a can: bus")
    merged = {**dict(spec.options), **options}
    return open_can_bus(spec.interface, spec.channel, bitrate=spec.bitrate or DEFAULT_BITRATE,
                        url=spec.url, **merged)
