"""Parameters by the names a person types and reads: ``type``, ``profile``, ``descriptor``,
``data-transfer``, ``beacon-interval`` … Pure.

The wire has parameter numbers and byte layouts (``parameters.py``); the model has fields
(``param_fields.py``). This table is the third face: one name per value a prosthetist or an
engineer may read or set (contracts §2 ``param get`` / ``param set``), its text form as in
system files (``0x9700``, ``on``, ``500``), and the write that sets it — a pair parameter
(Channel Type and Profile) is written whole, its other half kept as it is. The change's
effect names parameter changes with the same names.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

from pdcp_studio.errors import ParameterError
from pdcp_studio.model import param_fields as F
from pdcp_studio.model import parameters as P
from pdcp_studio.model.system import Channel, Device

Kind = Literal["hex16", "text", "flag", "ms", "indices", "number"]
Scope = Literal["device", "channel", "input", "output"]


@dataclass(frozen=True)
class NamedParameter:
    """One value by name: which parameter holds it, and which half of a pair."""

    name: str
    param: int
    scope: Scope
    kind: Kind
    half: int | None = None  # 0 or 1 of a pair16 parameter
    writable: bool = True

    def applies_to(self, obj: Device | Channel) -> bool:
        if isinstance(obj, Device):
            return self.scope == "device"
        return self.scope == "channel" or self.scope == obj.direction.value


NAMED: tuple[NamedParameter, ...] = (
    NamedParameter("descriptor", P.DEVICE_DESCRIPTOR, "device", "text"),
    NamedParameter("beacon-interval", P.DEVICE_BEACON_INTERVAL, "device", "ms"),
    NamedParameter("ack-timeout", P.DEVICE_ACK_TIMEOUT, "device", "ms"),
    NamedParameter("bind-timeout", P.DEVICE_BIND_TIMEOUT, "device", "ms"),
    NamedParameter("node-id", P.DEVICE_NODE_ID, "device", "number", writable=False),
    NamedParameter("type", P.CH_TYPE_PROFILE, "channel", "hex16", half=0),
    NamedParameter("profile", P.CH_TYPE_PROFILE, "channel", "hex16", half=1),
    NamedParameter("descriptor", P.CH_DESCRIPTOR, "channel", "text"),
    NamedParameter("data-transfer", P.CH_DATA_ENABLED, "channel", "flag"),
    NamedParameter("required-inputs", P.CH_REQUIRED_INPUTS, "channel", "indices"),
    NamedParameter("desired-inputs", P.CH_DESIRED_INPUTS, "channel", "indices"),
    NamedParameter("terminal-profile", P.IN_TERMINAL_PROFILE, "input", "hex16"),
    NamedParameter("node-id", P.OUT_NODE_ID, "output", "number", writable=False),
)


def named_for(obj: Device | Channel) -> list[NamedParameter]:
    """The named values a device (or a channel, by its direction) has."""
    return [n for n in NAMED if n.applies_to(obj)]


def lookup(obj: Device | Channel, name: str) -> NamedParameter:
    """The named value ``name`` of ``obj``; ParameterError naming the ones it has."""
    for n in named_for(obj):
        if n.name == name:
            return n
    what = "a part" if isinstance(obj, Device) else f"an {obj.direction.value} channel"
    raise ParameterError(f"{name!r} is not a parameter of {what} (one of: "
                         + ", ".join(n.name for n in named_for(obj)) + ")")


def _spec(obj: Device | Channel, n: NamedParameter) -> P.ParameterSpec:
    channel = 0 if isinstance(obj, Device) else obj.index
    direction = None if isinstance(obj, Device) else obj.direction
    spec = P.find_parameter(n.param, channel, direction)
    assert spec is not None  # the table names catalogued parameters only
    return spec


def _decode(obj: Device | Channel, n: NamedParameter, data: bytes) -> Any:
    value = P.decode_value(_spec(obj, n), data)
    return value[n.half] if n.half is not None else value


def text_of(n: NamedParameter, value: Any) -> str:
    """A decoded value as text, as a system file writes it."""
    if n.kind == "hex16":
        return f"0x{int(value):04X}"
    if n.kind == "flag":
        return "on" if value else "off"
    if n.kind == "indices":
        return ",".join(str(i) for i in value)
    return str(value)


def _parse(n: NamedParameter, text: str) -> Any:
    text = text.strip()
    try:
        if n.kind == "text":
            return text
        if n.kind == "flag":
            low = text.lower()
            if low in ("on", "1", "true", "yes"):
                return 1
            if low in ("off", "0", "false", "no"):
                return 0
            raise ValueError(text)
        if n.kind == "indices":
            return tuple(int(part, 0) for part in text.replace(" ", "").split(",") if part)
        return int(text, 0)
    except ValueError:
        want = {"flag": "on or off", "indices": "channel numbers such as 1,2",
                "hex16": "a number such as 0x9700"}.get(n.kind, "a number")
        raise ParameterError(f"{n.name}={text!r}: expected {want}") from None


def value_text(obj: Device | Channel, n: NamedParameter, data: bytes) -> str:
    """The text of ``n`` in the parameter bytes ``data``."""
    return text_of(n, _decode(obj, n, data))


def current_bytes(obj: Device | Channel, param: int) -> bytes:
    """The bytes of ``param`` as the model holds it now."""
    return F.encode_field_value(obj, param)


def values(obj: Device | Channel) -> dict[str, str]:
    """Every named value of ``obj`` as text (``param get``)."""
    out: dict[str, str] = {}
    for n in named_for(obj):
        try:
            out[n.name] = value_text(obj, n, current_bytes(obj, n.param))
        except (ParameterError, AssertionError):
            continue
    return out


def writes_for(obj: Device | Channel, assignments: Mapping[str, str]) -> list[tuple[int, bytes]]:
    """The parameter writes that set ``assignments`` (name → text) on ``obj``, one per
    parameter, in table order; a pair's other half keeps its value. ParameterError for a
    name ``obj`` does not have, a read-only one, or a value that does not fit."""
    wanted: dict[int, dict[int | None, Any]] = {}
    for name, text in assignments.items():
        n = lookup(obj, name)
        if not n.writable:
            raise ParameterError(f"{name} is read-only (the arbitrator sets it)")
        wanted.setdefault(n.param, {})[n.half] = _parse(n, text)
    writes: list[tuple[int, bytes]] = []
    for param, halves in wanted.items():
        n = next(m for m in named_for(obj) if m.param == param)
        spec = _spec(obj, n)
        if None in halves:
            value = halves[None]
        else:
            now = P.decode_value(spec, current_bytes(obj, param))
            value = tuple(halves.get(i, now[i]) for i in (0, 1))
        writes.append((param, P.encode_value(spec, value)))
    return writes


def changes_of(obj: Device | Channel, param: int, before: bytes, after: bytes
               ) -> list[tuple[NamedParameter, str, str]]:
    """Which named values a write of ``param`` (``before`` → ``after``) changes, with their
    texts. A parameter with no name (routing, source fields) gives none."""
    out: list[tuple[NamedParameter, str, str]] = []
    for n in named_for(obj):
        if n.param != param:
            continue
        try:
            old, new = value_text(obj, n, before), value_text(obj, n, after)
        except ParameterError:
            continue
        if old != new:
            out.append((n, old, new))
    return out


def snapshot(devices: Iterable[Device]) -> dict[str, dict[str, str]]:
    """The writable named values of ``devices`` and their channels, by ``2641/769/301`` and
    ``2641/769/301#1``: what a fitting-history entry keeps so a restore can put them back."""
    out: dict[str, dict[str, str]] = {}
    for device in devices:
        objs: list[tuple[str, Device | Channel]] = [(str(device.key), device)]
        objs += [(f"{device.key}#{ch.index}", ch)
                 for ch in sorted(device.channels.values(), key=lambda c: c.index)]
        for where, obj in objs:
            writable = {n.name for n in named_for(obj) if n.writable}
            vals = {k: v for k, v in values(obj).items() if k in writable}
            if vals:
                out[where] = vals
    return out
