"""``policy --bus URL [--autoconfigure on|off] [--yes] [--json]``: the arbitrator's
profile-layer policy (issue 17, contracts §2).

Shows whether start-up and the duty cycle may autoconfigure unconnected terminal channels on
their own (``{"autoconfigure": true, …}``). Changing it is a transaction of the change road
(reference §5): previewed, written only with ``--yes``, read back, recorded in the fitting
history. Turning autoconfigure on makes, in that same transaction, the links the duty cycle
would make now (else nothing links them until the next swap); turning it off removes nothing
and says which links stay (``pdcp_studio.engine.policy_change``).
"""

from __future__ import annotations

import argparse
import json
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from pdcp_studio.bus.session.change_road import ChangePreview
    from pdcp_studio.bus.transaction import TransactionResult


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("policy", help="show or change a live arbitrator's "
                                             "profile-layer policy",
                              description=__doc__.split("\n\n")[0])
    p.add_argument("--bus", required=True, metavar="URL", help="the prosthesis (contracts §3)")
    p.add_argument("--autoconfigure", choices=("on", "off"),
                   help="may start-up and the duty cycle autoconfigure on their own?")
    p.add_argument("--memory", metavar="FILE",
                   help="PDCP Studio's own arbitrator memory (sim: and can: buses)")
    from pdcp_studio.cli.live.change_road import add_road_arguments

    add_road_arguments(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.transaction import Change, Policy
    from pdcp_studio.cli.live.change_road import carry_out
    from pdcp_studio.cli.live.scan import open_bus_session
    from pdcp_studio.engine.policy_change import policy_switch

    session = open_bus_session(args.bus, memory=args.memory)
    try:
        current = session.read_policy()
        if args.autoconfigure is None:
            if args.json:
                print(json.dumps({**current.to_json(), "bus": args.bus}, indent=2))
            else:
                print(f"{args.bus}: autoconfigure: {'on' if current.autoconfigure else 'off'}")
            return 0
        switch = policy_switch(session.system(), current.autoconfigure,
                               args.autoconfigure == "on")
        change = Change.from_plan(switch.plan, switch.action)
        change.policy = Policy(autoconfigure=switch.after)
        if switch.words and not args.json:
            for line in switch.words:
                print(line)

        def doc(_preview: ChangePreview, result: TransactionResult | None) -> dict[str, Any]:
            now = (result.policy_after if result is not None else None) or current
            return {**now.to_json(), "bus": args.bus,
                    "links_added": [a.to_json() for a in change.links if a.op == "add"],
                    "links_kept": [lk.as_json() for lk in switch.kept],
                    "kept_text": switch.words}

        return carry_out(session, change, args, json_doc=doc)
    finally:
        session.close()
