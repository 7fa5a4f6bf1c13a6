"""``pdcp-studio config``: stored-configuration files (reference §3, contracts §2).

``decode FILE [--json]`` lists a ``.pdcfg`` file (``--json``: the contract JSON, one
document on stdout); ``encode JSON -o FILE`` writes one from that JSON, atomically.
``diff A B [--json]`` or ``diff A --bus URL`` compares two stored configurations (the
one diff of :mod:`pdcp_studio.model.config_diff`): exit 0 when equal, 3 when they differ.
``-`` reads standard input. The bus actions (``config read`` / ``config write``) live in
``pdcp_studio.cli.live.config_bus``, which registers them through
``add_bus_commands(config_subparsers)``; it is imported while the parser is built, so it
too must keep heavy imports (python-can) inside its ``run``.

Errors: a file that does not decode or validate, and an input file that cannot be read,
are bad input (exit 2) with one stderr line naming the file, ``offset N`` and the reason.
A failure to write the output is exit 1 (an ``OSError``, handled by the dispatcher).
"""

from __future__ import annotations

import argparse
from typing import Any

from pdcp_studio.cli import options
from pdcp_studio.model.safe_text import shown

#: The JSON ``config encode`` reads holds at most this many bytes: the largest collection the
#: codec accepts (16,384 links), as ``decode --json`` prints it, fits with room to spare.
MAX_JSON_BYTES = 16 * 1024 * 1024
#: … nested at most this deep (the format itself needs 6 levels).
MAX_JSON_DEPTH = 16


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Register ``config`` and its actions (``decode``, ``encode``, and the bus ones)."""
    parser = subparsers.add_parser(
        "config", help="stored configurations (.pdcfg): decode, encode, read, write",
        description="Read and write the byte format an arbitrator stores its links in.",
    )
    actions = parser.add_subparsers(dest="config_command", metavar="ACTION", required=True)

    decode = actions.add_parser("decode", help="list a stored-configuration file")
    decode.add_argument("file", metavar="FILE", help="a .pdcfg file, or - for stdin")
    decode.add_argument("--json", action="store_true", help="print the contract JSON")
    decode.set_defaults(func=run_decode)

    encode = actions.add_parser("encode", help="write a stored-configuration file from JSON")
    encode.add_argument("json_file", metavar="JSON", help="JSON as `decode --json` prints it")
    encode.add_argument("-o", "--output", required=True, type=options.file_name,
                        metavar="FILE", help="the .pdcfg")
    encode.set_defaults(func=run_encode)

    diff = actions.add_parser(
        "diff", help="compare two stored configurations (exit 3 when they differ)",
        description="Compare two .pdcfg files, or a file with the stored configuration of the "
                    "arbitrator on a bus. Exit 0 when equal, 3 when they differ.")
    diff.add_argument("a", metavar="A", help="a .pdcfg file")
    diff.add_argument("b", metavar="B", nargs="?", help="a second .pdcfg file")
    diff.add_argument("--bus", metavar="URL", help="compare A with this bus's stored configuration")
    diff.add_argument("--memory", metavar="FILE", help="PDCP Studio's own arbitrator memory")
    diff.add_argument("--json", action="store_true", help="print the difference as JSON")
    diff.set_defaults(func=run_diff)

    from pdcp_studio.cli.live import config_bus

    config_bus.add_bus_commands(actions)


def _read_input(path: str, limit: int, what: str, *, refuse: bool = True) -> bytes:
    """The input file (or stdin), at most ``limit`` bytes; beyond it bad input naming the
    file (``refuse``) or the first ``limit`` bytes for a reader that refuses them itself."""
    from pdcp_studio.cli.main import BadInput
    from pdcp_studio.storage.bounded_input import InputError, read_capped, read_prefix

    try:
        return read_capped(path, limit, what) if refuse else read_prefix(path, limit)
    except InputError as err:
        raise BadInput(f"{path}: {err}") from None
    except OSError as err:
        raise BadInput(f"{path}: cannot read: {err.strerror or err}") from err


#: ``config diff``'s exit status when the configurations differ (contracts §2).
DIFFER = 3


def _load_collection(path: str) -> Any:
    """A ``.pdcfg`` file (or stdin) as a collection; a bad one is bad input with its offset."""
    from pdcp_studio.cli.main import BadInput
    from pdcp_studio.errors import ConfigFormatError
    from pdcp_studio.storage import config_codec

    data = _read_input(path, config_codec.MAX_INPUT_BYTES + 1, "a stored configuration",
                       refuse=False)
    try:
        return config_codec.loads(data)
    except ConfigFormatError as err:
        raise BadInput(f"{path}: offset {err.offset}: {err.reason}") from err


def run_diff(args: argparse.Namespace) -> int:
    """Compare A with B or with the bus's stored configuration; 0 equal, 3 different."""
    import json

    from pdcp_studio.cli.main import BadInput
    from pdcp_studio.model.config_diff import diff_configurations

    if (args.b is None) == (args.bus is None):
        raise BadInput("config diff: give either a second file B or --bus URL (not both)")
    if args.memory and args.bus is None:
        raise BadInput("config diff: --memory needs --bus")
    if args.bus is not None:
        from pdcp_studio.bus.session.urls import check_bus_url

        check_bus_url(args.bus)  # BusUrlError: exit 2, the same line as from every command
    a = _load_collection(args.a)
    if args.b is not None:
        b, b_name = _load_collection(args.b), args.b
    else:
        from pdcp_studio.cli.live.scan import open_bus_session

        session = open_bus_session(args.bus, memory=args.memory)
        try:
            b = session.read_configuration()
        finally:
            session.close()
        b_name = f"the arbitrator on {args.bus}"
    diff = diff_configurations(a, b)
    if args.json:
        print(json.dumps(diff.to_json(), indent=2))
    elif diff.equal:
        print(shown(f"{args.a} and {b_name} store the same configurations "
                    f"({len(a.configurations)} configuration(s), "
                    f"{sum(len(c.links) for c in a.configurations)} link(s))"))
    else:
        for line in diff.lines(args.a, b_name):
            print(shown(line))
    return 0 if diff.equal else DIFFER


