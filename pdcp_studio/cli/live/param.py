"""``param get --bus URL PART[#CHANNEL] [--json]`` and
``param set --bus URL PART[#CHANNEL] NAME=VALUE… [--yes] [--store|--no-store] [--json]``.

One part's (or channel's) parameters on a live prosthesis, by name (contracts §2): ``type``,
``profile``, ``descriptor``, ``data-transfer`` (on/off), ``beacon-interval`` (ms) and the
rest of ``model/param_names.py``; numbers as in system files (``type=0x9700``). ``set`` is a
transaction of the change road (reference §5): previewed in words, written only with
``--yes``, read back and verified, recorded in the fitting history; by default the links
after it are stored as the arbitrator's configuration (``--no-store`` leaves it).
"""

from __future__ import annotations

import argparse
import json
import re
from typing import TYPE_CHECKING, Any

from pdcp_studio.cli.main import BadInput
from pdcp_studio.model.safe_text import shown

if TYPE_CHECKING:
    from pdcp_studio.model.refs import DeviceKey
    from pdcp_studio.model.system import Channel, Device, System

_PART = re.compile(r"^\s*(\w+)/(\w+)/(\w+)(?:#(\w+))?\s*$")


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    from pdcp_studio.cli.live.change_road import add_road_arguments

    p = subparsers.add_parser("param", help="read or set one part's parameters on a live "
                                            "prosthesis", description=__doc__.split("\n\n")[0])
    actions = p.add_subparsers(dest="param_command", metavar="ACTION", required=True)
    get = actions.add_parser("get", help="a part's or channel's parameters, by name")
    _common(get)
    get.add_argument("--json", action="store_true", help="print the contract's JSON document")
    get.set_defaults(func=run_get)
    put = actions.add_parser("set", help="set parameters by name (a previewed transaction)")
    _common(put)
    put.add_argument("assignments", nargs="+", metavar="NAME=VALUE",
                     help="e.g. type=0x9700 descriptor='Power grip' data-transfer=on")
    add_road_arguments(put)
    put.set_defaults(func=run_set)


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("--bus", required=True, metavar="URL", help="the prosthesis (contracts §3)")
    p.add_argument("part", metavar="PART[#CHANNEL]",
                   help="VID/PID/SERIAL, e.g. 2641/769/301 or 2641/769/301#1")
    p.add_argument("--memory", metavar="FILE",
                   help="PDCP Studio's own arbitrator memory (sim: and can: buses)")


def parse_part(text: str) -> tuple[DeviceKey, int | None]:
    """``2641/769/301#1`` → (key, 1); numbers in decimal or 0x…; BadInput otherwise."""
    from pdcp_studio.model.refs import DeviceKey

    m = _PART.match(text)
    if m is None:
        raise BadInput(f"{text!r}: a part is VID/PID/SERIAL, a channel VID/PID/SERIAL#N "
                       "(e.g. 2641/769/301#1)")
    try:
        vid, pid, serial = (int(x, 0) for x in m.group(1, 2, 3))
        channel = int(m.group(4), 0) if m.group(4) else None
    except ValueError as err:
        raise BadInput(f"{text!r}: {err}") from err
    return DeviceKey(vid, pid, serial), channel


def _target(system: System, text: str) -> tuple[Device, Device | Channel, int | None]:
    from pdcp_studio.model.names import Names

    key, channel = parse_part(text)
    device = system.device(key)
    if device is None:
        raise BadInput(f"{text}: no such part on the bus (parts: "
                       + ", ".join(f"{Names(system).part(k)} [{k}]" for k in system.devices)
                       + ")")
    if not device.present:
        raise BadInput(f"{text}: {Names(system).part(key)} is not on the bus now")
    if channel is None:
        return device, device, None
    ch = device.channels.get(channel)
    if ch is None:
        raise BadInput(f"{text}: {Names(system).part(key)} has no channel {channel} (it has "
                       + ", ".join(str(i) for i in sorted(device.channels)) + ")")
    return device, ch, channel


def _part_json(key: DeviceKey) -> dict[str, int]:
    return {"vid": key.vid, "pid": key.pid, "serial": key.serial}


def run_get(args: argparse.Namespace) -> int:
    from pdcp_studio.cli.live.scan import open_bus_session
    from pdcp_studio.model import param_names
    from pdcp_studio.model.names import Names

    session = open_bus_session(args.bus, memory=args.memory)
    try:
        system = session.system()
        device, obj, channel = _target(system, args.part)
        values = param_names.values(obj)
        if args.json:
            print(json.dumps({"part": _part_json(device.key), "channel": channel,
                              "parameters": values}, indent=2))
            return 0
        names = Names(system)
        title = names.part(device.key) if channel is None else names.channel(
            device.ref(channel))
        print(shown(f"{title} [{args.part.strip()}] on {args.bus}:"))
        width = max((len(k) for k in values), default=0)
        for name, value in values.items():
            print(shown(f"  {name:<{width}}  {value}"))
        return 0
    finally:
        session.close()


def assignments_of(items: list[str]) -> dict[str, str]:
    """``["type=0x9700", "descriptor=Power grip"]`` → a mapping; BadInput for a bad item."""
    out: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise BadInput(f"{item!r}: expected NAME=VALUE (e.g. type=0x9700)")
        out[name.strip()] = value
    return out


def run_set(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.transaction import Change, ParameterWrite
    from pdcp_studio.cli.live.change_road import carry_out
    from pdcp_studio.cli.live.scan import open_bus_session
    from pdcp_studio.errors import ParameterError
    from pdcp_studio.model import param_names

    wanted = assignments_of(args.assignments)
    session = open_bus_session(args.bus, memory=args.memory)
    try:
        system = session.system()
        device, obj, channel = _target(system, args.part)
        try:
            writes = param_names.writes_for(obj, wanted)
        except ParameterError as err:
            raise BadInput(f"{args.part}: {err}") from err
        change = Change("param set",
                        parameters=[ParameterWrite(device.key, param, channel or 0, data)
                                    for param, data in writes])

        def doc(_preview: Any, _result: Any) -> dict[str, Any]:
            now = session.system()
            d = now.device(device.key)
            target = d if d is None or channel is None else d.channels.get(channel)
            values = param_names.values(target) if target is not None else {}
            return {"part": _part_json(device.key), "channel": channel,
                    "parameters": values}

        return carry_out(session, change, args, json_doc=doc)
    finally:
        session.close()
