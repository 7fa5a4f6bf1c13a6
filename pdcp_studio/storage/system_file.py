"""System files (``pdcp-system/1``, contracts §1): a whole bus as JSON.

The loader validates everything and names the JSON path of the first problem
(``devices[2].channels[0].profile``). It is bounded by what it reads (contracts §1): a system
file holds at most ``MAX_FILE_BYTES`` bytes (counted as read, so pipes and devices too),
``MAX_DEPTH`` levels of nesting, ``MAX_DEVICES`` devices (a bus has 254 node IDs and every
device holds one), ``MAX_CHANNELS`` channels and ``MAX_LINKS`` links in all. The limits keep the
largest accepted file within the app's targets (``benchmarks/system_limits.py``).
The writer writes type, profile and terminal profile as ``"0x%04X"`` strings and everything
else as integers, atomically.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from pdcp_studio.errors import ModelError, SystemFileError
from pdcp_studio.model.refs import ChannelRef, Direction
from pdcp_studio.model.system import NO_SOURCE, Channel, Device, Link, SourceInfo, System
from pdcp_studio.storage.bounded_input import InputError, loads_json, read_capped
from pdcp_studio.storage.json_number import parse_number

FORMAT = "pdcp-system/1"
#: A system file holds at most this many bytes (2 MiB).
MAX_FILE_BYTES = 2 * 1024 * 1024
#: … nested at most this deep (the format itself needs 5 levels).
MAX_DEPTH = 16
#: … at most this many devices, present or missing (a bus has 254 node IDs).
MAX_DEVICES = 254
#: … at most this many channels, all devices together.
MAX_CHANNELS = 2048
#: … at most this many links.
MAX_LINKS = 2048


# -- reading ---------------------------------------------------------------------
def _int(value: Any, path: str, lo: int, hi: int) -> int:
    """An integer or ``"0x…"`` string within lo…hi, else SystemFileError at ``path``."""
    try:
        return parse_number(value, lo, hi, expected="a number")
    except ValueError as err:
        raise SystemFileError(str(err), path) from None


def _obj(value: Any, path: str) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise SystemFileError("expected an object", path)
    return value


def _list(value: Any, path: str) -> list[Any]:
    if not isinstance(value, list):
        raise SystemFileError("expected a list", path)
    return value


def _profile(d: dict[str, Any], path: str) -> int:
    """A channel's profile: required, and never the null profile (reference §1)."""
    if "profile" not in d:
        raise SystemFileError("missing 'profile'", path)
    value = _int(d["profile"], f"{path}.profile", 0, 0xFFFF)
    if value == 0:
        raise SystemFileError("the null profile 0x0000 is not a channel profile",
                              f"{path}.profile")
    return value


def _str(d: dict[str, Any], key: str, path: str) -> str:
    """An optional string field (default empty), else SystemFileError at ``path.key``."""
    value = d.get(key, "")
    if not isinstance(value, str):
        raise SystemFileError(f"expected a string, got {value!r}", f"{path}.{key}")
    return value


def _bool(d: dict[str, Any], key: str, path: str, default: bool) -> bool:
    value = d.get(key, default)
    if not isinstance(value, bool):
        raise SystemFileError("expected true or false", f"{path}.{key}")
    return value


def _ref(doc: Any, path: str) -> ChannelRef:
    d = _obj(doc, path)
    for key in ("vid", "pid", "serial", "index"):
        if key not in d:
            raise SystemFileError(f"missing {key!r}", path)
    return ChannelRef(
        _int(d["vid"], f"{path}.vid", 0, 0xFFFF),
        _int(d["pid"], f"{path}.pid", 0, 0xFFFF),
        _int(d["serial"], f"{path}.serial", 0, 0xFFFF),
        _int(d["index"], f"{path}.index", 1, 255),
    )


def _indices(value: Any, path: str) -> tuple[int, ...]:
    items = _list(value, path)
    out = tuple(_int(v, f"{path}[{i}]", 0, 255) for i, v in enumerate(items))
    if len(set(out)) != len(out):
        raise SystemFileError("an index is listed twice", path)
    return tuple(sorted(out))


def _source(doc: Any, path: str) -> SourceInfo:
    d = _obj(doc, path)
    return SourceInfo(
        vid=_int(d.get("vid", 0xFFFF), f"{path}.vid", 0, 0xFFFF),
        pid=_int(d.get("pid", 0xFFFF), f"{path}.pid", 0, 0xFFFF),
        serial=_int(d.get("serial", 0xFFFF), f"{path}.serial", 0, 0xFFFF),
        index=_int(d.get("index", 0xFF), f"{path}.index", 0, 0xFF),
        type=_int(d.get("type", 0), f"{path}.type", 0, 0xFFFF),
        profile=_int(d.get("profile", 0), f"{path}.profile", 0, 0xFFFF),
    )


