"""``pdcp-studio doctor [--json]``: what this installation has — what a clinic sends to support.

Versions; whether every module of PDCP Studio imports; each python-can interface and
whether its driver or package is here (and the fix when not); serial ports; the capture
formats python-can reads and writes; the resources folder; the fitting-history archive;
the display. It opens no bus and changes nothing. Exit 0 when every module imports and the
resources are there, else 1 (the report says what is wrong).
"""

from __future__ import annotations

import argparse
import ctypes.util
import importlib
import importlib.util
import json
import logging
import os
import pkgutil
import platform
import socket
import sys
from collections.abc import Callable
from importlib import metadata
from typing import Any

#: Packages whose versions the report gives (distribution names).
VERSIONED = ("pdcp-studio", "PySide6-Essentials", "PySide6", "shiboken6", "python-can",
             "pyserial", "networkx", "platformdirs", "msgpack", "psycopg")


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser(
        "doctor", help="what this installation has (for support)",
        description="Versions, modules, CAN interfaces and their drivers, serial ports, "
                    "capture formats, resources, fitting history and display.")
    p.add_argument("--json", action="store_true", help="print one JSON document")
    from pdcp_studio.cli.live.change_road import add_archive_argument

    add_archive_argument(p)
    p.set_defaults(func=run)


# -- the checks (each returns plain data) ------------------------------------------------

def versions() -> dict[str, str | None]:
    out: dict[str, str | None] = {"python": platform.python_version()}
    for name in VERSIONED:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = None
    try:
        from pdcp_studio.app.dialogs.help_viewer import qt_versions
    except ImportError:  # Qt's own libraries missing: the display check says which
        out["qt"] = None
    else:
        out.update(qt_versions())
    import can

    out["python-can"] = can.__version__
    from pdcp_studio import __version__

    out["pdcp-studio"] = __version__
    return out


def module_names() -> list[str]:
    """Every module of PDCP Studio (``__main__`` aside: importing it runs the CLI)."""
    import pdcp_studio

    names = ["pdcp_studio"]
    for info in pkgutil.walk_packages(pdcp_studio.__path__, "pdcp_studio."):
        if not info.name.endswith(".__main__"):
            names.append(info.name)
    return sorted(names)


def modules() -> tuple[dict[str, bool], dict[str, str]]:
    """Whether each module imports, and why not for those that do not."""
    ok: dict[str, bool] = {}
    why: dict[str, str] = {}
    for name in module_names():
        try:
            importlib.import_module(name)
        except Exception as err:  # any failure to import is what the report is for
            ok[name] = False
            why[name] = f"{type(err).__name__}: {err}"
        else:
            ok[name] = True
    return ok, why


def _module_flag(module: str, attr: str) -> Callable[[], str | None]:
    """A probe: the python-can module's ``attr`` is None when its library did not load."""
    def probe() -> str | None:
        mod = importlib.import_module(module)
        return None if getattr(mod, attr, None) is not None else "its library did not load"
    return probe


def _library(*names: str) -> Callable[[], str | None]:
    def probe() -> str | None:
        if any(ctypes.util.find_library(n) for n in names):
            return None
        return f"library {' / '.join(names)} not found"
    return probe


def _packages(*names: str) -> Callable[[], str | None]:
    def probe() -> str | None:
        lacking = [n for n in names if importlib.util.find_spec(n) is None]
        return f"Python package {', '.join(lacking)} not installed" if lacking else None
    return probe


#: Interfaces whose drivers python-can can use on Windows only.
WINDOWS_ONLY = frozenset({"etas", "ixxat", "nican", "systec", "usb2can", "vector"})


def _socketcan() -> str | None:
    if not sys.platform.startswith("linux") or not hasattr(socket, "AF_CAN"):
        return "SocketCAN exists on Linux only"
    try:
        socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW).close()
    except OSError as err:
        return f"the kernel refuses CAN sockets ({err.strerror or err})"
    return None


def _kvaser() -> str | None:
    mod = importlib.import_module("can.interfaces.kvaser.canlib")
    return None if getattr(mod, "__canlib", None) is not None else "Kvaser CANlib not found"


