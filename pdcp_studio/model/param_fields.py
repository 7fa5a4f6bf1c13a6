"""Which model field each catalog parameter fills: one table for every reader and writer. Pure.

The parameter catalog (``parameters.py``) says how a value is laid out on the wire; this table
says where that value lives in the model (``Device``, ``Channel``, an input's ``SourceInfo``).
The arbitrator's set-up and the scan build devices from the values they read with it, the
simulator builds a device's parameter table from a model device with it, and the app turns a
staged field back into the parameter it writes with it.

A pair layout fills two fields (``type`` and ``profile``); ``source.vid`` names a field of an
input's source. Parameters with no field here are the bus's, not the model's: Transfer Type
(the channel's direction), Number of Data Channels (the channels themselves) and Source's Node
Ids (routing the arbitrator keeps).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any, Literal

from pdcp_studio.errors import ParameterError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device

#: How a decoded value becomes a field: as it is, a flag, a tuple of indices, or a node ID
#: where 0 means none.
Kind = Literal["plain", "flag", "indices", "node_id"]


@dataclass(frozen=True)
class FieldMap:
    """Where one parameter's value lives in the model."""

    param: int
    scope: Literal["device", "channel", "input", "output"]
    fields: tuple[str, ...]  # one field, or two for a pair layout
    kind: Kind = "plain"
    identity: bool = False  # the device's key: read to check it, never changed from the bus

    @property
    def on_source(self) -> bool:
        """The fields are an input's ``source`` (``SourceInfo``) fields."""
        return self.fields[0].startswith("source.")

    @property
    def attrs(self) -> tuple[str, ...]:
        """The attribute names (of the source for ``source.…`` fields)."""
        return tuple(name.removeprefix("source.") for name in self.fields)

    def applies_to(self, scope: str) -> bool:
        return self.scope == scope or (self.scope == "channel" and scope != "device")


def _f(param: int, scope: Literal["device", "channel", "input", "output"], *fields: str,
       kind: Kind = "plain", identity: bool = False) -> FieldMap:
    return FieldMap(param, scope, fields, kind, identity)


#: The one mapping between parameter values and model fields.
FIELD_MAPS: tuple[FieldMap, ...] = (
    _f(P.DEVICE_VID_PID, "device", "vid", "pid", identity=True),
    _f(P.DEVICE_SERIAL, "device", "serial", identity=True),
    _f(P.DEVICE_EAN_LOW, "device", "ean_low"),
    _f(P.DEVICE_EAN_HIGH, "device", "ean_high"),
    _f(P.DEVICE_VERSION, "device", "fw_version", "hw_version"),
    _f(P.DEVICE_TYPE_PROFILE, "device", "device_type", "device_profile"),
    _f(P.DEVICE_DESCRIPTOR, "device", "descriptor"),
    _f(P.DEVICE_NODE_ID, "device", "node_id", kind="node_id"),
    _f(P.DEVICE_BEACON_INTERVAL, "device", "beacon_interval"),
    _f(P.DEVICE_ACK_TIMEOUT, "device", "ack_timeout"),
    _f(P.DEVICE_BIND_TIMEOUT, "device", "bind_timeout"),
    _f(P.CH_TYPE_PROFILE, "channel", "type", "profile"),
    _f(P.CH_DESCRIPTOR, "channel", "descriptor"),
    _f(P.CH_DATA_ENABLED, "channel", "data_enabled", kind="flag"),
    _f(P.CH_REQUIRED_INPUTS, "channel", "required_inputs", kind="indices"),
    _f(P.CH_DESIRED_INPUTS, "channel", "desired_inputs", kind="indices"),
    _f(P.IN_SOURCE_VID_PID, "input", "source.vid", "source.pid"),
    _f(P.IN_SOURCE_SN_INDEX, "input", "source.serial", "source.index"),
    _f(P.IN_SOURCE_TYPE_PROFILE, "input", "source.type", "source.profile"),
    _f(P.IN_TERMINAL_PROFILE, "input", "terminal_profile"),
    _f(P.OUT_NODE_ID, "output", "node_id", kind="node_id"),
)

