"""``apply MODE --bus URL [--config CFG] [--yes] [--json]`` and
``apply MODE --system FILE [--config CFG] -o NEW.json``.

On a live prosthesis (``--bus``, the thesis's ``pdcp_run autoconfig/clear/enforce``): prints the
plan the profile layer makes on the bus as it is now (with the arbitrator's stored
configuration unless ``--config`` names one); with ``--yes`` carries it out as one transaction
(reference §5: motion interlock, write, read back, restore on a mismatch, release, fitting
history); without ``--yes`` writes nothing and exits 0 (on a terminal it asks first).

On a file (``--system``): plans exactly as ``plan`` does, applies the plan to the system —
links and the inputs' stored source fields, the same ``Plan.apply`` the app uses — and writes
the result atomically to NEW.json. The input file is never changed unless it is also NEW.json.
"""

from __future__ import annotations

import argparse
import json

from pdcp_studio.cli import options
from pdcp_studio.cli.live.change_road import add_road_arguments
from pdcp_studio.cli.main import BadInput
from pdcp_studio.cli.plan import CONFIG_MODES, add_mode_arguments, load_config, load_tree, make_plan
from pdcp_studio.model.safe_text import shown


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("apply", help="apply a profile-layer plan to a live prosthesis "
                                            "or a system file",
                              description=__doc__.split("\n\n")[0])
    add_mode_arguments(p, source_required=False)
    p.add_argument("--bus", metavar="URL", help="a live prosthesis (contracts §3)")
    p.add_argument("--memory", metavar="FILE",
                   help="PDCP Studio's own arbitrator memory (sim: and can: buses)")
    p.add_argument("-o", "--output", type=options.file_name, metavar="NEW.json",
                   help="with --system: where to write the resulting pdcp-system/1 file")
    add_road_arguments(p)
    p.set_defaults(func=run)


def summary(plan_text: str) -> str:
    """The plan's text without the closing list of every link (the file has those)."""
    head, _, _ = plan_text.partition("\nLinks after the plan")
    return head.rstrip("\n") + "\n"


def run(args: argparse.Namespace) -> int:
    if (args.system is None) == (args.bus is None):
        raise BadInput("apply: give exactly one of --system FILE (with -o NEW.json) or "
                       "--bus URL")
    if args.bus is not None:
        if args.output:
            raise BadInput("apply --bus: -o is for --system files; a live prosthesis is "
                           "changed in place")
        return run_bus(args)
    if not args.output:
        raise BadInput("apply --system: -o NEW.json is required (where to write the result)")
    return run_file(args)


def run_file(args: argparse.Namespace) -> int:
    from pdcp_studio.storage.system_file import save_path

    tree = load_tree(args.profiles)
    system, plan = make_plan(args)
    plan.apply(system)
    try:
        save_path(system, args.output)
    except OSError as err:
        raise BadInput(f"{args.output}: cannot write: {err.strerror or err}") from err
    if args.json:
        print(json.dumps(plan.to_json(), indent=2))
    else:
        print(shown(summary(plan.to_text(tree)), newlines=True), end="")
        print(f"wrote {args.output}: {len(system.links)} link(s)")
    return 0


def run_bus(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.cli.live.change_road import carry_out
    from pdcp_studio.cli.live.scan import open_bus_session
    from pdcp_studio.errors import EngineError

    config = load_config(args.config) if args.mode in CONFIG_MODES and args.config else None
    session = open_bus_session(args.bus, memory=args.memory)
    try:
        try:
            plan = session.preview(args.mode, config)
        except EngineError as err:
            raise BadInput(f"{args.config or args.bus}: {err}") from err
        if not args.json:  # the plan's head line and notes; its actions are in the preview
            print(plan.to_text(load_tree(args.profiles)).splitlines()[0])
            for note in plan.notes:
                print(f"note: {note}")
        change = Change.from_plan(plan, f"apply {args.mode}")
        return carry_out(session, change, args,
                         json_doc=lambda _preview, _result: plan.to_json())
    finally:
        session.close()
