"""What python-can's failures to open a bus mean, and what fixes each: one line, never a traceback.

python-can raises many kinds of exception when ``can.Bus(...)`` cannot open: its own
``CanInterfaceNotImplementedError`` (an unknown interface, a driver module that does not
import), ``CanInitializationError`` (the adapter is not there), and, straight from the drivers,
``ImportError``, ``NameError`` (kvaser without CANlib), ``OSError`` (pcan without PCAN-Basic,
socketcan without the kernel module, a serial port that does not exist), ``TypeError`` and
``ValueError`` (a channel or option the interface does not accept). :func:`explain_open_error`
sorts them into the two answers the command line gives (contracts §2):

- :class:`~pdcp_studio.bus.session.urls.BusUrlError` — bad input, exit 2: the interface
  python-can does not have, a channel or option it refuses; the message says what was expected;
- :class:`DriverMissingError` / :class:`AdapterMissingError` — exit 1: a known interface whose
  driver package or adapter is missing; the message carries the fix.

Pure: it looks at the exception and the URL's parts, never at the bus.
"""

from __future__ import annotations

import errno
import socket
from typing import Any

from pdcp_studio.errors import TransportError

#: What installs each python-can interface's driver (python-can's interface pages).
DRIVER_FIX: dict[str, str] = {
    "canalystii": "install the canalystii package (pip install canalystii)",
    "cantact": "install the cantact package (pip install cantact)",
    "etas": "install ETAS BOA (the ECI/BOA driver; Windows)",
    "gs_usb": "install the gs_usb package and libusb (pip install gs_usb)",
    "iscan": "install the IS-CAN driver (iscandrv) from Ingenieurbüro Schneider",
    "ixxat": "install the IXXAT VCI 4 driver (Windows) or ECI driver (Linux)",
    "kvaser": "install Kvaser CANlib (Kvaser Drivers for Windows, or linuxcan on Linux)",
    "neousys": "install the Neousys WDT_DIO driver",
    "neovi": "install the python-ics package and Intrepid's drivers (pip install python-ics)",
    "nican": "install NI-CAN (Windows, 32-bit Python)",
    "nixnet": "install NI-XNET and the nixnet package (Windows; pip install nixnet)",
    "pcan": "install PEAK's PCAN-Basic (libpcanbasic on Linux, PCANBasic.dll on Windows)",
    "robotell": "install pyserial (pip install pyserial)",
    "seeedstudio": "install pyserial (pip install pyserial)",
    "serial": "install pyserial (pip install pyserial)",
    "slcan": "install pyserial (pip install pyserial)",
    "socketcan": "load SocketCAN in the kernel (sudo modprobe can can_raw; Linux only)",
    "socketcand": "start socketcand on the host and give ?host=…&port=…",
    "systec": "install SYSTEC's USB-CANmodul driver (Windows)",
    "udp_multicast": "install msgpack (pip install msgpack)",
    "usb2can": "install 8devices' usb2can driver and pywin32 (Windows)",
    "vector": "install Vector's XL Driver Library (vxlapi; Windows)",
    "virtual": "reinstall python-can",
}

#: What a channel of each interface looks like (said when the interface refuses one).
CHANNEL_FORM: dict[str, str] = {
    "socketcan": "a SocketCAN network interface, e.g. can:socketcan:can0",
    "pcan": "a PCAN channel, e.g. can:pcan:PCAN_USBBUS1",
    "kvaser": "a Kvaser channel number, e.g. can:kvaser:0",
    "vector": "a Vector channel number, e.g. can:vector:0?app_name=CANalyzer",
    "ixxat": "an IXXAT channel number, e.g. can:ixxat:0",
    "gs_usb": "a gs_usb channel, e.g. can:gs_usb:0?index=0",
    "slcan": "a serial port, e.g. can:slcan:/dev/ttyACM0?tty_baudrate=115200",
    "serial": "a serial port, e.g. can:serial:/dev/ttyUSB0",
    "robotell": "a serial port, e.g. can:robotell:/dev/ttyUSB0",
    "seeedstudio": "a serial port, e.g. can:seeedstudio:/dev/ttyUSB0",
    "udp_multicast": "a multicast group, e.g. can:udp_multicast:239.74.163.2?port=43200",
    "socketcand": "a socketcand bus, e.g. can:socketcand:can0?host=10.0.0.2&port=29536",
    "virtual": "any name, e.g. can:virtual:bus0",
}

#: OSError numbers that mean "this kind of bus does not exist on this computer".
_NO_SUPPORT = {errno.EAFNOSUPPORT, errno.EPROTONOSUPPORT, errno.ENOPROTOOPT}


class DriverMissingError(TransportError):
    """A known python-can interface whose driver or package is not installed (exit 1)."""


