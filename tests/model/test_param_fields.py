"""The one mapping between catalog parameters and model fields (model/param_fields.py)."""

from __future__ import annotations

import pytest

from pdcp_studio.errors import ParameterError
from pdcp_studio.model import param_fields as F
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, SourceInfo


def _device() -> Device:
    device = Device(2, 2, 7, descriptor="Hand", fw_version=3, hw_version=4, device_type=5,
                    device_profile=6, beacon_interval=250, ack_timeout=40, bind_timeout=300,
                    ean_low=0x1234, ean_high=0x56)
    device.add_channel(Channel(1, Direction.OUTPUT, 0x5001, 0x2220, descriptor="EMG",
                               required_inputs=(2,), node_id=9, data_enabled=True))
    device.add_channel(Channel(2, Direction.INPUT, 0x5002, 0x2230, terminal_profile=0x3000,
                               desired_inputs=(2,),
                               source=SourceInfo(2, 3, 11, 1, 0x5001, 0x2220)))
    device.add_channel(Channel(4, Direction.OUTPUT))  # index 3 unused
    return device


def test_every_writable_catalog_parameter_has_a_field_or_is_the_bus_s():
    bus_only = {(P.IN_SOURCE_NODE_IDS, "input")}
    for scope in ("device", "input", "output"):
        for spec in P.parameters_for(scope):
            fm = F.field_map(spec.id, 0 if scope == "device" else 1,
                             None if scope == "device" else Direction(scope))
            if spec.writable and (spec.id, scope) not in bus_only:
                assert fm is not None, spec.name


def test_a_device_survives_its_parameter_table():
    device = _device()
    table = F.parameter_table(device)
    assert table[P.DEVICE_CHANNEL_COUNT, 0] == b"\x04"
    assert (P.CH_TRANSFER_TYPE, 3) not in table
    values: F.Values = dict(table)
    values[P.CH_TRANSFER_TYPE, 3] = b"\0"  # the device says: index 3 unused
    back = F.device_from_values(device.key, values)
    assert back == device


def test_refused_and_malformed_values_keep_the_model_defaults():
    key = DeviceKey(1, 2, 3)
    values: F.Values = {(P.DEVICE_CHANNEL_COUNT, 0): b"\x01", (P.CH_TRANSFER_TYPE, 1): b"\x01",
                        (P.DEVICE_BEACON_INTERVAL, 0): b"\x01",  # 1 byte: not a u16
                        (P.DEVICE_DESCRIPTOR, 0): None, (P.IN_SOURCE_VID_PID, 1): None,
                        (P.CH_REQUIRED_INPUTS, 1): b"\x40\x00"}  # channel 1 = itself
    device = F.device_from_values(key, values, node_id=17)
    assert (device.beacon_interval, device.descriptor, device.node_id) == (100, "", 17)
    ch = device.channels[1]
    assert ch.source == SourceInfo() and ch.required_inputs == (1,)


def test_required_inputs_that_are_not_inputs_are_dropped():
    values: F.Values = {(P.DEVICE_CHANNEL_COUNT, 0): b"\x02", (P.CH_TRANSFER_TYPE, 1): b"\x02",
                        (P.CH_TRANSFER_TYPE, 2): b"\x01",
                        (P.CH_REQUIRED_INPUTS, 1): P.indices_to_bitmap((1, 2))}
    device = F.device_from_values(DeviceKey(1, 2, 3), values)
    assert device.channels[1].required_inputs == (2,)


def test_learn_value_writes_the_one_field_and_ignores_what_does_not_fit():
    device = _device()
    F.learn_value(device, P.IN_SOURCE_SN_INDEX, 2, b"\x05\x00\x03")
    assert (device.channels[2].source.serial, device.channels[2].source.index) == (5, 3)
    F.learn_value(device, P.OUT_NODE_ID, 1, b"\0")
    assert device.channels[1].node_id is None
    F.learn_value(device, P.DEVICE_SERIAL, 0, b"\x63\x00")  # identity: never from the bus
    F.learn_value(device, P.CH_DESCRIPTOR, 9, b"x\0")  # no such channel
    F.learn_value(device, P.DEVICE_ACK_TIMEOUT, 0, b"\x01")  # malformed
    assert (device.serial, device.ack_timeout) == (7, 40)


def test_a_staged_field_is_written_with_its_parameter():
    device = _device()
    assert F.param_of_field("profile", "input") == P.CH_TYPE_PROFILE
    assert F.param_of_field("beacon_interval", "device") == P.DEVICE_BEACON_INTERVAL
    with pytest.raises(ParameterError):
        F.param_of_field("name", "device")
    ch = device.channels[1]
    assert F.encode_field_value(ch, P.CH_TYPE_PROFILE) == P.encode_value(
        P.channel_parameter(P.CH_TYPE_PROFILE, Direction.OUTPUT), (0x5001, 0x2220))
    assert F.encode_field_value(ch, P.CH_DATA_ENABLED) == b"\x01"
    with pytest.raises(ParameterError):
        F.encode_field_value(device, P.DEVICE_CHANNEL_COUNT)
