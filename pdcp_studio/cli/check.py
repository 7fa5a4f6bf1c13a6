"""``check --system FILE [--json]``: what a prosthetist must know before trusting a system.

Lists links that break sole access, inputs with two sources, required inputs left unmet,
terminal channels left unconnected (and why, by the same search autoconfigure uses),
links whose ends are missing, required/desired bits naming channels that are not inputs,
and the null profile 0x0000.
"""

from __future__ import annotations

import argparse
import json

from pdcp_studio.model.safe_text import shown

EPILOG = (
    "exit status: 0 when no finding is an error (warnings and notes may remain), "
    "1 when at least one error is found, 2 when FILE cannot be read or is not a valid "
    "pdcp-system/1 file."
)


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("check", help="problems in a system: sole access, unmet inputs, …",
                              description=__doc__.split("\n\n")[0], epilog=EPILOG)
    p.add_argument("--system", required=True, metavar="FILE", help="a pdcp-system/1 file")
    p.add_argument("--json", action="store_true",
                   help="print {system, findings, summary} as one JSON document")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from pdcp_studio.engine import Severity, check_system
    from pdcp_studio.storage.system_file import load_path

    system = load_path(args.system)
    findings = check_system(system)
    counts = {s.value: sum(f.severity is s for f in findings) for s in Severity}
    if args.json:
        doc = {"system": str(args.system), "findings": [f.to_json() for f in findings],
               "summary": counts}
        print(json.dumps(doc, indent=2))
    else:
        for f in findings:
            print(shown(str(f), newlines=True))
        print(f"{shown(args.system)}: {counts['error']} error(s), {counts['warning']} warning(s), "
              f"{counts['info']} note(s)")
    return 1 if counts["error"] else 0
