"""``print`` and ``info``: long (appendix D style) and short listings of a system file, or of
a live bus as it is now (``--bus URL``: the scan's system with node IDs, the thesis's
``pdcp_run print`` / ``info``).

``print`` follows the thesis implementation's printout (appendix D): counts, then
each device, input channel, output channel and channel link. Object addresses of
the original become readable references (``2/2/5#3``).
"""

from __future__ import annotations

import argparse

from pdcp_studio.errors import ModelError
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.safe_text import shown
from pdcp_studio.model.system import Channel, Device, Link, System


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    for name, helptext, func in (
            ("print", "long listing of a system or a live bus (appendix D style)", run_print),
            ("info", "short listing of a system or a live bus", run_info)):
        p = subparsers.add_parser(name, help=helptext)
        source = p.add_mutually_exclusive_group(required=True)
        source.add_argument("--system", metavar="FILE", help="a pdcp-system/1 file")
        source.add_argument("--bus", metavar="URL",
                            help="a live prosthesis as it is now (the scan's system)")
        p.add_argument("--memory", metavar="FILE",
                       help="PDCP Studio's own arbitrator memory (sim: and can: buses)")
        p.set_defaults(func=func)


def _load(args: argparse.Namespace) -> System:
    """The system file, or the live bus scanned (node IDs included), over any transport."""
    if getattr(args, "bus", None):
        from pdcp_studio.cli.live.scan import open_bus_session

        session = open_bus_session(args.bus, memory=getattr(args, "memory", None))
        try:
            return session.scan()
        finally:
            session.close()
    from pdcp_studio.storage.system_file import load_path

    return load_path(args.system)


def _bitmap_value(indices: tuple[int, ...]) -> int:
    """The bitmap as the thesis printed it: the bytes as one big-endian integer."""
    from pdcp_studio.model.parameters import indices_to_bitmap

    return int.from_bytes(indices_to_bitmap(indices), "big") if indices else 0


def _node(value: int | None) -> str:
    return str(value) if value is not None else "0"


def format_long(system: System) -> str:
    """The appendix D printout of ``system``."""
    devices = list(system.devices.values())
    inputs = [(d, c) for d in devices for c in sorted(d.inputs(), key=lambda c: c.index)]
    outputs = [(d, c) for d in devices for c in sorted(d.outputs(), key=lambda c: c.index)]
    links = system.links
    out: list[str] = [
        f"n_devices: {len(devices)}",
        f"n_missing_devices: {sum(not d.present for d in devices)}",
        f"n_input_channels: {len(inputs)}",
        f"n_output_channels: {len(outputs)}",
        f"n_channel_links: {len(links)}",
        "",
    ]
    for i, d in enumerate(devices):
        ins = ", ".join(str(d.ref(c.index)) for c in sorted(d.inputs(), key=lambda c: c.index))
        outs = ", ".join(str(d.ref(c.index)) for c in sorted(d.outputs(), key=lambda c: c.index))
        out += [
            f"device {i} ({d.key}):",
            f"name: {d.label}",
            f"vendor id: {d.vid}",
            f"product id: {d.pid}",
            f"serial number: {d.serial}",
            f"present: {'yes' if d.present else 'no (missing)'}",
            f"node_id: {_node(d.node_id)}",
            f"type: {d.device_type:X}",
            f"profile: {d.device_profile:X}",
            f"# of input channels: {len(d.inputs())}",
            f"# of output channels: {len(d.outputs())}",
            f"input channels: {ins}",
            f"output channels: {outs}",
            "",
        ]
    for i, (d, c) in enumerate(inputs):
        s = c.source
        src = system.source_of(d.ref(c.index))
        src_dev = system.device(src.device) if src else None
        src_ch = system.channel(src) if src else None
        out += [
            f"input channel {i} ({d.ref(c.index)}):",
            f"channel index: {c.index}",
            f"type: {c.type:X}",
            f"profile: {c.profile:X}",
            f"transfer enable: {int(c.data_enabled)}",
            f"required ichans: {_bitmap_value(c.required_inputs)}",
            f"desired ichans: {_bitmap_value(c.desired_inputs)}",
            f"terminal profile: {c.terminal_profile:X}",
            f"source channel node id: {_node(src_ch.node_id if src_ch else None)}",
            f"source device node id: {_node(src_dev.node_id if src_dev else None)}",
            f"source vid: {s.vid:X}",
            f"source pid: {s.pid:X}",
            f"source snum: {s.serial:X}",
            f"source ci: {s.index:X}",
            f"source type: {s.type:X}",
            f"source profile: {s.profile:X}",
            f"owner: {d.key}",
            f"channel link: {_link_name(system, d, c, links)}",
            "",
        ]
    for i, (d, c) in enumerate(outputs):
        ref = d.ref(c.index)
        fed = [lk for lk in links if lk.output == ref]
        out += [
            f"output channel {i} ({ref}):",
            f"node id: {_node(c.node_id)}",
            f"channel index: {c.index}",
            f"type: {c.type:X}",
            f"profile: {c.profile:X}",
            f"transfer enable: {int(c.data_enabled)}",
            f"required ichans: {_bitmap_value(c.required_inputs)}",
            f"desired ichans: {_bitmap_value(c.desired_inputs)}",
            f"owner: {d.key}",
            f"# of channel links: {len(fed)}",
            f"channel links: {', '.join(f'link {links.index(lk)}' for lk in fed)}",
            "",
        ]
    for i, lk in enumerate(links):
        out += [
            f"channel link {i}:",
            f"input channel: {lk.input}",
            f"output channel: {lk.output}",
            f"link status: {_link_status(system, lk)}",
            "",
        ]
    return "\n".join(out).rstrip() + "\n"


def _link_name(system: System, d: Device, c: Channel, links: list[Link]) -> str:
    ref = d.ref(c.index)
    names = [f"link {i}" for i, lk in enumerate(links) if lk.input == ref]
    return ", ".join(names) if names else "none"


def _link_status(system: System, link: Link) -> str:
    if system.is_present(link.output) and system.is_present(link.input):
        return "connected"
    return "missing end"


def format_short(system: System) -> str:
    """One line per device and per link: each by its one name (``cli/naming.py``), the
    numbers beside it in brackets."""
    out = [
        f"{len(system.devices)} devices "
        f"({sum(not d.present for d in system.devices.values())} missing), "
        f"{sum(len(d.channels) for d in system.devices.values())} channels, "
        f"{len(system.links)} links"
    ]
    from pdcp_studio.cli.naming import names_for

    names = names_for(system)
    for d in system.devices.values():
        state = "  (missing)" if not d.present else ""
        out.append(
            f"  {names.part(d.key)}: {len(d.inputs())} in, {len(d.outputs())} out{state}"
            f"  [{d.key}{'' if d.node_id is None else f', node {d.node_id}'}]"
        )
    for lk in system.links:
        o, i = _linked(system, lk.output), _linked(system, lk.input)
        out.append(f"  link {names.link(lk)}  [{lk.output} (0x{o.profile:04X}) → "
                   f"{lk.input} (0x{i.profile:04X})]")
    return "\n".join(out) + "\n"


def _linked(system: System, ref: ChannelRef) -> Channel:
    """The channel at one end of a link (a system holds only links between its channels)."""
    channel = system.channel(ref)
    if channel is None:
        raise ModelError(f"link end {ref} is not a channel of the system")
    return channel


def run_print(args: argparse.Namespace) -> int:
    print(shown(format_long(_load(args)), newlines=True), end="")
    return 0


def run_info(args: argparse.Namespace) -> int:
    print(shown(format_short(_load(args)), newlines=True), end="")
    return 0