_BY_SCOPE: dict[str, dict[int, FieldMap]] = {
    scope: {m.param: m for m in FIELD_MAPS if m.applies_to(scope)}
    for scope in ("device", "input", "output")
}
#: (catalog spec, field map, source?, attributes) by scope and parameter: what learning a
#: value needs, looked up once (a scan of the full rig learns 3,500 values).
_LEARN: dict[str, dict[int, tuple[P.ParameterSpec, FieldMap, bool, tuple[str, ...]]]] = {
    scope: {m.param: (spec, m, m.on_source, m.attrs) for m in _BY_SCOPE[scope].values()
            if not m.identity
            for spec in [P.find_parameter(m.param, 0 if scope == "device" else 1,
                                          None if scope == "device" else Direction(scope))]
            if spec is not None}
    for scope in ("device", "input", "output")
}


def _scope(channel: int, direction: Direction | None) -> str:
    if channel == 0:
        return "device"
    if direction is None:
        raise ParameterError(f"channel {channel}: the direction is needed to find its fields")
    return direction.value


def field_map(param: int, channel: int, direction: Direction | None = None) -> FieldMap | None:
    """The fields parameter ``param`` of channel ``channel`` fills (None: none of the model's)."""
    return _BY_SCOPE[_scope(channel, direction)].get(param)


def param_of_field(name: str, scope: Literal["device", "input", "output"]) -> int:
    """The parameter a model field is written with (``profile`` → Channel Type and Profile)."""
    for m in _BY_SCOPE[scope].values():
        if name in m.fields:
            return m.param
    raise ParameterError(f"{scope} field {name!r} is not written by any parameter")


def model_value(obj: Device | Channel, fm: FieldMap) -> Any:
    """The parameter's value (as ``parameters.encode_value`` takes it) from the model."""
    if fm.on_source:
        assert isinstance(obj, Channel)
        values = [getattr(obj.source, name) for name in fm.attrs]
    else:
        values = [getattr(obj, name) for name in fm.attrs]
    if fm.kind == "flag":
        return int(bool(values[0]))
    if fm.kind == "node_id":
        return values[0] or 0
    if fm.kind == "indices":
        return tuple(values[0])
    return tuple(values) if len(values) == 2 else values[0]


def set_model_value(obj: Device | Channel, fm: FieldMap, value: Any) -> None:
    """Store a decoded parameter value in the model's fields (identity fields excepted)."""
    if not fm.identity:
        _store(obj, fm, fm.on_source, fm.attrs, value)


def _store(obj: Device | Channel, fm: FieldMap, on_source: bool, attrs: tuple[str, ...],
           value: Any) -> None:
    kind = fm.kind
    if kind == "flag":
        value = bool(value)
    elif kind == "node_id":
        value = value or None
    elif kind == "indices":
        value = tuple(value)
    if on_source:
        assert isinstance(obj, Channel)
        obj.source = replace(obj.source, **dict(zip(attrs, value, strict=True)))
    elif len(attrs) == 2:
        setattr(obj, attrs[0], value[0])
        setattr(obj, attrs[1], value[1])
    else:
        setattr(obj, attrs[0], value)


def encode_field_value(obj: Device | Channel, param: int, direction: Direction | None = None
                       ) -> bytes:
    """The bytes of parameter ``param`` as the model ``obj`` (a device or a channel) has it."""
    channel = 0 if isinstance(obj, Device) else obj.index
    if direction is None and isinstance(obj, Channel):
        direction = obj.direction
    fm = field_map(param, channel, direction)
    if fm is None:
        raise ParameterError(f"parameter {param} has no model field")
    spec = P.find_parameter(param, channel, direction)
    assert spec is not None
    return P.encode_value(spec, model_value(obj, fm))


