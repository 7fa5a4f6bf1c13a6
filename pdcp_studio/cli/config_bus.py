"""``config read --bus URL -o FILE`` and ``config write FILE --bus URL --yes``.

The arbitrator's stored configuration over a live bus (contracts §2). ``read`` saves it as a
``.pdcfg`` file (atomically). ``write`` shows what would change first — links added and
removed per configuration — and refuses (exit 2) without ``--yes``; with it, the session
writes, reads back and compares, and a mismatch fails (exit 1) saying what differs.
"""

from __future__ import annotations

import argparse
from typing import Any

from pdcp_studio.cli import options


def add_bus_commands(actions: Any) -> None:
    """Register ``read`` and ``write`` under ``config`` (called by cli/config_cmd.py)."""
    read = actions.add_parser("read", help="save an arbitrator's stored configuration")
    read.add_argument("--bus", required=True, metavar="URL", help="the bus (contracts §3)")
    read.add_argument("-o", "--output", required=True, type=options.file_name,
                      metavar="FILE", help="the .pdcfg")
    read.add_argument("--memory", metavar="FILE", help="PDCP Studio's own arbitrator memory")
    read.set_defaults(func=run_read)

    write = actions.add_parser("write", help="write a stored configuration to an arbitrator")
    write.add_argument("file", metavar="FILE", help="a .pdcfg file")
    write.add_argument("--bus", required=True, metavar="URL", help="the bus (contracts §3)")
    write.add_argument("--yes", action="store_true", help="write after showing the difference")
    write.add_argument("--memory", metavar="FILE", help="PDCP Studio's own arbitrator memory")
    write.set_defaults(func=run_write)


def _links(collection: Any) -> dict[int, set[tuple]]:
    return {c.index: {(sl.output.ref, sl.input.ref) for sl in c.links}
            for c in collection.configurations}


def describe_change(current: Any, new: Any) -> list[str]:
    """Lines saying how ``new`` differs from ``current``, link by link."""
    old_links, new_links = _links(current), _links(new)
    lines = [f"stored now: {len(current.configurations)} configuration(s), "
             f"{sum(len(v) for v in old_links.values())} link(s); to write: "
             f"{len(new.configurations)} configuration(s), "
             f"{sum(len(v) for v in new_links.values())} link(s)"]
    changed = False
    for index in sorted(set(old_links) | set(new_links)):
        before, after = old_links.get(index, set()), new_links.get(index, set())
        for out, inp in sorted(after - before):
            lines.append(f"  + configuration {index}: {out} → {inp}")
            changed = True
        for out, inp in sorted(before - after):
            lines.append(f"  - configuration {index}: {out} → {inp}")
            changed = True
    if not changed:
        lines.append("  no link changes")
    return lines


def run_read(args: argparse.Namespace) -> int:
    from pdcp_studio.cli.scan import open_bus_session
    from pdcp_studio.storage import config_codec

    session = open_bus_session(args.bus, memory=args.memory)
    try:
        collection = session.read_configuration()
    finally:
        session.close()
    config_codec.save_path(collection, args.output)
    links = sum(len(c.links) for c in collection.configurations)
    print(f"{args.output}: {len(collection.configurations)} configuration(s), {links} link(s) "
          f"read from {args.bus}")
    return 0


def run_write(args: argparse.Namespace) -> int:
    from pdcp_studio.cli.main import BadInput
    from pdcp_studio.cli.scan import open_bus_session
    from pdcp_studio.errors import ConfigFormatError
    from pdcp_studio.storage import config_codec

    try:
        collection = config_codec.load_path(args.file)
    except ConfigFormatError as err:
        raise BadInput(f"{args.file}: offset {err.offset}: {err.reason}") from err
    except OSError as err:
        raise BadInput(f"{args.file}: cannot read: {err.strerror or err}") from err
    session = open_bus_session(args.bus, memory=args.memory)
    try:
        current = session.read_configuration()
        for line in describe_change(current, collection):
            print(line)
        if not args.yes:
            raise BadInput(f"not written to {args.bus}: add --yes to write {args.file} "
                           "(the difference is shown above)")
        back = session.write_configuration(collection)
    finally:
        session.close()
    links = sum(len(c.links) for c in back.configurations)
    print(f"{args.file}: written to {args.bus} and verified ({len(back.configurations)} "
          f"configuration(s), {links} link(s) read back)")
    return 0