#: How to tell, without opening a bus, whether an interface's driver is here.
PROBES: dict[str, Callable[[], str | None]] = {
    "canalystii": _packages("canalystii"),
    "cantact": _packages("cantact"),
    "etas": _library("dll-csiBind"),
    "gs_usb": _packages("gs_usb", "usb"),
    "iscan": _module_flag("can.interfaces.iscan", "iscan"),
    "ixxat": _library("vcinpl2", "vcinpl"),
    "kvaser": _kvaser,
    "neousys": _module_flag("can.interfaces.neousys.neousys", "NEOUSYS_CANLIB"),
    "neovi": _packages("ics"),
    "nican": _library("nican"),
    "nixnet": _packages("nixnet"),
    "pcan": _library("pcanbasic", "PCANBasic", "PCBUSB"),
    "robotell": _packages("serial"),
    "seeedstudio": _packages("serial"),
    "serial": _packages("serial"),
    "slcan": _packages("serial"),
    "socketcan": _socketcan,
    "systec": _library("usbcan64", "usbcan32"),
    "udp_multicast": _packages("msgpack"),
    "usb2can": _library("usb2can"),
    "vector": _library("vxlapi64", "vxlapi"),
}


def can_interfaces() -> dict[str, dict[str, Any]]:
    """Every interface python-can has: ``driver`` true/false, and ``why`` and ``fix`` when
    false."""
    from can.interfaces import BACKENDS

    out: dict[str, dict[str, Any]] = {}
    quiet = logging.getLogger("can")
    level = quiet.level
    quiet.setLevel(logging.CRITICAL)  # python-can logs each driver it lacks on import
    try:
        for name in sorted(BACKENDS):
            out[name] = _interface(name, BACKENDS[name][0])
    finally:
        quiet.setLevel(level)
    return out


def _interface(name: str, module: str) -> dict[str, Any]:
    from pdcp_studio.bus.session.can_interfaces import driver_fix

    if name in WINDOWS_ONLY and sys.platform != "win32":
        why: str | None = "this driver exists for Windows only"
    else:
        try:
            importlib.import_module(module)
            why = PROBES.get(name, lambda: None)()
        except Exception as err:  # a driver module that does not import is the answer
            why = f"{module} does not import ({type(err).__name__}: {err})"
    entry: dict[str, Any] = {"driver": why is None}
    if why is not None:
        entry["why"] = why
        entry["fix"] = driver_fix(name)
    return entry


def serial_ports() -> list[dict[str, str]]:
    try:
        from serial.tools import list_ports
    except ImportError:
        return []
    return [{"device": p.device, "description": p.description, "hwid": p.hwid}
            for p in sorted(list_ports.comports(), key=lambda p: p.device)]


def log_formats() -> dict[str, dict[str, bool]]:
    """Capture file suffixes python-can reads and writes (``.mf4`` needs asammdf)."""
    from can.io.logger import MESSAGE_WRITERS
    from can.io.player import MESSAGE_READERS

    has_mdf = importlib.util.find_spec("asammdf") is not None
    out: dict[str, dict[str, bool]] = {}
    for suffix in sorted(set(MESSAGE_READERS) | set(MESSAGE_WRITERS)):
        usable = has_mdf or suffix != ".mf4"
        out[suffix] = {"read": suffix in MESSAGE_READERS and usable,
                       "write": suffix in MESSAGE_WRITERS and usable}
    return out


def display() -> dict[str, Any]:
    from pdcp_studio.app import qt_prereqs

    why = qt_prereqs.problem()
    return {"DISPLAY": os.environ.get("DISPLAY"),
            "WAYLAND_DISPLAY": os.environ.get("WAYLAND_DISPLAY"),
            "QT_QPA_PLATFORM": os.environ.get("QT_QPA_PLATFORM"),
            "window": why is None, "why": why,
            "screenshot": qt_prereqs.problem(screenshot=True) is None}


def archive(url: str | None = None) -> dict[str, Any]:
    """The fitting history in use: its engine and place, and who a change made now is
    recorded as (on PostgreSQL the signed-in role, asked of the server); an SQLite file is
    not made by asking."""
    from pdcp_studio.storage.archive import HistoryError, archive_url, describe, open_existing
    from pdcp_studio.storage.archive.base import default_operator

    doc: dict[str, Any] = {"engine": None, "location": None, "operator": None,
                           "signed_in": None, "may_record": None, "why": None}
    try:
        chosen = archive_url(url)
        doc["engine"] = "postgresql" if chosen.startswith("postgres") else "sqlite"
        doc["location"] = describe(chosen)
        opened = open_existing(chosen)
    except HistoryError as err:
        doc["why"] = str(err)
        return doc
    if opened is None:  # an SQLite archive not made yet
        doc["operator"], doc["may_record"] = default_operator(), True
        return doc
    with opened:
        try:
            opened.check_can_record()
            doc["may_record"] = True
        except HistoryError as err:
            doc["may_record"], doc["why"] = False, str(err)
        doc["operator"], doc["signed_in"] = opened.operator(), opened.signed_in()
    return doc


