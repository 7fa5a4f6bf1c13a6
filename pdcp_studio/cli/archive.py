"""``archive init URL``: make a PostgreSQL database the clinic's fitting history.

Creates the schema, the group roles ``pdcp_fitter`` (records changes, reads) and
``pdcp_reader`` (reads only) with their grants, and the triggers that keep the archive
append-only and its chain unforked (``storage/archive/schema_pg.py``). Run once by the
clinic's administrator, signed in as a role that may create roles and a schema; running it
again changes nothing that is there. Logins are then PostgreSQL roles made members of one
group: ``CREATE ROLE anna LOGIN PASSWORD '…' IN ROLE pdcp_fitter`` (docs/clinic-archive.md).
"""

from __future__ import annotations

import argparse

from pdcp_studio.cli.main import BadInput
from pdcp_studio.model.safe_text import shown


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("archive", help="set up the clinic's shared fitting history",
                              description=__doc__.split("\n\n")[0])
    actions = p.add_subparsers(dest="archive_command", metavar="ACTION", required=True)
    init = actions.add_parser(
        "init", help="create the schema and the roles pdcp_fitter and pdcp_reader",
        description="Creates the fitting-history schema in a PostgreSQL database with the "
                    "group roles pdcp_fitter (records changes, reads) and pdcp_reader (reads "
                    "only); entries can never be updated or deleted. Run as the clinic's "
                    "database administrator; safe to run again.")
    init.add_argument("url", metavar="URL", help="postgresql://ADMIN@HOST[:PORT]/DB")
    init.set_defaults(func=run_init)


def run_init(args: argparse.Namespace) -> int:
    import sys

    from pdcp_studio.storage.archive import HistoryError
    from pdcp_studio.storage.archive.open import is_postgres

    if not is_postgres(args.url):
        raise BadInput(f"archive init: {args.url!r}: a clinic's archive is a PostgreSQL "
                       "database: postgresql://USER@HOST[:PORT]/DB (an SQLite archive needs "
                       "no set-up)")
    from pdcp_studio.storage.archive.postgres import init_schema

    try:
        where = init_schema(args.url)
    except HistoryError as err:
        print(f"pdcp-studio: {shown(str(err))}", file=sys.stderr)
        return 1
    print(f"{shown(where)}: the fitting history is ready (schema pdcp; roles pdcp_fitter and "
          "pdcp_reader). Make logins with: CREATE ROLE name LOGIN PASSWORD '…' IN ROLE "
          "pdcp_fitter")
    return 0
