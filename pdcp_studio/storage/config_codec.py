"""The stored-configuration byte format (reference §3, thesis §4.5, table 4.1, figure 4.10).

This is what a bus arbitrator keeps in its memory so that it can rebuild the links after a
restart, so the reader is strict (a wrong link drives a motor) and bounded (the bytes may
come from erased flash or a hostile file). Loading comes in three tiers: ``loads(bytes)``,
``load(fileobj)``, ``load_path(path)``; writing mirrors them, and ``save_path`` is atomic.

Format: 3-byte records, a code (u8) and a value (u16, little-endian). Declarations follow
the thesis: a configuration runs from code 2 to the next 2 or End (15); a link from 4 to
the next 4, 2 or 15; an input channel from 5 to 6, 4, 2 or 15; an output channel from 6 to
5, 4, 2 or 15. Unknown codes (0 and 17…255) are allowed anywhere a declaration is open.

Unknown codes are kept, not dropped (reference §3): each unknown record is attached to the
innermost open declaration (collection, configuration, link, input or output channel) as an
``UnknownRecord`` in file order, with ``after`` = the known record of that declaration it
followed (``None`` when no known record of the declaration follows it). The writer puts it
back right after that record, so decode → encode of a valid file gives the same records,
only the checksum added or recomputed (and, as before, known values in code order). The
contract JSON carries each record as ``{"code", "value"}`` on its object, in file order, and
nothing more: through JSON a record keeps its declaration and order and is written at the
end of that declaration's own records, where writers append (``from_json`` also takes an
optional ``"after": CODE`` to pin it elsewhere).

Decisions (reference §3 plus the ones it leaves open):
- Extension code 16 = checksum: CRC-16/CCITT-FALSE of every byte before it, immediately
  before End. The writer always emits it; the reader verifies it when present and insists
  that End follows it directly (later records would be unprotected).
- Bytes after End are ignored (erased flash reads 0xFF), so only the part up to and
  including End must be whole records: 1–2 stray bytes are an error only when no End came
  before them ("truncated record"); otherwise a missing End is reported.
- Codes 1 and 3 are required: 1 is the first known record, 3 the first known record after
  its 2. A count that disagrees with what follows is reported at the count record.
- Configuration and link indices count from 1 and are unique (links per configuration);
  the channel index is 1…255. Channel index, owner VID, PID and serial are required; type
  and profile default to 0. A value record twice in one channel, or a second input
  (output) channel in one link, is refused. Values of 5, 6 and 15 are ignored ("use 0").
- Limits against hostile input: ``MAX_INPUT_BYTES`` (1 MiB; ``load`` reads at most one
  byte more), ``MAX_CONFIGURATIONS`` (255), ``MAX_LINKS`` (16,384 in the collection).
  Any collection within the limits encodes below 1 MiB; the writer enforces them too.
- Writer indices: kept if they are a permutation of 1…n (labels survive), else renumbered
  1…n in list order. A file the program wrote decodes and re-encodes to identical bytes.
- Decoding errors are ``ConfigFormatError(reason, offset)``, offset ≥ 0 = the offending
  record. Writer and JSON errors have offset -1 and name the JSON path
  (``configurations[0].links[1].input.index: 0 is out of range 1…255``).
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from pathlib import Path
from typing import Any, BinaryIO

from pdcp_studio.errors import ConfigFormatError
from pdcp_studio.model.config_diff import channel_json, link_json, unknown_json, with_unknown
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
    Unknown,
    UnknownRecord,
)
from pdcp_studio.protocol.crc import crc16_ccitt_false
from pdcp_studio.storage.json_number import parse_number

# Codes of table 4.1, plus the checksum extension (16).
COUNT_CONFIGURATIONS, CONFIGURATION, COUNT_LINKS, LINK = 1, 2, 3, 4
INPUT_CHANNEL, OUTPUT_CHANNEL = 5, 6
CHANNEL_TYPE, CHANNEL_PROFILE, CHANNEL_INDEX = 7, 8, 9
OWNER_VID, OWNER_PID, OWNER_SERIAL, OWNER_TYPE, OWNER_PROFILE = 10, 11, 12, 13, 14
END, CHECKSUM = 15, 16

CODE_NAMES = {
    1: "# of configurations", 2: "Configuration", 3: "# of links", 4: "Channel link",
    5: "Input channel", 6: "Output channel", 7: "Channel type", 8: "Channel profile",
    9: "Channel index", 10: "Owner VID", 11: "Owner PID", 12: "Owner serial number",
    13: "Owner type", 14: "Owner profile", 15: "End", 16: "Checksum",
}

RECORD_SIZE = 3
MAX_INPUT_BYTES = 1 << 20
MAX_CONFIGURATIONS = 255
MAX_LINKS = 16384

# One record: code (u8), value (u16 little-endian).
_RECORD = struct.Struct("<BH")
# Two records: (1, count) or (2, index) + (3, link count).
_TWO_RECORDS = struct.Struct("<BHBH")
# A channel's fixed block: (5|6, 0), (7, type), (8, profile), (9, index), (10, VID),
# (11, PID), (12, serial); owner type/profile (13, 14) follow as single records when set.
_CHANNEL = struct.Struct("<" + "BH" * 7)

_REQUIRED = (CHANNEL_INDEX, OWNER_VID, OWNER_PID, OWNER_SERIAL)
_Err = ConfigFormatError  # short alias: messages stay on one line


@dataclass(frozen=True)
class Decoded:
    """What ``decode`` found besides the links: for listings and diagnostics."""

    collection: ConfigCollection
    checksum: int | None  # the verified stored checksum, None in a thesis-era file
    end_offset: int  # byte offset of the End record
    size: int  # length of the input
    unknown_records: int  # records kept because their code is unknown

    @property
    def trailing_bytes(self) -> int:
        return self.size - self.end_offset - RECORD_SIZE


# -- reading ----------------------------------------------------------------------------
class _Reader:
    """The declaration state machine; methods run once per structural record."""

    def __init__(self) -> None:
        self.count: int | None = None  # code 1 value, and its record's offset
        self.configs: list[StoredConfiguration] = []
        self.config_indices: set[int] = set()
        self.cfg: StoredConfiguration | None = None  # the open configuration
        self.link_count: int | None = None  # its code 3 value
        self.link_indices: set[int] = set()
        self.total_links = 0
        self.link_index: int | None = None  # the open link
        self.ends: dict[int, StoredChannel] = {}  # its finished channels by code 5/6
        self.channel: list[int | None] | None = None  # the open channel's values by code
        self.channel_code = 0
        self.count_off = self.cfg_off = self.link_count_off = self.link_off = -1
        self.channel_off = -1
        # Unknown records of each open declaration, as [code, value, after].
        self.coll_unknown: list[list[int]] = []
        self.cfg_unknown: list[list[int]] = []
        self.link_unknown: list[list[int]] = []
        self.channel_unknown: list[list[int]] = []

    def unknown(self, code: int, value: int, after: int) -> None:
        """Keep an unknown record on the innermost open declaration."""
        if self.channel is not None:
            target = self.channel_unknown
        elif self.link_index is not None:
            target = self.link_unknown
        elif self.cfg is not None:
            target = self.cfg_unknown
        else:
            target = self.coll_unknown
        target.append([code, value, after])

    def where(self) -> str:
        kind = "input" if self.channel_code == INPUT_CHANNEL else "output"
        assert self.cfg is not None
        return f"{kind} channel of link {self.link_index} in configuration {self.cfg.index}"

    def close_channel(self, last: int) -> None:
        ch = self.channel
        if ch is None:
            return
        for code in _REQUIRED:
            if ch[code] is None:
                missing = f"{CODE_NAMES[code]} (code {code})"
                raise _Err(f"{self.where()} has no {missing}", self.channel_off)
        self.ends[self.channel_code] = StoredChannel(
            index=ch[9], vid=ch[10], pid=ch[11], serial=ch[12],  # type: ignore[arg-type]
            type=ch[7] or 0, profile=ch[8] or 0, owner_type=ch[13], owner_profile=ch[14],
            unknown=_kept(self.channel_unknown, last) if self.channel_unknown else ())
        self.channel, self.channel_unknown = None, []

    def close_link(self, last: int) -> None:
        self.close_channel(last)
        if self.link_index is None:
            return
        assert self.cfg is not None
        where = f"link {self.link_index} in configuration {self.cfg.index}"
        for code, kind in ((INPUT_CHANNEL, "input"), (OUTPUT_CHANNEL, "output")):
            if code not in self.ends:
                raise _Err(f"{where} has no {kind} channel (code {code})", self.link_off)
        link = StoredLink(self.ends[INPUT_CHANNEL], self.ends[OUTPUT_CHANNEL], self.link_index,
                          _kept(self.link_unknown, LINK) if self.link_unknown else ())
        self.cfg.links.append(link)
        self.link_index, self.link_unknown = None, []

    def close_configuration(self, last: int) -> None:
        self.close_link(last)
        cfg = self.cfg
        if cfg is None:
            return
        if self.link_count is None:
            raise _Err(f"configuration {cfg.index} has no # of links (code 3)", self.cfg_off)
        if self.link_count != len(cfg.links):
            raise _Err(f"# of links of configuration {cfg.index} says {self.link_count}, "
                      f"but {len(cfg.links)} follow", self.link_count_off)
        if self.cfg_unknown:
            cfg.unknown = _kept(self.cfg_unknown, COUNT_LINKS)
        self.configs.append(cfg)
        self.cfg, self.cfg_unknown = None, []

    def structural(self, code: int, value: int, offset: int, last: int) -> None:
        """Handle codes 1–6: open and close declarations, check counts and indices.

        ``last`` is the code of the last known record before this one.
        """
        if code == CONFIGURATION:
            if self.count is None:
                raise _Err("Configuration before the # of configurations (code 1)", offset)
            self.close_configuration(last)
            if value < 1 or value in self.config_indices:
                problem = "counts from 1" if value < 1 else "is a duplicate"
                raise _Err(f"configuration index {value} {problem}", offset)
            if len(self.configs) >= MAX_CONFIGURATIONS:
                raise _Err(f"more than {MAX_CONFIGURATIONS} configurations (the limit)", offset)
            self.config_indices.add(value)
            self.cfg, self.cfg_off = StoredConfiguration(index=value, links=[]), offset
            self.link_count, self.link_indices = None, set()
        elif code == LINK:
            if self.cfg is None:
                raise _Err("Channel link outside a configuration", offset)
            where = f"configuration {self.cfg.index}"
            if self.link_count is None:
                raise _Err(f"Channel link before the # of links (code 3) of {where}", offset)
            self.close_link(last)
            if value < 1 or value in self.link_indices:
                problem = "counts from 1" if value < 1 else "is a duplicate"
                raise _Err(f"link index {value} in {where} {problem}", offset)
            self.total_links += 1
            if self.total_links > MAX_LINKS:
                raise _Err(f"more than {MAX_LINKS} links (the limit)", offset)
            self.link_indices.add(value)
            self.link_index, self.link_off, self.ends = value, offset, {}
        elif code in (INPUT_CHANNEL, OUTPUT_CHANNEL):
            kind = "input" if code == INPUT_CHANNEL else "output"
            if self.link_index is None:
                raise _Err(f"{kind} channel declaration outside a channel link", offset)
            self.close_channel(last)
            if code in self.ends:
                raise _Err(f"second {kind} channel in link {self.link_index}", offset)
            self.channel, self.channel_code, self.channel_off = [None] * 15, code, offset
        elif code == COUNT_LINKS:
            if self.cfg is None or self.link_count is not None or self.link_index is not None:
                raise _Err("# of links must directly follow its Configuration record", offset)
            if value > MAX_LINKS:
                raise _Err(f"{value} links exceed the limit {MAX_LINKS}", offset)
            self.link_count, self.link_count_off = value, offset
        else:  # COUNT_CONFIGURATIONS
            if self.count is not None:
                raise _Err("# of configurations must be the first record, and only once", offset)
            if value > MAX_CONFIGURATIONS:
                raise _Err(f"{value} configurations exceed the limit {MAX_CONFIGURATIONS}", offset)
            self.count, self.count_off = value, offset

    def end(self, offset: int, last: int) -> ConfigCollection:
        if self.count is None:
            raise _Err("End before the # of configurations (code 1)", offset)
        self.close_configuration(last)
        if self.count != len(self.configs):
            raise _Err(f"# of configurations says {self.count}, but {len(self.configs)} follow",
                      self.count_off)
        kept = _kept(self.coll_unknown, COUNT_CONFIGURATIONS) if self.coll_unknown else ()
        return ConfigCollection(configurations=self.configs, unknown=kept)


def _kept(records: list[list[int]], last: int) -> Unknown:
    """Unknown records of a closed declaration; ``after`` the declaration's last known
    record becomes ``None`` (the end), the usual place and the one edits keep."""
    return tuple(UnknownRecord(code, value, None if after == last else after)
                 for code, value, after in records)


def decode(data: bytes | bytearray | memoryview) -> Decoded:
    """Decode and report what else was found (checksum, unknown records, trailing bytes)."""
    size = len(data)
    if size > MAX_INPUT_BYTES:
        raise _Err(f"input is larger than the limit of {MAX_INPUT_BYTES} bytes", MAX_INPUT_BYTES)
    view = memoryview(data).cast("B")
    whole = size - size % RECORD_SIZE
    reader = _Reader()
    channel: list[int | None] | None = None
    checksum: int | None = None
    unknown = 0
    last = 0  # the code of the last known record (0: none yet)
    offset = -RECORD_SIZE
    for code, value in _RECORD.iter_unpack(view[:whole]):
        offset += RECORD_SIZE
        if CHANNEL_TYPE <= code <= OWNER_PROFILE:  # the hot path: value records
            if channel is None:
                raise _Err(f"{CODE_NAMES[code]} record outside a channel declaration", offset)
            if channel[code] is not None:
                raise _Err(f"second {CODE_NAMES[code]} record in the {reader.where()}", offset)
            if code == CHANNEL_INDEX and not 1 <= value <= 255:
                raise _Err(f"channel index {value} is out of range 1…255", offset)
            channel[code] = value
            last = code
        elif code <= OUTPUT_CHANNEL and code:
            reader.structural(code, value, offset, last)
            channel = reader.channel
            last = code
        elif code == END:
            return Decoded(reader.end(offset, last), checksum, offset, size, unknown)
        elif code == CHECKSUM:
            computed = crc16_ccitt_false(view[:offset])
            if value != computed:
                raise _Err(f"checksum mismatch: stored 0x{value:04X}, "
                           f"computed 0x{computed:04X}", offset)
            following = offset + RECORD_SIZE
            if following + RECORD_SIZE <= whole and view[following] != END:
                raise _Err("only End may follow the Checksum record", following)
            checksum = value
        else:
            unknown += 1
            reader.unknown(code, value, last)
    if size % RECORD_SIZE:
        raise _Err(f"truncated record: {size % RECORD_SIZE} byte(s) left and no End", whole)
    raise _Err("missing End record (code 15)", whole)


def loads(data: bytes | bytearray | memoryview) -> ConfigCollection:
    """Decode a stored-configuration byte string; ConfigFormatError says where and why."""
    return decode(data).collection


def load(fileobj: BinaryIO) -> ConfigCollection:
    """Decode from a binary file object, reading at most ``MAX_INPUT_BYTES`` + 1 bytes."""
    return loads(fileobj.read(MAX_INPUT_BYTES + 1))


def load_path(path: str | Path) -> ConfigCollection:
    """Decode a ``.pdcfg`` file; a FIFO or a device is refused (``NotARegularFile``)."""
    from pdcp_studio.storage.regular_file import open_regular

    with open_regular(path) as handle:
        return load(handle)


# -- writing ----------------------------------------------------------------------------
def _indices(given: list[int]) -> list[int]:
    """Keep indices that are a permutation of 1…n; otherwise number 1…n in list order."""
    n = len(given)
    if sorted(given) == list(range(1, n + 1)):
        return given
    return list(range(1, n + 1))


def _check_channel(ch: StoredChannel, path: str) -> None:
    """Name the first bad field of a channel the writer cannot encode."""
    for name in ("index", "vid", "pid", "serial", "type", "profile", "owner_type",
                 "owner_profile"):
        value, lo, hi = getattr(ch, name), int(name == "index"), 255 if name == "index" else 0xFFFF
        if value is None and name.startswith("owner_"):
            continue
        if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
            raise ConfigFormatError(f"{path}.{name}: {value!r} is out of range {lo}…{hi}")


def _check_unknown(records: Unknown, path: str) -> None:
    """Unknown records must keep unknown codes, or they would change the structure."""
    for i, rec in enumerate(records):
        where = f"{path}.unknown_records[{i}]"
        for name, hi in (("code", 255), ("value", 0xFFFF)):
            value = getattr(rec, name)
            if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= hi:
                raise ConfigFormatError(f"{where}.{name}: {value!r} is out of range 0…{hi}")
        if 1 <= rec.code <= CHECKSUM:
            raise ConfigFormatError(f"{where}.code: {rec.code} is a known code "
                                    f"({CODE_NAMES[rec.code]}), not an unknown record")
        after = rec.after
        if after is not None and (isinstance(after, bool) or not isinstance(after, int)
                                  or not 0 <= after <= 255):
            raise ConfigFormatError(f"{where}.after: {after!r} is out of range 0…255")


def _put_with_unknown(out: bytearray, known: list[tuple[int, int]], unknown: Unknown,
                      path: str, first: int) -> None:
    """A declaration's known records in order, each unknown one after the record it
    followed (``after``; ``None``: at the end). ``first`` is the lowest place an unknown
    record may take, so that it can never slip into the previous declaration."""
    _check_unknown(unknown, path)
    end = 1 << 16
    placed = [(code, 0, code, value) for code, value in known]
    placed += [(end if rec.after is None else max(rec.after, first), 1, rec.code, rec.value)
               for rec in unknown]
    placed.sort(key=lambda item: (item[0], item[1]))  # stable: file order among equals
    for _, _, code, value in placed:
        out += _RECORD.pack(code, value)


def _put_channel(out: bytearray, code: int, ch: StoredChannel, path: str) -> None:
    owner_type, owner_profile = ch.owner_type, ch.owner_profile
    if ch.unknown:
        _check_channel(ch, path)
        known = [(code, 0), (CHANNEL_TYPE, ch.type), (CHANNEL_PROFILE, ch.profile),
                 (CHANNEL_INDEX, ch.index), (OWNER_VID, ch.vid), (OWNER_PID, ch.pid),
                 (OWNER_SERIAL, ch.serial)]
        if owner_type is not None:
            known.append((OWNER_TYPE, owner_type))
        if owner_profile is not None:
            known.append((OWNER_PROFILE, owner_profile))
        _put_with_unknown(out, known, ch.unknown, path, code)
        return
    if not 1 <= ch.index <= 255 or owner_type is not None or owner_profile is not None:
        _check_channel(ch, path)  # slow path: full validation
    try:
        out += _CHANNEL.pack(
            code, 0, CHANNEL_TYPE, ch.type, CHANNEL_PROFILE, ch.profile, CHANNEL_INDEX,
            ch.index, OWNER_VID, ch.vid, OWNER_PID, ch.pid, OWNER_SERIAL, ch.serial,
        )
    except (struct.error, TypeError):
        _check_channel(ch, path)
        raise
    if owner_type is not None:
        out += _RECORD.pack(OWNER_TYPE, owner_type)
    if owner_profile is not None:
        out += _RECORD.pack(OWNER_PROFILE, owner_profile)


def dumps(collection: ConfigCollection) -> bytes:
    """Encode in figure 4.10 order, then the checksum, then End (see module decisions)."""
    configs = collection.configurations
    if len(configs) > MAX_CONFIGURATIONS:
        raise ConfigFormatError(f"configurations: more than {MAX_CONFIGURATIONS} (the limit)")
    total = sum(len(cfg.links) for cfg in configs)
    if total > MAX_LINKS:
        raise ConfigFormatError(f"configurations: {total} links exceed the limit of {MAX_LINKS}")
    out = bytearray()
    _put_with_unknown(out, [(COUNT_CONFIGURATIONS, len(configs))], collection.unknown,
                      "collection", 0)
    config_indices = _indices([cfg.index for cfg in configs])
    for cpos, (cfg, cidx) in enumerate(zip(configs, config_indices, strict=True)):
        if cfg.unknown:
            _put_with_unknown(out, [(CONFIGURATION, cidx), (COUNT_LINKS, len(cfg.links))],
                              cfg.unknown, f"configurations[{cpos}]", CONFIGURATION)
        else:
            out += _TWO_RECORDS.pack(CONFIGURATION, cidx, COUNT_LINKS, len(cfg.links))
        link_indices = _indices([link.index for link in cfg.links])
        for lpos, (link, lidx) in enumerate(zip(cfg.links, link_indices, strict=True)):
            path = f"configurations[{cpos}].links[{lpos}]"
            if link.unknown:
                _put_with_unknown(out, [(LINK, lidx)], link.unknown, path, LINK)
            else:
                out += _RECORD.pack(LINK, lidx)
            _put_channel(out, INPUT_CHANNEL, link.input, f"{path}.input")
            _put_channel(out, OUTPUT_CHANNEL, link.output, f"{path}.output")
    out += _RECORD.pack(CHECKSUM, crc16_ccitt_false(out))
    out += _RECORD.pack(END, 0)
    return bytes(out)


def dump(collection: ConfigCollection, fileobj: BinaryIO) -> None:
    """Encode into a binary file object."""
    fileobj.write(dumps(collection))


def save_path(collection: ConfigCollection, path: str | Path) -> None:
    """Encode into ``path`` atomically (the old file survives a failed save)."""
    from pdcp_studio.storage.atomic import atomic_write_bytes

    atomic_write_bytes(path, dumps(collection))


# -- JSON (contracts §2, ``config decode --json``) -------------------------------------
# One JSON shape for a stored channel, link and unknown records: the configuration diff's
# (model/config_diff.py), which compares exactly what ``config decode --json`` prints.
channel_to_json = channel_json
unknown_to_json = unknown_json
link_to_json = link_json
_with_unknown = with_unknown


def to_json(collection: ConfigCollection) -> dict[str, Any]:
    """The contract JSON of ``config decode --json`` (indices as stored); unknown records
    as ``unknown_records`` on the object they belong to, only where there are some."""
    return _with_unknown({"configurations": [
        _with_unknown({"index": cfg.index, "links": [link_to_json(link) for link in cfg.links]},
                      cfg.unknown)
        for cfg in collection.configurations]}, collection.unknown)


def _json_int(doc: dict[str, Any], key: str, path: str, hi: int = 0xFFFF, lo: int = 0,
              default: int | None = None, required: bool = True) -> Any:
    """An integer or ``"0x…"`` string within lo…hi; ``default`` when absent."""
    value, where = doc.get(key), f"{path}.{key}"
    if value is None:
        if default is None and required:
            raise _Err(f"{where}: missing")
        return default
    try:
        return parse_number(value, lo, hi)
    except ValueError as err:
        raise _Err(f"{where}: {err}") from None


def _json_list(doc: Any, key: str, path: str) -> list[Any]:
    if not isinstance(doc, dict):
        raise _Err(f"{path or 'document'}: expected an object")
    if not isinstance(doc.get(key), list):
        raise _Err(f"{path + '.' if path else ''}{key}: expected a list")
    found: list[Any] = doc[key]
    return found


def unknown_from_json(doc: dict[str, Any], path: str) -> Unknown:
    """The optional ``unknown_records`` list of an object; codes 1…16 are refused."""
    items = doc.get("unknown_records")
    if items is None:
        return ()
    where = f"{path + '.' if path else ''}unknown_records"
    if not isinstance(items, list):
        raise _Err(f"{where}: expected a list")
    records = []
    for i, item in enumerate(items):
        ipath = f"{where}[{i}]"
        if not isinstance(item, dict):
            raise _Err(f"{ipath}: expected an object")
        code = _json_int(item, "code", ipath, hi=255)
        if 1 <= code <= CHECKSUM:
            raise _Err(f"{ipath}.code: {code} is a known code ({CODE_NAMES[code]}), "
                       "not an unknown record")
        records.append(UnknownRecord(code, _json_int(item, "value", ipath),
                                     _json_int(item, "after", ipath, hi=255, required=False)))
    return tuple(records)


def channel_from_json(doc: Any, path: str) -> StoredChannel:
    """One channel object; type and profile default to 0, as when their records are absent."""
    if not isinstance(doc, dict):
        raise _Err(f"{path}: expected an object")
    return StoredChannel(
        index=_json_int(doc, "index", path, 255, 1), vid=_json_int(doc, "vid", path),
        pid=_json_int(doc, "pid", path), serial=_json_int(doc, "serial", path),
        type=_json_int(doc, "type", path, default=0),
        profile=_json_int(doc, "profile", path, default=0),
        owner_type=_json_int(doc, "owner_type", path, required=False),
        owner_profile=_json_int(doc, "owner_profile", path, required=False),
        unknown=unknown_from_json(doc, path))


def from_json(doc: Any) -> ConfigCollection:
    """Parse the contract JSON; ConfigFormatError (offset -1) names the JSON path.

    Indices may be omitted (they then follow list order); extra keys are ignored.
    """
    configs = []
    for cpos, cdoc in enumerate(_json_list(doc, "configurations", "")):
        cpath = f"configurations[{cpos}]"
        links = []
        for lpos, ldoc in enumerate(_json_list(cdoc, "links", cpath)):
            lpath = f"{cpath}.links[{lpos}]"
            if not isinstance(ldoc, dict):
                raise _Err(f"{lpath}: expected an object")
            links.append(StoredLink(
                input=channel_from_json(ldoc.get("input"), f"{lpath}.input"),
                output=channel_from_json(ldoc.get("output"), f"{lpath}.output"),
                index=_json_int(ldoc, "index", lpath, lo=1, default=lpos + 1),
                unknown=unknown_from_json(ldoc, lpath)))
        index = _json_int(cdoc, "index", cpath, lo=1, default=cpos + 1)
        configs.append(StoredConfiguration(index=index, links=links,
                                           unknown=unknown_from_json(cdoc, cpath)))
    return ConfigCollection(configurations=configs, unknown=unknown_from_json(doc, ""))
