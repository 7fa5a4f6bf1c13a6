"""python-can's ASC reader with a fast path for the line every capture is made of.

A Vector ASC capture is almost all classic data frames (``12.345 1 1A3 Rx d 8 01 02 …``);
python-can's ``ASCReader`` runs a dozen regular expressions, splits and method calls for
each of them, which made the reader alone most of a replay's time. ``QuickASCReader``
reads such a line with one regular expression and hands every other line (the header,
trigger blocks, remote, error and CAN FD frames, decimal captures, anything unusual) to
python-can's own parsing — and yields the same ``can.Message`` python-can would, field for
field (``tests/bus/test_trace_asc_quick.py`` compares the two on every capture we have and
on generated lines).
"""

from __future__ import annotations

import re
from collections.abc import Generator
from typing import Any

import can
from can.io.asc import ASC_MESSAGE_REGEX, ASC_TRIGGER_REGEX, BASE_HEX
from can.util import dlc2len

#: A classic data frame in a hexadecimal capture, as python-can's ``split()`` reads it:
#: time, channel, identifier (``x`` for 29 bits), direction, ``d``, a one-digit DLC, the
#: data bytes (two hex digits each, each a token of its own), then anything (``Length =``…).
_DATA_FRAME = re.compile(
    r"(\d+\.\d+)\s+(\d+)\s+([0-9A-Fa-f]+)(x?)\s+(Rx|Tx)\s+d\s+([0-9A-Fa-f])(?=\s|$)"
    r"((?:\s+[0-9A-Fa-f]{2}(?=\s|$))*)(.*)", re.ASCII)
_START_OF_MEASUREMENT = re.compile(r"^\d+\.\d+\s+Start of measurement")


class QuickASCReader(can.ASCReader):
    """``can.ASCReader``, faster on classic data frames, the same messages."""

    def __iter__(self) -> Generator[can.Message, None, None]:
        self._extract_header()
        quick = self._converted_base == BASE_HEX
        match_data_frame = _DATA_FRAME.match
        message = can.Message
        for raw in self.file:
            line = raw.strip()
            found = match_data_frame(line) if quick else None
            if found is not None:
                stamp, channel, ident, extended, direction, dlc_text, data, rest = \
                    found.groups()
                dlc = dlc2len(int(dlc_text, 16))
                tokens = data.split()
                wanted = min(8, dlc)
                if len(tokens) >= wanted or not rest.strip():
                    yield message(
                        timestamp=float(stamp) + self.start_time, channel=int(channel) - 1,
                        is_rx=direction == "Rx", is_extended_id=extended == "x",
                        arbitration_id=int(ident, 16), dlc=dlc,
                        data=bytearray.fromhex("".join(tokens[:wanted])))
                    continue
            msg = self._python_can_line(line)
            if msg is not None:
                yield msg
        self.stop()

    def _python_can_line(self, line: str) -> can.Message | None:
        """One line as python-can's ``ASCReader.__iter__`` reads it (``None``: no frame)."""
        trigger = ASC_TRIGGER_REGEX.match(line)
        if trigger:
            when = trigger.group("datetime_string")
            self.start_time = 0.0 if self.relative_timestamp \
                else self._datetime_to_timestamp(when)
            return None
        if _START_OF_MEASUREMENT.match(line) or not ASC_MESSAGE_REGEX.match(line):
            return None
        fields: dict[str, Any] = {}
        try:
            stamp, channel, rest = line.split(None, 2)
            fields["timestamp"] = float(stamp) + self.start_time
            if channel == "CANFD":
                fields["is_fd"] = True
            elif channel.isdigit():
                fields["channel"] = int(channel) - 1
            else:
                return None  # "statistic", J1939TP …: not a CAN frame
        except ValueError:
            return None
        if "is_fd" in fields:
            return self._process_fd_can_frame(rest, fields)
        return self._process_classic_can_frame(rest, fields)
