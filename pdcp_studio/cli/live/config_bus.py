"""``config read --bus URL -o FILE``, ``config write FILE --bus URL --yes`` and
``config save --bus URL [--yes]``.

The arbitrator's stored configuration over a live bus (contracts §2). ``read`` saves it as a
``.pdcfg`` file (atomically). ``write`` shows what would change first — links added and
removed per configuration — and refuses (exit 2) without ``--yes``; with it, the change road
(reference §5) writes, reads back and compares, restores the old configuration on a mismatch
(exit 1, saying what differs) and records the transaction in the fitting history. ``save``
stores the live links (the thesis's ``pdcp_run save``) the same way; without ``--yes`` it only
shows the difference and exits 0.
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pdcp_studio.model.configuration import ConfigCollection

from pdcp_studio.cli import options
from pdcp_studio.model.safe_text import shown


def add_bus_commands(actions: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Register ``read``, ``write`` and ``save`` under ``config`` (called by
    cli/config_cmd.py)."""
    from pdcp_studio.cli.live.change_road import add_archive_argument, add_road_arguments

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
    write.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    write.add_argument("--memory", metavar="FILE", help="PDCP Studio's own arbitrator memory")
    write.add_argument("--patient", metavar="REF",
                       help="the patient reference to record with the change (free text)")
    add_archive_argument(write)
    write.set_defaults(func=run_write)

    save = actions.add_parser("save", help="store the live links as the arbitrator's "
                                           "configuration (the thesis's save)")
    save.add_argument("--bus", required=True, metavar="URL", help="the bus (contracts §3)")
    save.add_argument("--memory", metavar="FILE", help="PDCP Studio's own arbitrator memory")
    add_road_arguments(save, store=False)
    save.set_defaults(func=run_save)


def _link_count(collection: ConfigCollection) -> int:
    return sum(len(c.links) for c in collection.configurations)


def describe_change(current: ConfigCollection, new: ConfigCollection) -> list[str]:
    """Lines saying how ``new`` differs from ``current``, link by link (the one
    configuration diff, model/config_diff.py)."""
    from pdcp_studio.model.config_diff import diff_configurations

    diff = diff_configurations(current, new)
    lines = [f"stored now: {len(current.configurations)} configuration(s), "
             f"{_link_count(current)} link(s); to write: {len(new.configurations)} "
             f"configuration(s), {_link_count(new)} link(s)"]
    for c in diff.configurations:
        for sl in c.only_in_b:
            lines.append(f"  + configuration {c.index}: {sl.output.ref} → {sl.input.ref}")
        for sl in c.only_in_a:
            lines.append(f"  - configuration {c.index}: {sl.output.ref} → {sl.input.ref}")
        for ch in c.changed:
            lines.append(f"  ~ configuration {c.index}: {ch.ends[0]} → {ch.ends[1]} "
                         "(channel records differ)")
    if len(lines) == 1:
        lines.append("  no link changes")
    return lines


def run_read(args: argparse.Namespace) -> int:
    from pdcp_studio.cli.live.scan import open_bus_session
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


def _print_change(current: ConfigCollection, new: ConfigCollection) -> None:
    for line in describe_change(current, new):
        print(shown(line))


def run_write(args: argparse.Namespace) -> int:
    """Show the difference; with ``--yes``, write it as a transaction (reference §5)."""
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.cli.live.change_road import carry_out
    from pdcp_studio.cli.live.scan import open_bus_session
    from pdcp_studio.cli.main import BadInput
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
        _print_change(session.read_configuration(), collection)
        if not args.yes:
            raise BadInput(f"not written to {args.bus}: add --yes to write {args.file} "
                           "(the difference is shown above)")
        change = Change(f"config write {args.file}", configuration=collection)
        code = carry_out(session, change, args, default_store=False)
        if code == 0:
            back = session.read_configuration()
            links = sum(len(c.links) for c in back.configurations)
            print(f"{args.file}: written to {args.bus} and verified ({len(back.configurations)} "
                  f"configuration(s), {links} link(s) read back)")
        return code
    finally:
        session.close()


def run_save(args: argparse.Namespace) -> int:
    """``config save --bus URL [--yes]``: the live links become the stored configuration."""
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.cli.live.change_road import carry_out
    from pdcp_studio.cli.live.scan import open_bus_session

    session = open_bus_session(args.bus, memory=args.memory)
    try:
        collection = session.configuration_of_links()
        if not args.json:
            _print_change(session.read_configuration(), collection)
        return carry_out(session, Change("config save", configuration=collection), args,
                         default_store=False)
    finally:
        session.close()
