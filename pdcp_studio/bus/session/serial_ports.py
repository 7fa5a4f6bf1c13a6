"""Why a serial port did not open, in one line with the fix (contracts §2).

A known interface whose device is missing is exit 1 "with the fix in one line", as the ``can:``
adapters give (``bus/session/can_interfaces.py``). For the host link's serial port the fix
depends on why pyserial refused: a port that is not there (name the ports pyserial's
``list_ports`` sees, or say none is plugged in), one the user may not open, one another program
holds, a network port nobody serves, a file that is not a serial port. :func:`open_failure` is
pure (the ports are given) so each case is tested without hardware; :func:`seen_ports` asks
pyserial.
"""

from __future__ import annotations

import errno
import importlib.util
import os
import re
import sys
from collections.abc import Sequence

#: How many of the computer's ports a message names (a few; the Connect dialog lists all).
PORTS_SHOWN = 4


def seen_ports() -> list[str]:
    """The serial ports pyserial sees on this computer, sorted (empty when it cannot tell)."""
    try:
        from serial.tools import list_ports

        return sorted(p.device for p in list_ports.comports())
    except Exception:  # a platform pyserial cannot enumerate: say none rather than fail
        return []


def example_port(platform: str = sys.platform) -> str:
    """A port name as this kind of computer spells it."""
    if platform.startswith("win"):
        return "COM3"
    if platform == "darwin":
        return "/dev/cu.usbserial-1410"
    return "/dev/ttyUSB0"


def _which_port(ports: Sequence[str], platform: str, form: str) -> str:
    """The fix's ending: the ports this computer has, or that none is plugged in, written as
    the user names a port there (``form``: ``serial:`` in a bus URL, nothing after
    ``--host-serial``)."""
    if not ports:
        return ("no serial port is plugged in: plug the serial cable in, then name its port "
                f"(e.g. {form}{example_port(platform)})")
    shown = ", ".join(f"{form}{p}" for p in ports[:PORTS_SHOWN])
    more = f" and {len(ports) - PORTS_SHOWN} more" if len(ports) > PORTS_SHOWN else ""
    return f"plug the serial cable in and name one of this computer's ports: {shown}{more}"


def url_protocols() -> list[str]:
    """The URL protocols pyserial has (``socket``, ``rfc2217``, ``loop`` …), sorted."""
    import pkgutil

    import serial

    names: set[str] = set()
    for package in serial.protocol_handler_packages:
        try:
            found = importlib.util.find_spec(package)
        except (ImportError, ValueError):
            continue
        for module in pkgutil.iter_modules(found.submodule_search_locations or []
                                           if found else []):
            if module.name.startswith("protocol_"):
                names.add(module.name.removeprefix("protocol_"))
    return sorted(names)


def unknown_protocol(port: str) -> str | None:
    """Why ``port`` is a URL pyserial cannot open (a protocol it does not have), or None;
    checked before opening, so the CLI calls it bad input."""
    if "://" not in port:
        return None
    protocol = port.split("://", 1)[0].lower()
    known = url_protocols()
    if protocol in known:
        return None
    return (f"pyserial has no {protocol!r} URL; a port is a device (/dev/ttyUSB0, COM3) or "
            f"one of {', '.join(p + '://' for p in known)}")


def _errno(err: BaseException) -> int | None:
    """The operating system's reason, from pyserial's exception or the one it wraps."""
    for candidate in (err, err.__cause__, err.__context__):
        code = getattr(candidate, "errno", None)
        if isinstance(code, int):
            return code
    match = re.search(r"\[Errno (\d+)\]|\((\d+), '", str(err))
    if match:
        return int(match.group(1) or match.group(2))
    return None


def _reason(err: BaseException) -> str:
    """pyserial's words without the repeats ("could not open port X: [Errno 2] …: 'X'")."""
    code = _errno(err)
    if code is not None and code in errno.errorcode:
        return os.strerror(code)
    text = " ".join(str(err).split()) or type(err).__name__
    return text if len(text) <= 160 else text[:157] + "…"


def open_failure(where: str, name: str, err: BaseException, ports: Sequence[str],
                 platform: str = sys.platform) -> str:
    """One line: ``where`` (the bus URL, or what the port is for), the port, why it did not
    open and the fix."""
    code = _errno(err)
    why = _reason(err)
    form = "serial:" if where.startswith("serial:") else ""
    network = "://" in name and not name.startswith(("loop://", "spy://"))
    if isinstance(err, ValueError) and "://" in name:
        fix = ("name a serial port or a pyserial URL such as socket://HOST:PORT or "
               "rfc2217://HOST:PORT")
        return f"{where}: cannot open serial port {name!r} ({why}); fix: {fix}"
    if network:
        fix = (f"check that the arbitrator serves its host link at {name.split('://', 1)[1]} "
               "and that this computer can reach it")
    elif code in (errno.EACCES, errno.EPERM):
        fix = ("add your user to the group that owns the port (dialout on most Linux "
               "systems), then log in again")
    elif code == errno.EBUSY:
        fix = "close the other program that has the port open"
    elif code == errno.ENOTTY:
        fix = f"{name} is not a serial port; " + _which_port(ports, platform, form)
    elif code in (errno.ENOENT, errno.ENODEV, errno.ENXIO) or "not found" in why.lower() \
            or "cannot find" in why.lower():
        return f"{where}: serial port {name!r} not found; fix: {_which_port(ports, platform, form)}"
    else:
        fix = _which_port(ports, platform, form)
    return f"{where}: cannot open serial port {name!r} ({why}); fix: {fix}"
