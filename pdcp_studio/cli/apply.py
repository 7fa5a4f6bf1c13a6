"""``apply MODE --system FILE [--config CFG] -o NEW.json``: write the system with a plan applied.

Plans exactly as ``plan`` does (same modes, same ``--config`` forms: ``.pdcfg`` bytes,
``config decode --json`` JSON, or a system file whose links are the configuration), applies
the plan to the system — links and the inputs' stored source fields — and writes the result
atomically to NEW.json. The input file is never changed unless it is also NEW.json.
"""

from __future__ import annotations

import argparse
import json

from pdcp_studio.cli import options
from pdcp_studio.cli.main import BadInput
from pdcp_studio.cli.plan import add_mode_arguments, load_tree, make_plan


def add_subparser(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser("apply", help="apply a profile-layer plan and write the new system",
                              description=__doc__.split("\n\n")[0])
    add_mode_arguments(p)
    p.add_argument("-o", "--output", required=True, type=options.file_name, metavar="NEW.json",
                   help="where to write the resulting pdcp-system/1 file")
    p.add_argument("--json", action="store_true", help="print the applied plan as JSON")
    p.set_defaults(func=run)


def summary(plan_text: str) -> str:
    """The plan's text without the closing list of every link (the file has those)."""
    head, _, _ = plan_text.partition("\nLinks after the plan")
    return head.rstrip("\n") + "\n"


def run(args: argparse.Namespace) -> int:
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
        print(summary(plan.to_text(tree)), end="")
        print(f"wrote {args.output}: {len(system.links)} link(s)")
    return 0
