"""``open_session(url)``: any bus URL (contracts §3) opened through one table of schemes.

- ``sim:NAME`` — a built-in prosthesis on an in-process virtual bus (bus/session/sim.py);
- ``can:INTERFACE:CHANNEL[@BITRATE]`` — PDCP Studio as the arbitrator of a python-can bus
  (bus/session/in_process.py);
- ``serial:PORT[@BAUD]`` — an arbitrator elsewhere, over its host link
  (bus/hostlink/client.py).

As python-can loads an interface's driver, a scheme's opener is imported only when a URL of
that scheme is opened, so a build without one (the host-link client) fails with one line,
and only for that scheme.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

from pdcp_studio.bus.session.base import BusSession
from pdcp_studio.bus.session.urls import BusSpec, BusUrlError, check_bus_url
from pdcp_studio.errors import TransportError

#: Bus URL scheme → (module, opener, what it is in words). An opener takes the parsed
#: ``BusSpec`` and the caller's options and returns an open session.
OPENERS: dict[str, tuple[str, str, str]] = {
    "sim": ("pdcp_studio.bus.session.sim", "open_sim_url", "the simulator"),
    "can": ("pdcp_studio.bus.session.in_process", "open_can_session", "the python-can arbitrator"),
    "serial": ("pdcp_studio.bus.hostlink.client", "open_hostlink_session",
               "the host-link client"),
}

__all__ = ["OPENERS", "BusUrlError", "open_session"]


def _opener(spec: BusSpec) -> Callable[..., BusSession]:
    module_name, name, what = OPENERS[spec.kind]
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError as err:
        missing = err.name or ""
        if not missing or not (module_name == missing or module_name.startswith(missing + ".")):
            raise  # the transport is there, something it imports is not: not this case
        raise TransportError(f"{spec.url}: {what} is not available in this build, so "
                             f"{spec.kind}: buses cannot be opened") from err
    opener: Callable[..., BusSession] = getattr(module, name)
    return opener


def open_session(url: str, **options: Any) -> BusSession:
    """Open a bus URL (``sim:``, ``can:``, ``serial:``) as a session; see the module doc.

    BusUrlError for a URL that does not parse, names an interface python-can does not have
    or a ``sim:`` prosthesis that does not exist, or carries options the interface refuses;
    TransportError when the bus cannot be opened (a missing driver or adapter: the fix).
    """
    spec = check_bus_url(url)
    return _opener(spec)(spec, **options)