class AdapterMissingError(TransportError):
    """The interface works but its adapter, port or network is not there (exit 1)."""


def driver_fix(interface: str) -> str:
    """The one-line fix for a missing driver of ``interface``."""
    return DRIVER_FIX.get(interface, f"install the driver python-can's {interface!r} "
                                     "interface needs")


def channel_form(interface: str) -> str:
    return CHANNEL_FORM.get(interface, f"a channel python-can's {interface!r} interface takes")


def unknown_interface(url: str, interface: str) -> Exception:
    """BusUrlError: python-can has no such interface (the names it has are listed)."""
    from pdcp_studio.bus.session.urls import BusUrlError, known_interfaces

    return BusUrlError(f"bus URL {url!r}: python-can has no interface {interface!r} "
                       f"(one of {', '.join(known_interfaces())})")


def refused(url: str, interface: str, why: str) -> Exception:
    """BusUrlError: the interface refuses the URL's channel or an option."""
    from pdcp_studio.bus.session.urls import BusUrlError

    return BusUrlError(f"bus URL {url!r}: {interface} refuses the channel or an option "
                       f"({why}); expected {channel_form(interface)}")


def check_channel(url: str, interface: str, channel: str, options: dict[str, Any]) -> None:
    """Raise BusUrlError for what python-can would refuse when opening, checked without
    opening: an option the interface does not know or a value its parameter does not take
    (``bus/session/can_options.py``; python-can would drop the one silently and fail deep in the
    driver on the other), its own option checks (``can.util.load_config``: port range, state,
    fd, bit timing) and a ``udp_multicast`` group that is not a multicast address."""
    import ipaddress

    import can.util

    from pdcp_studio.bus.session.can_options import refused_option

    why = refused_option(interface, {k: v for k, v in options.items() if k != "bitrate"})
    if why:
        from pdcp_studio.bus.session.urls import BusUrlError

        raise BusUrlError(f"bus URL {url!r}: {why}")
    try:
        can.util.load_config(config={"interface": interface, "channel": channel, **options})
    except (ValueError, TypeError, KeyError) as err:
        raise refused(url, interface, _first_line(err)) from None
    except NotImplementedError:
        raise unknown_interface(url, interface) from None
    if interface == "udp_multicast":
        try:
            multicast = ipaddress.ip_address(channel).is_multicast
        except ValueError:
            multicast = False
        if not multicast:
            raise refused(url, interface, f"{channel!r} is not a multicast address")


def _plug_in(interface: str) -> str:
    return f"plug the adapter in and check the channel ({channel_form(interface)})"


def _first_line(err: BaseException) -> str:
    text = " ".join(str(err).split()) or type(err).__name__
    return text if len(text) <= 200 else text[:197] + "…"


def explain_open_error(url: str, interface: str, channel: str,
                       err: BaseException) -> Exception:
    """The exception to raise instead of ``err`` from ``can.Bus(interface, channel, …)``.

    BusUrlError (bad input) or a TransportError subclass (exit 1) whose message is one line
    that names the URL and says what was expected or what fixes it.
    """
    why = _first_line(err)
    try:
        import can
    except ImportError:  # pragma: no cover - python-can is a dependency
        return DriverMissingError(f"{url}: python-can is not installed (pip install python-can)")
    if isinstance(err, can.CanInterfaceNotImplementedError | ImportError | NameError
                  | AttributeError):
        if isinstance(err, can.CanInterfaceNotImplementedError) and "Unknown interface" in why:
            return unknown_interface(url, interface)
        return DriverMissingError(f"{url}: the {interface} driver is not installed ({why}); "
                                  f"fix: {driver_fix(interface)}")
    if isinstance(err, NotImplementedError):
        return unknown_interface(url, interface)
    if isinstance(err, socket.gaierror | TypeError | ValueError | OverflowError | KeyError):
        return refused(url, interface, why)
    if isinstance(err, OSError) and not isinstance(err, can.CanError):
        if (err.errno is None and "not found" in why.lower()) or err.errno in _NO_SUPPORT:
            return DriverMissingError(f"{url}: the {interface} driver is not usable here "
                                      f"({why}); fix: {driver_fix(interface)}")
        if err.errno == errno.EACCES or err.errno == errno.EPERM:
            return AdapterMissingError(f"{url}: no permission to open {channel!r} ({why}); "
                                       "fix: add your user to the group that owns it "
                                       "(dialout on most Linux systems)")
        return AdapterMissingError(f"{url}: adapter {channel!r} not found ({why}); "
                                   f"fix: {_plug_in(interface)}")
    if isinstance(err, can.CanError):
        return AdapterMissingError(f"{url}: cannot open adapter {channel!r} ({why}); "
                                   f"fix: {_plug_in(interface)}")
    return TransportError(f"{url}: cannot open the bus ({type(err).__name__}: {why})")