def run_decode(args: argparse.Namespace) -> int:
    """Decode a file and print it as text or as the contract JSON."""
    import json

    from pdcp_studio.cli.main import BadInput
    from pdcp_studio.errors import ConfigFormatError
    from pdcp_studio.storage import config_codec

    # One byte over the limit is enough for the codec to refuse a huge file.
    data = _read_input(args.file, config_codec.MAX_INPUT_BYTES + 1, "a stored configuration",
                       refuse=False)
    try:
        decoded = config_codec.decode(data)
    except ConfigFormatError as err:
        raise BadInput(f"{args.file}: offset {err.offset}: {err.reason}") from err
    if args.json:
        print(json.dumps(config_codec.to_json(decoded.collection), indent=2))
    else:
        print("\n".join(shown(line) for line in format_listing(args.file, decoded)))
    return 0


def format_listing(name: str, decoded: Any) -> list[str]:
    """A readable listing: a summary line, then each configuration's links, output → input."""
    configs = decoded.collection.configurations
    links = sum(len(cfg.links) for cfg in configs)
    checksum = (f"checksum 0x{decoded.checksum:04X} verified" if decoded.checksum is not None
                else "no checksum (thesis-era file)")
    lines = [f"{name}: {len(configs)} configuration(s), {links} link(s), {decoded.size} bytes, "
             f"{checksum}"]
    if decoded.unknown_records:
        lines.append(f"  {decoded.unknown_records} record(s) with unknown codes kept")
    if decoded.collection.unknown:
        lines.append(f"  collection: {_unknown_text(decoded.collection.unknown)}")
    if decoded.trailing_bytes:
        lines.append(f"  {decoded.trailing_bytes} byte(s) after End ignored")
    for cfg in configs:
        extra = f"; {_unknown_text(cfg.unknown)}" if cfg.unknown else ""
        lines.append(f"configuration {cfg.index}: {len(cfg.links)} link(s){extra}")
        for link in cfg.links:
            extra = f"  ({_unknown_text(link.unknown)})" if link.unknown else ""
            lines.append(f"  link {link.index}: output {_channel_text(link.output)}{extra}")
            pad = " " * len(f"link {link.index}")
            lines.append(f"  {pad}→ input  {_channel_text(link.input)}")
    return lines


def _unknown_text(records: Any) -> str:
    """``unknown records: code 32 = 0x1234, …`` (kept and written back as they are)."""
    return "unknown records: " + ", ".join(f"code {r.code} = 0x{r.value:04X}" for r in records)


def _channel_text(ch: Any) -> str:
    text = f"{ch.ref}  type 0x{ch.type:04X}  profile 0x{ch.profile:04X}"
    if ch.owner_type is not None:
        text += f"  owner type {ch.owner_type}"
    if ch.owner_profile is not None:
        text += f"  owner profile {ch.owner_profile}"
    if ch.unknown:
        text += f"  {_unknown_text(ch.unknown)}"
    return text


def run_encode(args: argparse.Namespace) -> int:
    """Validate the JSON and write the byte file atomically."""
    from pdcp_studio.cli.main import BadInput
    from pdcp_studio.errors import ConfigFormatError
    from pdcp_studio.storage import config_codec
    from pdcp_studio.storage.atomic import atomic_write_bytes
    from pdcp_studio.storage.bounded_input import InputError, loads_json

    data = _read_input(args.json_file, MAX_JSON_BYTES, "configuration JSON")
    try:
        doc = loads_json(data, max_depth=MAX_JSON_DEPTH)
    except InputError as err:
        raise BadInput(f"{args.json_file}: {err}") from None
    try:
        collection = config_codec.from_json(doc)
        data = config_codec.dumps(collection)
    except ConfigFormatError as err:
        raise BadInput(f"{args.json_file}: {err.reason}") from err
    atomic_write_bytes(args.output, data)
    links = sum(len(cfg.links) for cfg in collection.configurations)
    print(f"{args.output}: {len(collection.configurations)} configuration(s), "
          f"{links} link(s), {len(data)} bytes written")
    return 0

