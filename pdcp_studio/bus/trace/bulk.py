"""Bulk transfers followed on the bus: announced by a Configure (Get Bulk response or Set
Bulk), carried by Bulk Data packets, each packet shown with its place in the transfer and the
value named once it is complete."""

from __future__ import annotations

from collections.abc import Callable, Mapping

from pdcp_studio.bus.trace.frames import CACHE_SIZE
from pdcp_studio.errors import FrameError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import Direction
from pdcp_studio.protocol import messages as M
from pdcp_studio.protocol.bulk import BulkReassembler, packet_count
from pdcp_studio.protocol.codes import FunctionCode
from pdcp_studio.protocol.identifier import Mode

_BULK_DATA_RESPONSE = int(FunctionCode.BULK_DATA) | 0x80


class BulkTransfers:
    """The transfers in progress, by (node, sender's mode), and the values completed.

    ``expect(node, response code)`` tells the decoder a response now fits (the receiver
    answers the last packet); ``in_context()`` counts a packet of an announced transfer."""

    def __init__(self, expect: Callable[[int, int], None], in_context: Callable[[], None],
                 directions: Mapping[tuple[int, int], Direction]) -> None:
        self._expect, self._in_context, self._directions = expect, in_context, directions
        #: (param, channel, reassembler) by (node, mode)
        self._open: dict[tuple[int, Mode], tuple[int, int, BulkReassembler]] = {}
        self.values: dict[tuple[int, int, int], bytes] = {}  # (node, chan, param) → value

    def announced(self, node: int, mode: Mode) -> bool:
        return (node, mode) in self._open

    def start(self, node: int, mode: Mode, param: int, chan: int, size: int) -> None:
        try:
            self._open[node, mode] = (param, chan, BulkReassembler(size))
        except FrameError:
            pass  # an impossible size: its packets will show as unannounced

    def refused(self, node: int) -> None:
        """The device refused the arbitrator's Set Bulk: no packets follow."""
        self._open.pop((node, Mode.ARBITRATOR), None)

    def packet(self, msg: M.BulkData, parts: list[str]) -> str | None:
        """Describe a packet into ``parts``; the fault that aborted its transfer, if any."""
        transfer = self._open.get((msg.node_id, msg.mode))
        hex_data = msg.data.hex(" ").upper()
        if transfer is None:
            parts.append(f"packet {msg.packet_id}  {hex_data}  (no transfer announced)")
            return None
        param, chan, r = transfer
        self._in_context()
        parts.append(f"packet {msg.packet_id}/{packet_count(r.expected_size)}  {hex_data}")
        try:
            complete = r.add(msg.packet_id, msg.data)
        except FrameError as err:
            del self._open[msg.node_id, msg.mode]
            self._expect(msg.node_id, _BULK_DATA_RESPONSE)  # the receiver answers, failing
            parts.append(f"bulk transfer aborted: {err}")
            return str(err)
        if complete:
            del self._open[msg.node_id, msg.mode]
            self._expect(msg.node_id, _BULK_DATA_RESPONSE)
            value = r.result()
            if len(self.values) >= CACHE_SIZE:
                self.values.clear()
            self.values[msg.node_id, chan, param] = value
            direction = self._directions.get((msg.node_id, chan))
            spec = P.find_parameter(param, chan, direction)
            name = P.parameter_name(param, chan, direction)
            parts.append(f"complete: {name} chan {chan} = {P.render_value(spec, value)}")
        return None