def learn_value(device: Device, param: int, channel: int, value: bytes) -> None:
    """Store a parameter value read from (or written to) a device in its model ``Device``.

    Unknown parameters, channels the device does not have and values that do not fit their
    layout are ignored (a monitor shows them; the model keeps what it understands).
    """
    if channel == 0:
        target: Device | Channel = device
        scope = "device"
    else:
        ch = device.channels.get(channel)
        if ch is None:
            return
        target, scope = ch, ch.direction.value
    entry = _LEARN[scope].get(param)
    if entry is None:
        return
    spec, fm, on_source, attrs = entry
    try:
        decoded = P.decode_value(spec, value)
    except ParameterError:
        return
    _store(target, fm, on_source, attrs, decoded)


def only_inputs(device: Device) -> None:
    """Drop required/desired indices that are not input channels of the device."""
    inputs = {c.index for c in device.inputs()}
    for ch in device.channels.values():
        ch.required_inputs = tuple(i for i in ch.required_inputs if i in inputs)
        ch.desired_inputs = tuple(i for i in ch.desired_inputs if i in inputs)


#: Raw values read from one device: (parameter, channel) → bytes (None: refused).
Values = dict[tuple[int, int], bytes | None]


def decoded(values: Values, param: int, channel: int = 0,
            direction: Direction | None = None) -> Any:
    """A value read from a device, decoded (None: not read, refused or malformed)."""
    data = values.get((param, channel))
    spec = P.find_parameter(param, channel, direction)
    if data is None or spec is None:
        return None
    try:
        return P.decode_value(spec, data)
    except ParameterError:
        return None


def channel_direction(values: Values, index: int) -> Direction | None:
    """Channel ``index``'s direction from its Transfer Type (None: unused or not a direction)."""
    transfer = decoded(values, P.CH_TRANSFER_TYPE, index, Direction.INPUT)
    try:
        return Direction.from_transfer_type(transfer) if transfer in (1, 2) else None
    except ValueError:
        return None


def device_from_values(key: DeviceKey, values: Values, node_id: int | None = None) -> Device:
    """A model Device from the raw parameter bytes read from it (channel 0 and 1…N).

    What is missing, refused or malformed keeps the model's default; a Device Node Id of 0
    (or none read) gives ``node_id``.
    """
    device = Device(key.vid, key.pid, key.serial)
    for (param, channel), data in values.items():
        if channel == 0 and data is not None:
            learn_value(device, param, 0, data)
    device.node_id = device.node_id or node_id
    count = decoded(values, P.DEVICE_CHANNEL_COUNT) or 0
    for index in range(1, count + 1):
        direction = channel_direction(values, index)
        if direction is None:
            continue  # an index the device does not use
        device.add_channel(Channel(index, direction))
    for (param, channel), data in values.items():
        if channel and channel in device.channels and data is not None:
            learn_value(device, param, channel, data)
    only_inputs(device)
    return device


def parameter_table(device: Device) -> dict[tuple[int, int], bytes]:
    """(parameter, channel) → bytes for every catalog parameter the model device has.

    The parameters with no model field get what the model implies: Number of Data Channels
    the highest channel index, Transfer Type the direction, Source's Node Ids none.
    """
    table: dict[tuple[int, int], bytes] = {}
    for spec in P.parameters_for("device"):
        if spec.id == P.DEVICE_CHANNEL_COUNT:
            table[spec.id, 0] = P.encode_value(spec, max(device.channels, default=0))
        else:
            table[spec.id, 0] = encode_field_value(device, spec.id)
    for ch in device.channels.values():
        for spec in P.parameters_for(ch.direction):
            if spec.id == P.CH_TRANSFER_TYPE:
                value: Any = ch.direction.transfer_type
            elif ch.is_input and spec.id == P.IN_SOURCE_NODE_IDS:
                value = (0, 0)
            else:
                table[spec.id, ch.index] = encode_field_value(ch, spec.id)
                continue
            table[spec.id, ch.index] = P.encode_value(spec, value)
    return table


__all__ = ["FIELD_MAPS", "FieldMap", "Values", "channel_direction", "decoded",
           "device_from_values", "encode_field_value", "field_map", "learn_value",
           "model_value", "only_inputs", "param_of_field", "parameter_table",
           "set_model_value"]
