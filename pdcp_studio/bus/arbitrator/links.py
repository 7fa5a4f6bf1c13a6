"""The link writer: the parameters that make, re-make and remove a link on the wire.

What to write for a link is decided by pure functions (:func:`link_writes`,
:func:`unlink_writes`: node IDs and the model's channels in, the writes out, in order); the
:class:`LinkWriter` carries them out through the arbitrator's request engine, updates the
model's channels after each, and keeps links in step on the bus: after an Update Data Channel
request, when a source leaves (its inputs stop listening) and after an adapter outage (the
links are read back and re-made where they differ). Wire work is serialized by the wire
lock (``bus/arbitrator/state.py``).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.common import _NOT_CONNECTED, _OFF, _ON, _input_value, _Node
from pdcp_studio.bus.arbitrator.state import Emit, ReportError, SendFrame, SubmitJob, SystemState
from pdcp_studio.errors import ModelError, NodeIdExhaustedError, PdcpError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import NO_SOURCE, Channel, Link, SourceInfo
from pdcp_studio.protocol import ResponseCode, UpdateDataChannel, UpdateDataChannelResponse

if TYPE_CHECKING:
    from pdcp_studio.bus.arbitrator.nodes import NodeTable
    from pdcp_studio.bus.arbitrator.reading.requests import RequestEngine

log = logging.getLogger("pdcp_studio.bus.arbitrator.core")  # one logger for the arbitrator

#: The model change a write stands for once the device has taken it.
Effect = Literal["", "source", "input_on", "output_on", "input_cleared", "output_off"]


@dataclass(frozen=True)
class Write:
    """One Set Parameter on the wire, and what the model then says."""

    node_id: int
    param: int
    channel: int
    value: bytes
    then: Effect = ""


def wanted_source(link: Link, out_ch: Channel) -> SourceInfo:
    """What the input of ``link`` stores about its source (the redundant source fields)."""
    out = link.output
    return SourceInfo(out.vid, out.pid, out.serial, out.index, out_ch.type, out_ch.profile)


def link_writes(link: Link, in_node: int, out_node: int, out_id: int, have: SourceInfo,
                want: SourceInfo) -> list[Write]:
    """Make ``link`` (setup step 6): the input's Source's Node Ids, the source fields that
    differ from ``have``, its Data Transfer Enabled; then the output's."""
    i = link.input.index
    writes = [Write(in_node, P.IN_SOURCE_NODE_IDS, i, bytes([out_node, out_id]))]
    for param, mine, theirs in (
            (P.IN_SOURCE_VID_PID, (want.vid, want.pid), (have.vid, have.pid)),
            (P.IN_SOURCE_SN_INDEX, (want.serial, want.index), (have.serial, have.index)),
            (P.IN_SOURCE_TYPE_PROFILE, (want.type, want.profile), (have.type, have.profile))):
        if mine != theirs:
            writes.append(Write(in_node, param, i, _input_value(param, mine)))
    last = writes[-1]
    writes[-1] = Write(last.node_id, last.param, last.channel, last.value, "source")
    writes.append(Write(in_node, P.CH_DATA_ENABLED, i, _ON, "input_on"))
    writes.append(Write(out_node, P.CH_DATA_ENABLED, link.output.index, _ON, "output_on"))
    return writes


def unlink_writes(link: Link, in_node: int | None, out_node: int | None) -> list[Write]:
    """Undo ``link``: clear the input (``in_node`` None: it keeps another source, or is not
    on the bus) and stop the output (``out_node`` None: it still feeds a present input)."""
    writes: list[Write] = []
    if in_node is not None:
        i = link.input.index
        writes += [Write(in_node, P.CH_DATA_ENABLED, i, _OFF),
                   Write(in_node, P.IN_SOURCE_NODE_IDS, i, b"\0\0")]
        writes += [Write(in_node, param, i, value) for param, value in _NOT_CONNECTED.items()]
        last = writes[-1]
        writes[-1] = Write(last.node_id, last.param, last.channel, last.value, "input_cleared")
    if out_node is not None:
        writes.append(Write(out_node, P.CH_DATA_ENABLED, link.output.index, _OFF, "output_off"))
    return writes


def needs_remaking(out_node: int, out_id: int, sources: bytes, enabled: bytes) -> bool:
    """After an outage: an input read back (its Source's Node Ids and Data Transfer Enabled)
    does not listen to the output (``out_node``, ``out_id``) the model links it to."""
    return sources != bytes([out_node, out_id]) or enabled != _ON


