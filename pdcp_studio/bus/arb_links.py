"""Links on the wire: the parameters that make, re-make and remove a link between devices.

A mixin of :class:`pdcp_studio.bus.arbitrator.Arbitrator`: the public ``add_link`` and
``remove_link``, re-making links after an Update Data Channel request, and silencing inputs
whose source left. Wire work is serialized by the arbitrator's plan lock.
"""

from __future__ import annotations

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arb_common import _NOT_CONNECTED, _OFF, _ON, _input_value, _Node
from pdcp_studio.errors import ModelError, NodeIdExhaustedError, PdcpError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import NO_SOURCE, Link, SourceInfo
from pdcp_studio.protocol import ResponseCode, UpdateDataChannel, UpdateDataChannelResponse


class LinksMixin:
    """Making and removing links on the bus for the :class:`Arbitrator`."""

    # -- departures: inputs whose source left ---------------------------------------------
    def _links_from(self, output: ChannelRef) -> list[Link]:
        return [Link(output, i) for i in self._system.inputs_fed_by(output)]

    def _silence_inputs(self, links: list[Link]) -> None:
        """Inputs fed by a departed output stop listening: its node ID may be reused."""
        try:
            with self._plan_lock:
                for link in links:
                    with self._lock:
                        node_id = self._node_of.get(link.input.device)
                        others = [s for s in self._system.sources_of(link.input)
                                  if s != link.output and self._system.is_present(s)]
                    if node_id is None or others:
                        continue
                    try:
                        self.requests.set(node_id, P.CH_DATA_ENABLED, link.input.index, _OFF)
                        self.requests.set(node_id, P.IN_SOURCE_NODE_IDS, link.input.index,
                                          b"\0\0")
                    except PdcpError as err:
                        self._error(f"input {link.input} could not be told its source left: "
                                    f"{err}", "transport")
                        continue
                    with self._lock:
                        ch = self._system.channel(link.input)
                        if ch is not None:
                            ch.data_enabled = False
        finally:
            with self._lock:
                self._jobs -= 1

    # -- Update Data Channel --------------------------------------------------------------
    def _on_update(self, node: _Node, msg: UpdateDataChannel) -> None:
        self._send_quiet(UpdateDataChannelResponse(node.node_id, ResponseCode.SUCCESS,
                                                   msg.channel))
        with self._lock:
            node.updates.add(msg.channel)
            if not node.set_up:
                return  # set-up (step 5) handles it
            ref = ChannelRef(*node.key, msg.channel)
            links = [Link(s, ref) for s in self._system.sources_of(ref)]
            self._jobs += 1
        try:
            self._pool_exec.submit(self._sync_links, links)
        except RuntimeError:
            with self._lock:
                self._jobs -= 1

    def _sync_links(self, links: list[Link]) -> None:
        try:
            with self._plan_lock:
                for link in links:
                    with self._lock:
                        live = (self._system.has_link(link) and self._system.is_present(link.output)
                                and self._system.is_present(link.input))
                    if live:
                        try:
                            self._wire_add(link)
                        except PdcpError as err:
                            self._error(f"link {link} could not be re-made: {err}", "transport")
        finally:
            with self._lock:
                self._jobs -= 1

    # -- links on the wire ----------------------------------------------------------------
    def _wire_add(self, link: Link) -> None:
        """Input: Source's Node Ids, the redundant source fields, Data Transfer Enabled;
        output: Data Transfer Enabled (setup step 6). Updates the model's channels."""
        with self._lock:
            out_node = self._node_of.get(link.output.device)
            in_node = self._node_of.get(link.input.device)
            out_id = self._pool.id_of((link.output.device, link.output.index))
            out_ch = self._system.channel(link.output)
            in_ch = self._system.channel(link.input)
            if out_node is None or in_node is None or out_ch is None or in_ch is None:
                raise ModelError(f"link {link}: both devices must be on the bus")
            if out_id is None:
                raise NodeIdExhaustedError(f"link {link}: output {link.output} has no node ID")
            want = SourceInfo(link.output.vid, link.output.pid, link.output.serial,
                              link.output.index, out_ch.type, out_ch.profile)
            have = in_ch.source
        i = link.input.index
        self.requests.set(in_node, P.IN_SOURCE_NODE_IDS, i, bytes([out_node, out_id]))
        if (have.vid, have.pid) != (want.vid, want.pid):
            self.requests.set(in_node, P.IN_SOURCE_VID_PID, i,
                              _input_value(P.IN_SOURCE_VID_PID, (want.vid, want.pid)))
        if (have.serial, have.index) != (want.serial, want.index):
            self.requests.set(in_node, P.IN_SOURCE_SN_INDEX, i,
                              _input_value(P.IN_SOURCE_SN_INDEX, (want.serial, want.index)))
        if (have.type, have.profile) != (want.type, want.profile):
            self.requests.set(in_node, P.IN_SOURCE_TYPE_PROFILE, i,
                              _input_value(P.IN_SOURCE_TYPE_PROFILE, (want.type, want.profile)))
        with self._lock:
            in_ch.source = want
        self.requests.set(in_node, P.CH_DATA_ENABLED, i, _ON)
        with self._lock:
            in_ch.data_enabled = True
        self.requests.set(out_node, P.CH_DATA_ENABLED, link.output.index, _ON)
        with self._lock:
            out_ch.data_enabled = True

    def _wire_remove(self, link: Link) -> None:
        """After the model dropped ``link``: clear the input unless it has another source,
        and stop the output unless it still feeds a present input."""
        with self._lock:
            in_node = self._node_of.get(link.input.device)
            out_node = self._node_of.get(link.output.device)
            in_ch = self._system.channel(link.input)
            out_ch = self._system.channel(link.output)
            other = self._system.source_of(link.input)
            still_feeds = any(self._system.is_present(i)
                              for i in self._system.inputs_fed_by(link.output))
        if in_node is not None and in_ch is not None and other is None:
            i = link.input.index
            self.requests.set(in_node, P.CH_DATA_ENABLED, i, _OFF)
            self.requests.set(in_node, P.IN_SOURCE_NODE_IDS, i, b"\0\0")
            for param, value in _NOT_CONNECTED.items():
                self.requests.set(in_node, param, i, value)
            with self._lock:
                in_ch.source, in_ch.data_enabled = NO_SOURCE, False
        if out_node is not None and out_ch is not None and not still_feeds:
            self.requests.set(out_node, P.CH_DATA_ENABLED, link.output.index, _OFF)
            with self._lock:
                out_ch.data_enabled = False

    def add_link(self, link: Link) -> None:
        """Make a link on the bus; ModelError for what the model refuses (a second source on
        an input, wrong directions) or an end that is not on the bus.

        A dead link (its output gone) on the same input is replaced.
        """
        with self._plan_lock:
            with self._lock:
                system = self._system
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
                self._remove(old)
            self._add(link)

    def remove_link(self, link: Link) -> None:
        """Remove a link from the model and the bus (ModelError if there is no such link)."""
        with self._plan_lock:
            with self._lock:
                if not self._system.has_link(link):
                    raise ModelError(f"link {link} is not in the system")
            self._remove(link)

    def _add(self, link: Link) -> None:
        with self._lock:
            present = (self._system.is_present(link.output)
                       and self._system.is_present(link.input))
        if present:
            self._wire_add(link)
        with self._lock:
            if not self._system.has_link(link):
                self._system.add_link(link, check=False)
        self._emit(ev.LinkMade(link))

    def _remove(self, link: Link) -> None:
        with self._lock:
            if self._system.has_link(link):
                self._system.remove_link(link)
        self._wire_remove(link)
        self._emit(ev.LinkRemoved(link))