def _channel(doc: Any, path: str) -> Channel:
    d = _obj(doc, path)
    if "index" not in d:
        raise SystemFileError("missing 'index'", path)
    direction = d.get("direction")
    if direction not in ("input", "output"):
        raise SystemFileError(
            f"must be 'input' or 'output', not {direction!r}", f"{path}.direction"
        )
    descriptor = _str(d, "descriptor", path)
    ch = Channel(
        index=_int(d["index"], f"{path}.index", 1, 255),
        direction=Direction(direction),
        type=_int(d.get("type", 0x5000), f"{path}.type", 0, 0xFFFF),
        profile=_profile(d, path),
        terminal_profile=_int(d.get("terminal_profile", 0), f"{path}.terminal_profile", 0, 0xFFFF),
        required_inputs=_indices(d.get("required_inputs", []), f"{path}.required_inputs"),
        desired_inputs=_indices(d.get("desired_inputs", []), f"{path}.desired_inputs"),
        descriptor=descriptor,
        source=_source(d["source"], f"{path}.source") if "source" in d else NO_SOURCE,
        node_id=_int(d["node_id"], f"{path}.node_id", 1, 254) if "node_id" in d else None,
        data_enabled=_bool(d, "data_enabled", path, False),
    )
    return ch


_DEVICE_INTS = {
    "fw_version": 0xFFFF,
    "hw_version": 0xFFFF,
    "device_type": 0xFFFF,
    "device_profile": 0xFFFF,
    "beacon_interval": 0xFFFF,
    "ack_timeout": 0xFFFF,
    "bind_timeout": 0xFFFF,
    "ean_low": 0xFFFFFFFF,
    "ean_high": 0xFFFFFFFF,
}


def _device(doc: Any, path: str) -> Device:
    d = _obj(doc, path)
    for key in ("vid", "pid", "serial"):
        if key not in d:
            raise SystemFileError(f"missing {key!r}", path)
    present = _bool(d, "present", path, True)
    ints: dict[str, Any] = {k: _int(d[k], f"{path}.{k}", 0, hi)
                            for k, hi in _DEVICE_INTS.items() if k in d}
    device = Device(
        vid=_int(d["vid"], f"{path}.vid", 0, 0xFFFF),
        pid=_int(d["pid"], f"{path}.pid", 0, 0xFFFF),
        serial=_int(d["serial"], f"{path}.serial", 0, 0xFFFF),
        name=_str(d, "name", path),
        present=present,
        node_id=_int(d["node_id"], f"{path}.node_id", 1, 254) if "node_id" in d else None,
        descriptor=_str(d, "descriptor", path),
        **ints,
    )
    for i, ch_doc in enumerate(_list(d.get("channels", []), f"{path}.channels")):
        cpath = f"{path}.channels[{i}]"
        index = _obj(ch_doc, cpath).get("index")
        if index is not None and _int(index, f"{cpath}.index", 1, 255) in device.channels:
            raise SystemFileError(f"duplicate channel index {index}", f"{cpath}.index")
        ch = _channel(ch_doc, cpath)
        device.channels[ch.index] = ch
    for i, ch in enumerate(device.channels.values()):
        for field in ("required_inputs", "desired_inputs"):
            for j, idx in enumerate(getattr(ch, field)):
                target = device.channels.get(idx)
                if target is None or not target.is_input:
                    raise SystemFileError(
                        f"{idx} is not an input channel of this device",
                        f"{path}.channels[{i}].{field}[{j}]",
                    )
    return device


def from_json(doc: Any) -> System:
    """Build a System from a parsed ``pdcp-system/1`` document."""
    d = _obj(doc, "$")
    if d.get("format") != FORMAT:
        raise SystemFileError(f"unknown format {d.get('format')!r} (expected {FORMAT!r})", "format")
    system = System()
    devices = _list(d.get("devices", []), "devices")
    if len(devices) > MAX_DEVICES:
        raise SystemFileError(f"{len(devices)} devices; a system file holds at most "
                              f"{MAX_DEVICES}", "devices")
    channels = 0
    for i, dev_doc in enumerate(devices):
        device = _device(dev_doc, f"devices[{i}]")
        channels += len(device.channels)
        if channels > MAX_CHANNELS:
            raise SystemFileError(f"more than {MAX_CHANNELS} channels in all; a system file "
                                  f"holds at most {MAX_CHANNELS}", f"devices[{i}].channels")
        if device.key in system.devices:
            raise SystemFileError(f"duplicate device {device.key}", f"devices[{i}]")
        system.add_device(device)
    seen: set[Link] = set()
    links = _list(d.get("links", []), "links")
    if len(links) > MAX_LINKS:
        raise SystemFileError(f"{len(links)} links; a system file holds at most {MAX_LINKS}",
                              "links")
    for i, link_doc in enumerate(links):
        path = f"links[{i}]"
        ld = _obj(link_doc, path)
        if "output" not in ld or "input" not in ld:
            raise SystemFileError("a link needs 'output' and 'input'", path)
        link = Link(_ref(ld["output"], f"{path}.output"), _ref(ld["input"], f"{path}.input"))
        if link in seen:
            raise SystemFileError(f"duplicate link {link}", path)
        seen.add(link)
        ends = (("output", link.output, "an output"), ("input", link.input, "an input"))
        for end, ref, want in ends:
            ch = system.channel(ref)
            if ch is None:
                raise SystemFileError(f"no channel {ref} in this system", f"{path}.{end}")
            if ch.direction.value != end:
                raise SystemFileError(f"{ref} is not {want} channel", f"{path}.{end}")
        try:
            system.add_link(link, check=False)
        except ModelError as err:  # pragma: no cover - guarded above
            raise SystemFileError(str(err), path) from err
    return system


