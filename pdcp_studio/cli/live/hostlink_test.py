"""``hostlink-test --bus serial:PORT [--json]``: the host-link conformance suite.

Runs every case of ``bus/hostlink/testing/conformance.py`` against the arbitrator on PORT — a
firmware under development, or PDCP Studio's own (``arbitrator --host-serial``) — and prints one
line per case (``--json``: ``{"passed": [...], "failed": [...], "skipped": [...], "why":
{case: reason}}``). A case for a capability the arbitrator's HELLO does not declare is skipped,
not failed. Exit 0 only when no case fails, 1 when one fails or the port cannot be opened, 2 for
a bus URL that is not ``serial:``.
"""

from __future__ import annotations

import argparse
import json
import sys


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("hostlink-test",
                              help="run the host-link conformance suite against an arbitrator",
                              description=__doc__.split("\n\n")[0])
    p.add_argument("--bus", required=True, metavar="URL",
                   help="serial:PORT[@BAUD] — the arbitrator's host link")
    p.add_argument("--json", action="store_true", help="one JSON document on stdout")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.hostlink.port import open_port
    from pdcp_studio.bus.hostlink.testing.conformance import run_suite
    from pdcp_studio.bus.session.urls import BusUrlError, check_bus_url
    from pdcp_studio.cli.main import BadInput
    from pdcp_studio.errors import TransportError

    try:
        spec = check_bus_url(args.bus)
    except BusUrlError as err:
        raise BadInput(str(err)) from err
    if spec.kind != "serial":
        raise BadInput(f"--bus {args.bus}: hostlink-test talks to an arbitrator's host link "
                       "(serial:PORT[@BAUD])")
    try:
        port = open_port(spec.port, spec.baud, spec.url)
    except TransportError as err:
        print(f"pdcp-studio: {err}", file=sys.stderr)
        return 1

    def report(name: str, why: str | None) -> None:
        if not args.json:
            word = "pass" if why is None else "skip" if why.startswith("skipped: ") else "FAIL"
            print(f"{word}  {name}" + (f": {why}" if why else ""), flush=True)

    try:
        result = run_suite(port, report)
    finally:
        port.close()
    if args.json:
        print(json.dumps(result.to_json(), indent=2))
    else:
        print(f"{len(result.passed)} passed, {len(result.failed)} failed, "
              f"{len(result.skipped)} skipped")
    return 0 if result.ok else 1
