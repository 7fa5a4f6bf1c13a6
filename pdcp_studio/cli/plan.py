"""``plan MODE --system FILE [--config CFG] [--json]``: the profile layer as a dry run.

Prints what the engine would add and remove, in order, with the rule and similarity
behind each step and what it tried and refused; ``--json`` prints the contract's document
(contracts §2) with the explanations as extra fields.

``--config`` is read for ``replacements``, ``implement`` and ``startup`` only (ignored,
unread, for the others). It may be stored-configuration bytes (``.pdcfg``), the JSON that
``config decode --json`` prints, or a ``pdcp-system/1`` file whose links are taken as the
configuration. ``implement`` and ``replacements`` without it work on the system's own
links; ``startup`` without it retrieves the configuration from the devices. A collection
with no configuration in it (an arbitrator's empty memory) means nothing stored.
"""

from __future__ import annotations

import argparse
import json
from typing import TYPE_CHECKING

from pdcp_studio.cli.main import BadInput
from pdcp_studio.model.safe_text import shown

if TYPE_CHECKING:
    from pdcp_studio.engine.plan import Plan
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.model.profile_tree import ProfileTree
    from pdcp_studio.model.system import System

# Kept here (not imported from the engine) so that building the parser stays cheap;
# tests/cli/test_cli_plan.py checks they match pdcp_studio.engine.MODES + EXTRA_MODES.
MODE_NAMES = ("autoconfigure", "replacements", "implement", "startup", "enforce", "clear",
              "duty-cycle")
CONFIG_MODES = ("replacements", "implement", "startup")
MODE_HELP = (
    "autoconfigure: link unconnected terminal channels (listing 4.7); "
    "replacements: implement CFG, then replace its missing channels (4.6); "
    "implement: make CFG's links (4.3); startup: the start-up procedure (4.1/5.1); "
    "enforce: remove links that break sole access; clear: remove every link; "
    "duty-cycle: the hot-swap cycle (4.2)"
)


def add_mode_arguments(p: argparse.ArgumentParser, *, source_required: bool = True) -> None:
    """The arguments ``plan`` and ``apply`` share (``apply`` takes ``--bus`` instead of
    ``--system`` too, so there ``--system`` is not required)."""
    p.add_argument("mode", choices=MODE_NAMES, metavar="MODE", help=MODE_HELP)
    p.add_argument("--system", required=source_required, metavar="FILE",
                   help="a pdcp-system/1 file")
    p.add_argument("--config", metavar="CFG",
                   help="the stored configuration: .pdcfg bytes, `config decode --json` JSON, "
                        "or a pdcp-system/1 file whose links are the configuration")
    p.add_argument("--profiles", metavar="TREE",
                   help="a pdcp-profile-tree/1 file, to name profiles in the text output")


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("plan", help="what the profile layer would link, and why (dry run)",
                              description=__doc__.split("\n\n")[0])
    add_mode_arguments(p)
    p.add_argument("--json", action="store_true", help="print the plan as one JSON document")
    p.set_defaults(func=run)


def load_system(path: str) -> System:
    from pdcp_studio.storage.system_file import load_path

    return load_path(path)


def load_config(path: str) -> ConfigCollection:
    """Stored configurations from bytes, their decode JSON, or a system file's links."""
    from pdcp_studio.cli.config_cmd import MAX_JSON_BYTES, MAX_JSON_DEPTH
    from pdcp_studio.errors import ConfigFormatError, SystemFileError
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.storage import config_codec
    from pdcp_studio.storage.bounded_input import InputError, loads_json, read_capped

    try:
        data = read_capped(path, MAX_JSON_BYTES, "a configuration")
    except InputError as err:
        raise BadInput(f"{path}: {err}") from None
    except OSError as err:
        raise BadInput(f"{path}: cannot read: {err.strerror or err}") from err
    try:
        if data.lstrip()[:1] != b"{":
            return config_codec.loads(data)
        try:
            doc = loads_json(data, max_depth=MAX_JSON_DEPTH)
        except InputError as err:
            raise BadInput(f"{path}: {err}") from None
        if isinstance(doc, dict) and doc.get("format") == "pdcp-system/1":
            from pdcp_studio.engine import configuration_from_system
            from pdcp_studio.storage.system_file import from_json

            return ConfigCollection([configuration_from_system(from_json(doc))])
        return config_codec.from_json(doc)
    except (ConfigFormatError, SystemFileError) as err:
        raise BadInput(f"{path}: {err}") from err


#: A profile-tree file holds at most this many bytes and this many levels of nesting.
MAX_TREE_BYTES = 1024 * 1024
MAX_TREE_DEPTH = 64


def load_tree(path: str | None) -> ProfileTree | None:
    if not path:
        return None
    from pdcp_studio.errors import ProfileError
    from pdcp_studio.model.profile_tree import ProfileTree
    from pdcp_studio.storage.bounded_input import loads_json, read_capped

    try:
        doc = loads_json(read_capped(path, MAX_TREE_BYTES, "a profile tree"),
                         max_depth=MAX_TREE_DEPTH)
        return ProfileTree.from_json(doc, where=f"{path}: ")
    except OSError as err:
        raise BadInput(f"{path}: cannot read: {err.strerror or err}") from err
    except (ValueError, ProfileError) as err:
        raise BadInput(f"{path}: {err}") from err


def make_plan(args: argparse.Namespace) -> tuple[System, Plan]:
    """Load the inputs named by ``args`` and plan; bad input raises BadInput (exit 2)."""
    from pdcp_studio.engine import plan_for
    from pdcp_studio.errors import EngineError

    system = load_system(args.system)
    config = None
    if args.mode in CONFIG_MODES and args.config:
        config = load_config(args.config)
    try:
        return system, plan_for(args.mode, system, config)
    except EngineError as err:
        raise BadInput(f"{args.config or args.system}: {err}") from err


def run(args: argparse.Namespace) -> int:
    tree = load_tree(args.profiles)
    system, plan = make_plan(args)
    if args.json:
        print(json.dumps(plan.to_json(), indent=2))
    else:
        from pdcp_studio.cli.naming import names_for

        print(shown(plan.to_text(tree, names_for(system, tree)), newlines=True), end="")
    return 0