class LinkWriter:
    """Links on the bus (no state of its own: the links are the system's, the node IDs the
    node table's). It writes through the request engine, answers Update Data Channel through
    ``send``, and runs its jobs (silencing, re-making, reading back) through ``submit``."""

    def __init__(self, state: SystemState, nodes: NodeTable, requests: RequestEngine, *,
                 send: SendFrame, submit: SubmitJob, error: ReportError, emit: Emit,
                 name: str) -> None:
        self._state = state
        self._nodes = nodes
        self._requests = requests
        self._send = send
        self._submit = submit
        self._error = error
        self._emit = emit
        self._name = name

    # -- carrying writes out ----------------------------------------------------------------
    def _write(self, writes: list[Write], in_ch: Channel | None, out_ch: Channel | None,
               source: SourceInfo = NO_SOURCE) -> None:
        for w in writes:
            self._requests.set(w.node_id, w.param, w.channel, w.value)
            if not w.then:
                continue
            with self._state.lock:
                if w.then == "source" and in_ch is not None:
                    in_ch.source = source
                elif w.then == "input_on" and in_ch is not None:
                    in_ch.data_enabled = True
                elif w.then == "output_on" and out_ch is not None:
                    out_ch.data_enabled = True
                elif w.then == "input_cleared" and in_ch is not None:
                    in_ch.source, in_ch.data_enabled = NO_SOURCE, False
                elif w.then == "output_off" and out_ch is not None:
                    out_ch.data_enabled = False

    def wire_add(self, link: Link) -> None:
        """Make ``link`` on the wire and in the model's channels (both ends on the bus)."""
        with self._state.lock:
            system, nodes = self._state.system, self._nodes
            out_node = nodes.node_of.get(link.output.device)
            in_node = nodes.node_of.get(link.input.device)
            out_id = nodes.output_id(link.output)
            out_ch = system.channel(link.output)
            in_ch = system.channel(link.input)
            if out_node is None or in_node is None or out_ch is None or in_ch is None:
                raise ModelError(f"link {link}: both devices must be on the bus")
            if out_id is None:
                raise NodeIdExhaustedError(f"link {link}: output {link.output} has no node ID")
            want = wanted_source(link, out_ch)
            writes = link_writes(link, in_node, out_node, out_id, in_ch.source, want)
        self._write(writes, in_ch, out_ch, want)

    def wire_remove(self, link: Link) -> None:
        """After the model dropped ``link``: clear the input unless it has another source,
        and stop the output unless it still feeds a present input."""
        with self._state.lock:
            system = self._state.system
            in_node = self._nodes.node_of.get(link.input.device)
            out_node = self._nodes.node_of.get(link.output.device)
            in_ch = system.channel(link.input)
            out_ch = system.channel(link.output)
            clear_input = in_ch is not None and system.source_of(link.input) is None
            stop_output = out_ch is not None and not any(
                system.is_present(i) for i in system.inputs_fed_by(link.output))
        writes = unlink_writes(link, in_node if clear_input else None,
                               out_node if stop_output else None)
        self._write(writes, in_ch, out_ch)

    # -- links in the model and on the wire ---------------------------------------------
    def add_link(self, link: Link) -> None:
        """See :meth:`Arbitrator.add_link`."""
        with self._state.wire_lock:
            with self._state.lock:
                system = self._state.system
                system.check_link(link)
                if system.has_link(link):
                    return
                for end in (link.output, link.input):
                    if not system.is_present(end):
                        raise ModelError(f"link {link}: {end} is not on the bus")
                dead = [Link(s, link.input) for s in system.sources_of(link.input)
                        if not system.is_present(s)]
                live = [s for s in system.sources_of(link.input) if system.is_present(s)]
                if live:
                    raise ModelError(f"link {link}: input {link.input} already has source "
                                     f"{live[0]}")
            for old in dead:
                self.remove(old)
            self.add(link)

    def remove_link(self, link: Link) -> None:
        """See :meth:`Arbitrator.remove_link`."""
        with self._state.wire_lock:
            with self._state.lock:
                if not self._state.system.has_link(link):
                    raise ModelError(f"link {link} is not in the system")
            self.remove(link)

    def add(self, link: Link) -> None:
        """Make ``link`` (on the wire when both ends are present) and say so."""
        with self._state.lock:
            present = (self._state.system.is_present(link.output)
                       and self._state.system.is_present(link.input))
        if present:
            self.wire_add(link)
        with self._state.lock:
            if not self._state.system.has_link(link):
                self._state.system.add_link(link, check=False)
        self._emit(ev.LinkMade(link))

    def remove(self, link: Link) -> None:
        """Drop ``link`` from the model and the wire and say so."""
        with self._state.lock:
            if self._state.system.has_link(link):
                self._state.system.remove_link(link)
        self.wire_remove(link)
        self._emit(ev.LinkRemoved(link))

    # -- keeping the bus in step ----------------------------------------------------------
    def links_from(self, output: ChannelRef) -> list[Link]:
        """Under the lock: the links ``output`` feeds."""
        return [Link(output, i) for i in self._state.system.inputs_fed_by(output)]

    def silence_inputs(self, links: list[Link]) -> None:
        """Inputs fed by a departed output stop listening (its node ID may be reused): a job."""
        self._submit(lambda: self._silence_inputs(links))

    def _silence_inputs(self, links: list[Link]) -> None:
        state = self._state
        with state.wire_lock:
            for link in links:
                with state.lock:
                    node_id = self._nodes.node_of.get(link.input.device)
                    others = [s for s in state.system.sources_of(link.input)
                              if s != link.output and state.system.is_present(s)]
                if node_id is None or others:
                    continue
                try:
                    self._requests.set(node_id, P.CH_DATA_ENABLED, link.input.index, _OFF)
                    self._requests.set(node_id, P.IN_SOURCE_NODE_IDS, link.input.index,
                                       b"\0\0")
                except PdcpError as err:
                    self._error(f"input {link.input} could not be told its source left: "
                                f"{err}", "transport")
                    continue
                with state.lock:
                    ch = state.system.channel(link.input)
                    if ch is not None:
                        ch.data_enabled = False

    def on_update(self, node: _Node, msg: UpdateDataChannel) -> None:
        """Update Data Channel: answer, and re-make the links into that input (a job)."""
        self._send(UpdateDataChannelResponse(node.node_id, ResponseCode.SUCCESS, msg.channel))
        with self._state.lock:
            if not node.set_up:
                return  # set-up (step 5) handles it
            ref = ChannelRef(*node.key, msg.channel)
            links = [Link(s, ref) for s in self._state.system.sources_of(ref)]
        self._submit(lambda: self._sync_links(links))

    def _sync_links(self, links: list[Link]) -> None:
        """Re-make the links still live."""
        state = self._state
        with state.wire_lock:
            for link in links:
                with state.lock:
                    system = state.system
                    live = (system.has_link(link) and system.is_present(link.output)
                            and system.is_present(link.input))
                if live:
                    try:
                        self.wire_add(link)
                    except PdcpError as err:
                        self._error(f"link {link} could not be re-made: {err}", "transport")

    def reread(self) -> None:
        """After an outage, a job: read each linked input's Source's Node Ids and Data Transfer
        Enabled back; re-make the links whose input does not say what the model says."""
        self._submit(self._reread)

    def _reread(self) -> None:
        state = self._state
        with state.wire_lock:
            with state.lock:
                links = [lk for lk in state.system.links
                         if state.system.is_present(lk.output)
                         and state.system.is_present(lk.input)]
            for link in links:
                with state.lock:
                    in_node = self._nodes.node_of.get(link.input.device)
                    out_node = self._nodes.node_of.get(link.output.device)
                    out_id = self._nodes.output_id(link.output)
                if in_node is None or out_node is None or out_id is None:
                    continue
                try:
                    sources = self._requests.get(in_node, P.IN_SOURCE_NODE_IDS,
                                                 link.input.index)
                    enabled = self._requests.get(in_node, P.CH_DATA_ENABLED, link.input.index)
                    if needs_remaking(out_node, out_id, sources, enabled):
                        log.info("%s: link %s was lost during the outage: re-making it",
                                 self._name, link)
                        self.wire_add(link)
                except PdcpError as err:
                    self._error(f"link {link} could not be read back after the outage: "
                                f"{err}", "transport")


__all__ = ["LinkWriter", "Write", "link_writes", "needs_remaking", "unlink_writes",
           "wanted_source"]