def report(archive_in_use: str | None = None) -> dict[str, Any]:
    from pdcp_studio import paths

    mods, failures = modules()
    try:
        resources: str | None = str(paths.resources_dir())
    except FileNotFoundError:
        resources = None
    vers = versions()
    return {
        "version": vers["pdcp-studio"],
        "versions": vers,
        "platform": platform.platform(),
        "frozen": bool(getattr(sys, "frozen", False)),
        "modules": mods,
        "module_errors": failures,
        "can_interfaces": can_interfaces(),
        "serial_ports": serial_ports(),
        "log_formats": log_formats(),
        "resources": resources,
        "user_data": str(paths.user_data_dir()),
        "history": str(paths.history_path()),
        "archive": archive(archive_in_use),
        "display": display(),
        "catalog_problems": _catalog_problems(),
    }


def _catalog_problems() -> list[str]:
    """Device catalogue files that were skipped, each with its file and why."""
    from pdcp_studio.model.catalog import default_catalog_problems

    return default_catalog_problems()


def _text(doc: dict[str, Any]) -> str:
    lines = [f"PDCP Studio {doc['version']} on {doc['platform']}"
             + (" (desktop build)" if doc["frozen"] else "")]
    lines.append("versions: " + ", ".join(f"{k} {v}" for k, v in doc["versions"].items()
                                          if v is not None))
    bad = [m for m, ok in doc["modules"].items() if not ok]
    lines.append(f"modules: {len(doc['modules']) - len(bad)} of {len(doc['modules'])} import")
    lines += [f"  {m}: {doc['module_errors'][m]}" for m in bad]
    lines.append("CAN interfaces (python-can):")
    for name, entry in doc["can_interfaces"].items():
        lines.append(f"  {name}: driver present" if entry["driver"]
                     else f"  {name}: {entry['why']} — fix: {entry['fix']}")
    ports = doc["serial_ports"]
    lines.append("serial ports: " + (", ".join(f"{p['device']} ({p['description']})"
                                              for p in ports) if ports else "none"))
    lines.append("capture formats: " + " ".join(
        s + ("" if f["read"] and f["write"] else " (read only)" if f["read"] else
             " (write only)" if f["write"] else " (needs asammdf)")
        for s, f in doc["log_formats"].items()))
    lines.append(f"resources: {doc['resources'] or 'MISSING'}")
    lines.append(f"user data: {doc['user_data']}")
    # The operator's full name comes from the clinic's server: shown, never run.
    lines.append("fitting history: " + _safe(_archive_text(doc["archive"], doc["history"])))
    lines += [f"device catalogue skipped: {p}" for p in doc["catalog_problems"]]
    shown = doc["display"]
    lines.append("display: " + ("a window can open" if shown["window"] else shown["why"]))
    return "\n".join(lines)


def _safe(text: str) -> str:
    from pdcp_studio.model.safe_text import shown

    return shown(text)


def _archive_text(a: dict[str, Any], path: str) -> str:
    if a["location"] is None:
        return f"{path} — {a['why']}"
    text = f"{a['location']} ({a['engine']})"
    if a["operator"] is None:
        return f"{text} — {a['why']}"
    who = (f"signed in as {a['signed_in']}" + (f" ({a['operator']})"
                                               if a["operator"] != a["signed_in"] else "")
           if a["signed_in"] else f"operator {a['operator']}")
    return f"{text}, {who}" + ("" if a["may_record"] else f" — {a['why']}")


def run(args: argparse.Namespace) -> int:
    doc = report(getattr(args, "archive", None))
    if args.json:
        print(json.dumps(doc, indent=2))
    else:
        print(_text(doc))
    healthy = all(doc["modules"].values()) and doc["resources"] is not None
    return 0 if healthy else 1
