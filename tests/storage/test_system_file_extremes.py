"""System files at the extremes (issue 15): whatever the bytes, the loader returns a System
or refuses with SystemFileError naming the file — never another exception, never a hang."""

from __future__ import annotations

import json

from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.errors import SystemFileError
from pdcp_studio.storage import system_file

VALID = {
    "format": "pdcp-system/1",
    "devices": [
        {"vid": 2, "pid": 2, "serial": 4, "channels": [
            {"index": 1, "direction": "output", "type": "0x5000", "profile": "0x2110"}]},
        {"vid": 2, "pid": 2, "serial": 5, "channels": [
            {"index": 2, "direction": "input", "type": "0x5200", "profile": "0x2110",
             "source": {"vid": 65535, "pid": 65535, "serial": 65535, "index": 255}}]},
    ],
    "links": [{"output": {"vid": 2, "pid": 2, "serial": 4, "index": 1},
               "input": {"vid": 2, "pid": 2, "serial": 5, "index": 2}}],
}
TEXT = json.dumps(VALID)

EXTREME_NUMBERS = ["0", "-1", "65535", "65536", "255", "256", "4294967296", "1e999", "-0",
                   "1.0", "9" * 60, "9" * 5000, '"0xFFFF"', '"0x10000"', '"0x"', '"0x0000"', "null",
                   "true", '"2200"', "[]", "{}", "NaN", "Infinity"]


def _loads(text: str | bytes) -> None:
    try:
        system_file.loads(text, "s.json")
    except SystemFileError as err:
        assert str(err).startswith("s.json")


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.data())
def test_every_number_replaced_by_an_extreme_value(data):
    pieces = TEXT.split(": ")
    i = data.draw(st.integers(1, len(pieces) - 1))
    value = data.draw(st.sampled_from(EXTREME_NUMBERS))
    rest = pieces[i].split(",", 1)
    rest[0] = value + ("}" * rest[0].count("}")) + ("]" * rest[0].count("]"))
    pieces[i] = ",".join(rest)
    _loads(": ".join(pieces))


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.binary(max_size=400), st.integers(0, len(TEXT)))
def test_random_bytes_spliced_into_a_valid_file(junk, at):
    _loads(TEXT.encode()[:at] + junk + TEXT.encode()[at:])


@settings(max_examples=100, deadline=None, derandomize=True)
@given(st.integers(1, 3000), st.sampled_from(["[", "{\"a\":", "[{\"b\":["]))
def test_nesting_at_any_depth(depth, opener):
    closer = {"[": "]", "{\"a\":": "}", "[{\"b\":[": "]}]"}[opener]
    _loads('{"format": "pdcp-system/1", "devices": ' + opener * depth + "0"
           + closer * depth + "}")


def test_the_most_a_system_file_may_hold_at_the_value_extremes():
    devices = [{"vid": 0xFFFF, "pid": 0xFFFF, "serial": serial, "name": "n" * 200,
                "channels": [{"index": 255 - c, "direction": "output", "type": "0xFFFF",
                              "profile": "0xFFFF"} for c in range(8)]}
               for serial in range(system_file.MAX_DEVICES)]
    system = system_file.loads(json.dumps({"format": "pdcp-system/1", "devices": devices}))
    assert len(system.devices) == 254
    assert sum(len(d.channels) for d in system.devices.values()) == 254 * 8