def parse_json(data: str | bytes) -> Any:
    """The JSON document of a system file, within the depth limit and with no key twice."""
    if len(data) > MAX_FILE_BYTES:
        raise SystemFileError(f"larger than {MAX_FILE_BYTES:,} bytes, the limit for a system file")
    try:
        return loads_json(data, max_depth=MAX_DEPTH)
    except InputError as err:
        raise SystemFileError(err.reason, err.path) from None


def loads(text: str | bytes, name: str = "<string>") -> System:
    """A System from system-file text; SystemFileError names ``name``, the JSON path, why."""
    try:
        return from_json(parse_json(text))
    except SystemFileError as err:
        where = f"{name}: {err.path}" if err.path else name
        raise SystemFileError(f"{where}: {err.reason}") from err


def read_path(path: str | Path) -> bytes:
    """A system file's bytes (``-``: standard input), at most ``MAX_FILE_BYTES``."""
    try:
        return read_capped(path, MAX_FILE_BYTES, "a system file")
    except InputError as err:
        raise SystemFileError(f"{path}: {err.reason}") from None
    except OSError as err:
        raise SystemFileError(f"{path}: cannot read: {err.strerror or err}") from err


def load_path(path: str | Path) -> System:
    """Read and validate a system file; SystemFileError names the file, the JSON path, why."""
    return loads(read_path(path), str(path))


# -- writing ---------------------------------------------------------------------
def _hex(v: int) -> str:
    return f"0x{v:04X}"


def channel_to_json(ch: Channel, *, node_ids: bool = True) -> dict[str, Any]:
    d: dict[str, Any] = {"index": ch.index, "direction": ch.direction.value,
                         "type": _hex(ch.type), "profile": _hex(ch.profile)}
    if ch.is_input:
        d["terminal_profile"] = _hex(ch.terminal_profile)
    d["required_inputs"] = list(ch.required_inputs)
    d["desired_inputs"] = list(ch.desired_inputs)
    if ch.descriptor:
        d["descriptor"] = ch.descriptor
    if ch.is_input:
        s = ch.source
        d["source"] = {"vid": s.vid, "pid": s.pid, "serial": s.serial, "index": s.index}
        if s.connected:
            d["source"].update(type=_hex(s.type), profile=_hex(s.profile))
    if node_ids and ch.node_id is not None:
        d["node_id"] = ch.node_id
    if ch.data_enabled:
        d["data_enabled"] = True
    return d


def to_json(system: System, *, node_ids: bool = True) -> dict[str, Any]:
    """The ``pdcp-system/1`` document; ``node_ids`` adds the node IDs a bus gave."""
    devices = []
    for dev in system.devices.values():
        d: dict[str, Any] = {"vid": dev.vid, "pid": dev.pid, "serial": dev.serial}
        if dev.name:
            d["name"] = dev.name
        d["present"] = dev.present
        if dev.descriptor:
            d["descriptor"] = dev.descriptor
        if node_ids and dev.node_id is not None:
            d["node_id"] = dev.node_id
        for key in _DEVICE_INTS:
            value = getattr(dev, key)
            if value != getattr(Device, key, None) and value:
                d[key] = value
        d["channels"] = [channel_to_json(c, node_ids=node_ids)
                         for c in sorted(dev.channels.values(), key=lambda c: c.index)]
        devices.append(d)
    return {"format": FORMAT, "devices": devices,
            "links": [lk.as_json() for lk in system.links]}


def dumps(system: System, *, node_ids: bool = True) -> str:
    return json.dumps(to_json(system, node_ids=node_ids), indent=2) + "\n"


def save_path(system: System, path: str | Path, *, node_ids: bool = True) -> None:
    from pdcp_studio.storage.atomic import atomic_write_text

    atomic_write_text(path, dumps(system, node_ids=node_ids))
