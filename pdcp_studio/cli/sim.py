"""``pdcp-studio sim``: the built-in simulated prostheses.

``sim list`` names them, one a line. ``sim replay NAME [--json]`` runs a prosthesis's
scripted events (plug, unplug, replace, reset) on an in-process virtual bus and prints the
final system (``--json``: a system file with node IDs); it fails (exit 1) when the final
links are not the ones the script must end in. ``sim devices NAME|FILE --bus can:…`` runs
only the simulated devices on a CAN bus, for an arbitrator in another process, until
interrupted (or ``--seconds N``).
"""

from __future__ import annotations

import argparse
import sys
import time

from pdcp_studio.cli import options
from pdcp_studio.model.safe_text import shown


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("sim", help="built-in simulated prostheses",
                              description="List, replay and run simulated prostheses.")
    actions = p.add_subparsers(dest="sim_command", metavar="ACTION", required=True)

    ls = actions.add_parser("list", help="name the built-in prostheses, one a line")
    ls.add_argument("--long", action="store_true", help="with descriptions and scripts")
    ls.set_defaults(func=run_list)

    rp = actions.add_parser("replay", help="run a prosthesis's scripted events")
    rp.add_argument("name", metavar="NAME", help="a name `sim list` prints")
    rp.add_argument("--script", metavar="SCRIPT", help="another of its scripts (see list --long)")
    rp.add_argument("--json", action="store_true", help="print a system file with node IDs")
    rp.set_defaults(func=run_replay)

    dv = actions.add_parser("devices", help="run only the simulated devices on a CAN bus")
    dv.add_argument("name", metavar="NAME|FILE", help="a built-in prosthesis or a system file")
    dv.add_argument("--bus", required=True, metavar="URL", help="can:INTERFACE:CHANNEL")
    dv.add_argument("--seconds", type=options.SECONDS, metavar="N", help="stop after N seconds")
    dv.add_argument("--rate", type=options.RATE_HZ, metavar="HZ",
                    help="data rate of enabled outputs")
    dv.set_defaults(func=run_devices)


def run_list(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.sim.rigs import list_prostheses, prosthesis

    for name in list_prostheses():
        if args.long:
            entry = prosthesis(name)
            print(f"{name}: {entry.description}")
            for script in entry.scripts:
                print(f"  {script.name}: {script.description}")
        else:
            print(name)
    return 0


def run_replay(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.session.capabilities import SimulatorControls
    from pdcp_studio.bus.sim.rigs import ScriptError, UnknownProsthesisError, prosthesis
    from pdcp_studio.cli.live.scan import (
        format_system,
        open_bus_session,
        sorted_system,
        stderr_progress,
    )
    from pdcp_studio.cli.main import BadInput
    from pdcp_studio.errors import TransportError
    from pdcp_studio.storage import system_file

    try:
        entry = prosthesis(args.name)
        script = entry.script(args.script)
    except (ScriptError, UnknownProsthesisError) as err:
        raise BadInput(str(err)) from err
    session = open_bus_session(f"sim:{args.name}")
    try:
        if not isinstance(session, SimulatorControls):
            raise TransportError(f"sim:{args.name}: the bus opened has no simulator")
        result = session.run_script(script.name, stderr_progress(sys.stderr.isatty()))
        system = sorted_system(session.system())
    finally:
        session.close()
    if args.json:
        sys.stdout.write(system_file.dumps(system, node_ids=True))
    else:
        print(f"{args.name} · {script.name}: {script.description}")
        for step, links in result.trace:
            print(f"  {step}: {len(links)} link(s)")
        print(shown(format_system(system), newlines=True))
    if not result.ok:
        print(f"pdcp-studio: error: {args.name} {script.name} did not end in the expected "
              f"links: {result.mismatch()}", file=sys.stderr)
        return 1
    return 0


def run_devices(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.session.urls import check_bus_url, open_spec
    from pdcp_studio.bus.sim.device import SimulatedDevice
    from pdcp_studio.bus.sim.device_host import DeviceHost
    from pdcp_studio.bus.sim.rigs import UnknownProsthesisError, load_prosthesis
    from pdcp_studio.cli.main import BadInput

    spec = check_bus_url(args.bus)  # BusUrlError: exit 2, as from every command
    if spec.kind != "can":
        raise BadInput(f"--bus {args.bus}: sim devices runs on a can: bus "
                       "(can:INTERFACE:CHANNEL), for an arbitrator elsewhere")
    if args.seconds is not None and args.seconds <= 0:
        raise BadInput(f"--seconds {args.seconds}: must be positive")
    try:
        system = load_prosthesis(args.name)
    except UnknownProsthesisError as err:
        raise BadInput(str(err)) from err
    kwargs = {} if args.rate is None else {"data_rate_hz": args.rate}
    devices = [SimulatedDevice(d, **kwargs) for d in system.devices.values()]
    host = DeviceHost(open_spec(spec), devices, name=f"{args.bus} devices", plugged=False)
    try:
        plugged = [d.key for d in system.devices.values() if d.present]
        for key in plugged:
            host.plug(key)
        print(f"simulating {len(plugged)} device(s) of {args.name} on {args.bus}"
              + ("" if args.seconds else "; Ctrl-C stops"), file=sys.stderr, flush=True)
        started = time.monotonic()
        while args.seconds is None or time.monotonic() - started < args.seconds:
            time.sleep(0.1)
    except KeyboardInterrupt:
        pass
    finally:
        host.close()
    return 0
