"""A session over an arbitrator's serial host link (``serial:PORT[@BAUD]`` bus URLs).

A :class:`~pdcp_studio.bus.session.base.BusSession` like a simulated or CAN bus, so scan,
plans, parameter edits, the stored configuration, the monitor and the app work unchanged. The
protocol is host link 2 (docs/host-link.md); the line, retransmission and reconnection are in
``bus/hostlink/conn.py``.

What the arbitrator holds is read once and cached: its device table, each device's channel
table, its links, its stored configuration (by length and CRC). Events say what changed — a
device joined or left, a link was made or removed — and only that is read again; after lost
events or a new greeting everything is. A scan is therefore one pass over the tables the first
time and nothing on the line after that while the bus stays the same.
"""

from __future__ import annotations

import logging
import struct
import threading
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.hostlink import records as hr
from pdcp_studio.bus.hostlink.conn import (
    HostLinkConnection,
    HostLinkError,
    VersionRefused,
)
from pdcp_studio.bus.session.base import BusSession, ProgressFn
from pdcp_studio.bus.session.urls import BusSpec
from pdcp_studio.bus.transaction import Change, Policy, TransactionResult
from pdcp_studio.bus.transaction import Status as TxnStatus
from pdcp_studio.errors import PdcpError, TransportError
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Device, Link, System
from pdcp_studio.protocol import hostlink_messages as hm
from pdcp_studio.protocol.crc import crc16_ccitt_false
from pdcp_studio.protocol.hostlink_messages import Event, Req, Status

if TYPE_CHECKING:
    from pdcp_studio.bus.session.change_road import ConfirmFn
    from pdcp_studio.bus.trace.decoder import FrameDecoder
    from pdcp_studio.storage.archive.chain import Anchor
    from pdcp_studio.storage.history import History

log = logging.getLogger(__name__)

__all__ = ["ChannelCounts", "HostLinkError", "HostLinkSession", "VersionRefused",
           "open_hostlink_session"]

#: How long the arbitrator's system must stay the same to count as settled.
SETTLE_POLL_S = 0.1
#: Seconds TRANSACT_RUN may take: interlock, writes, read-back and perhaps a restore.
TRANSACT_TIMEOUT_S = 30.0
#: Reads of the stored configuration restarted when it changes under them.
CONFIG_READ_ATTEMPTS = 3
BUS_ERROR_KINDS = ("", "bad_frame", "error_frame", "duplicate_device", "node_ids_exhausted",
                   "setup", "plan", "transport", "other_arbitrator")


@dataclass(frozen=True)
class ChannelCounts:
    """Channel data frames per output channel over ``seconds`` (the host link sends counts,
    not the frames: the line cannot carry a busy CAN bus)."""

    counts: dict[ChannelRef, int]
    seconds: float
    timestamp: float
    by_node: dict[int, int]  # as sent: channel node ID → frames (also those not yet read)


class _Cache:
    """What has been read from the arbitrator, and what events say is out of date."""

    def __init__(self) -> None:
        self.lock = threading.RLock()  # short: marking and storing, never across a request
        self.refresh_lock = threading.Lock()  # one refresh at a time (held across requests)
        self.devices: dict[DeviceKey, Device] = {}
        self.links: list[Link] = []
        self.all_stale = True
        self.links_stale = True
        self.stale: set[DeviceKey] = set()
        self.config: tuple[int, int, bytes] | None = None  # length, crc, bytes

    def invalidate(self) -> None:
        with self.lock:
            self.all_stale = self.links_stale = True
            self.config = None


class HostLinkSession(BusSession):
    """A live arbitrator reached over a serial line. Close it (or use ``with``)."""

    def __init__(self, port: Any, *, url: str = "", baudrate: int = 128_000,
                 reply_timeout: float | None = None, monitor: bool = True,
                 transact_timeout: float = TRANSACT_TIMEOUT_S, **link_options: Any) -> None:
        super().__init__(url, events_owner="host link")
        self.transact_timeout = transact_timeout
        self._cache = _Cache()
        self._monitor = monitor
        self._decoder: FrameDecoder | None = None
        options = dict(link_options)
        if reply_timeout is not None:
            options["reply_timeout"] = reply_timeout
        self.conn = HostLinkConnection(port, baudrate=baudrate, where=url or str(port),
                                       on_event=self._on_event, on_notice=self._notice,
                                       on_greeted=self._on_greeted, **options)
        self.info = self.conn.info
        if monitor:
            self._start_monitor()

    @property
    def closed(self) -> bool:
        """True once closed here, or once the line closed for good."""
        return super().closed or self.conn.closed

    @property
    def port(self) -> Any:
        return self.conn.port

    def _release(self) -> None:
        """Close the port."""
        self.conn.close()

    def request(self, code: Req, body: bytes = b"", *, timeout: float | None = None) -> bytes:
        return self.conn.request(code, body, timeout=timeout)

    # -- events (from the line thread) --------------------
    def _notice(self, text: str) -> None:
        log.warning("%s", text)
        self._emit(ev.BusError(text, "transport"))

    def _on_greeted(self, count: int) -> None:
        if count > 1:  # the arbitrator forgot us: what we cached may be old
            self._cache.invalidate()
            if self._monitor:
                threading.Thread(target=self._start_monitor, daemon=True,
                                 name="pdcp host link monitor").start()

    def _start_monitor(self) -> None:
        try:
            self.request(Req.MONITOR, bytes([0x03, 10]))
        except PdcpError as err:
            log.info("%s: no monitor traffic: %s", self.url, err)

    def _on_event(self, message: bytes) -> None:
        code, body = message[0], bytes(message[1:])
        cache = self._cache
        try:
            if code == Event.DEVICE_JOINED:
                key = hr.unpack_key(body)
                with cache.lock:
                    cache.stale.add(key)
                    cache.links_stale = True
                self._emit(ev.DeviceJoined(key))
            elif code == Event.DEVICE_LEFT:  # the key, then (optional) why it left (§5.7)
                left = hr.unpack_left(body)
                with cache.lock:
                    cache.stale.add(left.key)
                    cache.links_stale = True
                self._emit(ev.DeviceLeft(left.key, why=left.why, silent_s=left.silent_s,
                                         interval_s=left.interval_s))
            elif code == Event.DEVICE_REPLACED:  # the old key, the new one (§5.7)
                old, new = hr.unpack_key(body), hr.unpack_key(body, hm.KEY.size)
                with cache.lock:
                    cache.stale.update((old, new))
                    cache.links_stale = True
                self._emit(ev.DeviceReplaced(old, new))
            elif code in (Event.LINK_MADE, Event.LINK_REMOVED):
                link, _ = hr.unpack_link_event(body)
                with cache.lock:
                    cache.stale.update((link.output.device, link.input.device))
                    cache.links_stale = True
                self._emit(ev.LinkMade(link) if code == Event.LINK_MADE else ev.LinkRemoved(link))
            elif code == Event.OTHER_ARBITRATOR:
                self._emit(ev.BusError(hm.text(body), "other_arbitrator"))
            elif code == Event.BUS_ERROR:
                hm.need(body, 1, "BUS_ERROR")
                kind = BUS_ERROR_KINDS[body[0]] if body[0] < len(BUS_ERROR_KINDS) else ""
                self._emit(ev.BusError(hm.text(body[1:]), kind))
            elif code == Event.TRANSACTION_DONE:
                hm.need(body, 1, "TRANSACTION_DONE")
                statuses = list(TxnStatus)
                status = statuses[body[0]] if body[0] < len(statuses) else TxnStatus.FAILED
                cache.config = None  # links come as their own events
                self._emit(ev.TransactionDone(TransactionResult(status, hm.text(body[1:]))))
            elif code == Event.TERMINALS_UNCONNECTED:
                hm.need(body, 1, "TERMINALS_UNCONNECTED")
                n = body[0]
                hm.need(body, 1 + n * hm.REF.size, "TERMINALS_UNCONNECTED")
                refs = tuple(ChannelRef(*hm.REF.unpack_from(body, 1 + i * hm.REF.size))
                             for i in range(n))
                self._emit(ev.TerminalsUnconnected(refs, hm.text(body[1 + n * hm.REF.size:])))
            elif code == Event.EVENTS_LOST:
                cache.invalidate()
            elif code == Event.FRAMES:
                self._frames(body)
            elif code == Event.CHANNEL_COUNTS:
                self._counts(body)
        except hm.MessageError as err:
            log.warning("%s: a malformed event 0x%02X: %s", self.url, code, err)

    def _frames(self, body: bytes) -> None:
        from pdcp_studio.bus.trace.decoder import FrameDecoder

        frames, dropped = hm.unpack_frames(body)
        if dropped:
            self._emit(ev.BusError(f"the monitor missed {dropped} frame(s): more than the "
                                   "serial line carries", "monitor"))
        if self._decoder is None:
            self._decoder = FrameDecoder()
        now = time.time()
        last = frames[-1].time_ms if frames else 0
        for f in frames:
            stamp = now - ((last - f.time_ms) & 0xFFFFFFFF) / 1000.0
            line = self._decoder.decode(f.arbitration_id, f.data, stamp).line
            self._emit(ev.FrameSeen(stamp, f.arbitration_id, f.data, line))

    def _counts(self, body: bytes) -> None:
        period, counts = hm.unpack_counts(body)
        by_node: dict[int, ChannelRef] = {}
        with self._cache.lock:
            for dev in self._cache.devices.values():
                for ch in dev.outputs():
                    if ch.node_id:
                        by_node[ch.node_id] = dev.ref(ch.index)
        refs = {by_node[n]: c for n, c in counts.items() if n in by_node}
        self._emit(ChannelCounts(refs, period / 1000.0, time.time(), counts))

    # -- reading the tables --------------------
    def _fetch_device(self, key: DeviceKey) -> Device:
        """GET_DEVICE (its parameters and the first channels), GET_CHANNELS for the rest."""
        body = self.request(Req.GET_DEVICE, hr.pack_key(key))
        device, count, used = hr.unpack_device_info(key, body)
        channels, nxt = hr.unpack_channel_page(body[used:])
        while True:
            for ch in channels:
                device.add_channel(ch)
            if len(device.channels) >= count or (channels and not nxt):
                return device
            start = nxt
            channels, nxt = hr.unpack_channel_page(
                self.request(Req.GET_CHANNELS, hr.pack_key(key) + bytes([start])))
            if not channels:
                return device

    def _fetch_rows(self) -> list[hr.DeviceRow]:
        rows: list[hr.DeviceRow] = []
        while True:
            body = self.request(Req.LIST_DEVICES, struct.pack("<H", len(rows)))
            hm.need(body, 4, "LIST_DEVICES reply")
            total, _ = struct.unpack_from("<HH", body)
            page = hr.unpack_device_rows(body[4:])
            rows += page
            if len(rows) >= total or not page:
                return rows

    def _fetch_links(self) -> list[Link]:
        links: list[Link] = []
        while True:
            body = self.request(Req.LIST_LINKS, struct.pack("<H", len(links)))
            hm.need(body, 4, "LIST_LINKS reply")
            total, _ = struct.unpack_from("<HH", body)
            rest = body[4:]
            page = [hr.unpack_link(rest, off) for off in range(0, len(rest), 2 * hm.REF.size)]
            links += page
            if len(links) >= total or not page:
                return links

    def _refresh(self, progress: ProgressFn | None = None,
                 cancel: threading.Event | None = None) -> System:
        """Read what events marked out of date. Requests run outside ``cache.lock`` (the line
        thread takes it to mark things stale), one refresh at a time."""
        cache = self._cache
        with cache.refresh_lock:
            with cache.lock:
                full, cache.all_stale = cache.all_stale, False
                if full:
                    cache.stale.clear()
                    cache.links_stale = True
            if full:
                keys = [r.key for r in self._fetch_rows()]
                with cache.lock:
                    cache.devices = {k: d for k, d in cache.devices.items() if k in keys}
                    cache.stale.update(keys)
            with cache.lock:
                todo = sorted(cache.stale)
                cache.stale.difference_update(todo)
                links_stale, cache.links_stale = cache.links_stale, False
            total = len(todo) + 1
            try:
                for n, key in enumerate(todo):
                    if cancel is not None and cancel.is_set():
                        from pdcp_studio.bus.arbitrator.reading.scan import ScanCancelled

                        raise ScanCancelled(f"scan cancelled after {n} of {len(todo)} devices",
                                            self._snapshot())
                    if progress is not None:
                        progress(n, total, f"{key}")
                    try:
                        device: Device | None = self._fetch_device(key)
                    except HostLinkError as err:
                        if err.status is not Status.UNKNOWN_DEVICE:
                            raise
                        device = None
                    with cache.lock:
                        if device is None:
                            cache.devices.pop(key, None)
                        else:
                            cache.devices[key] = device
                    todo[n] = None  # type: ignore[call-overload]
                if links_stale:
                    links = self._fetch_links()
                    with cache.lock:
                        cache.links = links
                    links_stale = False
            finally:  # what was not read stays out of date
                with cache.lock:
                    cache.stale.update(k for k in todo if k is not None)
                    cache.links_stale = cache.links_stale or links_stale
            return self._snapshot()

    def _snapshot(self) -> System:
        cache = self._cache
        with cache.lock:
            system = System([d for _, d in sorted(cache.devices.items())])
            for link in cache.links:
                if system.device(link.output.device) and system.device(link.input.device):
                    system.add_link(link, check=False)
            return system.copy()

    # -- the session face --------------------
    def system(self) -> System:
        """The arbitrator's system (node IDs, presence, links), read only where it changed."""
        return self._refresh()

    def scan(self, progress: ProgressFn | None = None,
             cancel: threading.Event | None = None) -> System:
        """The arbitrator's tables: devices, channels, parameters, links (cached)."""
        report = self._reporting(progress)
        system = self._refresh(report, cancel)
        present = System([d for d in system.devices.values() if d.present])
        for link in system.links:
            if present.device(link.output.device) and present.device(link.input.device):
                present.add_link(link, check=False)
        report(1, 1, f"{len(present.devices)} device(s), {len(present.links)} link(s)")
        return present

    def status(self) -> dict[str, Any]:
        flags, devices, links, changes, lost = hm.STATUS.unpack(self.request(Req.STATUS))
        return {"settled": bool(flags & 1), "startup_done": bool(flags & 2),
                "other_arbitrator": bool(flags & 4), "devices": devices, "links": links,
                "changes": changes, "events_lost": lost}

    def wait_settled(self, timeout: float) -> bool:
        """True once the arbitrator reports no bind, set-up or plan in progress."""
        deadline = time.monotonic() + timeout
        while True:
            if self.status()["settled"]:
                return True
            if time.monotonic() >= deadline:
                return False
            time.sleep(SETTLE_POLL_S)

    def get_parameter(self, key: DeviceKey, param: int, channel: int = 0, *,
                      timeout: float | None = None) -> bytes:
        """One parameter value of any length (the arbitrator reads it; chunks over the link)."""
        address = hm.PARAM.pack(*DeviceKey(*key), channel, param)
        value = bytearray()
        while True:
            body = self.request(Req.GET_PARAM, address + struct.pack("<H", len(value)),
                                timeout=timeout)
            hm.need(body, hm.SPAN.size, "GET_PARAM reply")
            offset, total = hm.SPAN.unpack_from(body)
            value[offset:] = body[hm.SPAN.size:]
            if len(value) >= total or len(body) == hm.SPAN.size:
                return bytes(value[:total])

    def write_parameter_bytes(self, key: DeviceKey, param: int, channel: int,
                              value: bytes, *, timeout: float | None = None) -> None:
        """SET_PARAM in chunks, outside any transaction (the protocol's primitive; the session's
        ``set_parameter`` is a transaction, as every change to a prosthesis)."""
        key = DeviceKey(*key)
        address = hm.PARAM.pack(*key, channel, param)
        value = bytes(value)
        offset = 0
        while True:
            chunk = value[offset:offset + hm.CHUNK]
            self.request(Req.SET_PARAM, address + hm.SPAN.pack(offset, len(value)) + chunk,
                         timeout=timeout)
            offset += len(chunk)
            if offset >= len(value):
                break
        with self._cache.lock:
            self._cache.stale.add(key)

    def suspend(self, key: DeviceKey, ms: int = 0) -> None:
        self.request(Req.SUSPEND, hr.pack_key(DeviceKey(*key)) + struct.pack("<H", ms))

    def release(self, key: DeviceKey) -> None:
        self.request(Req.RELEASE, hr.pack_key(DeviceKey(*key)))

    def reset_device(self, key: DeviceKey) -> None:
        self.request(Req.RESET_DEVICE, hr.pack_key(DeviceKey(*key)))

    # -- the stored configuration --------------------
    def read_configuration_bytes(self) -> bytes:
        """The stored configuration's bytes (from the cache when its length and CRC match)."""
        length, crc = hm.CONFIG_INFO.unpack(self.request(Req.CONFIG_INFO))
        cached = self._cache.config
        if cached is not None and cached[:2] == (length, crc):
            return cached[2]
        return self._read_config_fresh()

    def _read_config_fresh(self) -> bytes:
        for _ in range(CONFIG_READ_ATTEMPTS):
            data = bytearray()
            first: tuple[int, int] | None = None
            while True:
                body = self.request(Req.CONFIG_READ, struct.pack("<H", len(data)))
                hm.need(body, hm.CONFIG_INFO.size, "CONFIG_READ reply")
                info = hm.CONFIG_INFO.unpack_from(body)
                if first is None:
                    first = info
                elif info != first:
                    break  # changed under us: read again
                data += body[hm.CONFIG_INFO.size:]
                if len(data) >= info[0] or len(body) == hm.CONFIG_INFO.size:
                    break
            if first is not None and len(data) == first[0] and \
                    crc16_ccitt_false(data) == first[1]:
                self._cache.config = (first[0], first[1], bytes(data))
                return bytes(data)
        raise TransportError(f"{self.url}: the stored configuration kept changing while it "
                             "was read")

    def read_configuration(self) -> ConfigCollection:
        """The arbitrator's stored configuration (empty when it has none)."""
        from pdcp_studio.storage import config_codec

        data = self.read_configuration_bytes()
        return config_codec.loads(data) if data else ConfigCollection()

    def write_configuration_bytes(self, data: bytes) -> None:
        """Stage ``data`` in chunks and commit it; the arbitrator stores it only whole and with
        a matching CRC (HostLinkError CHECKSUM / BAD_OFFSET otherwise; the old one stays)."""
        data = bytes(data)
        self.request(Req.CONFIG_WRITE_BEGIN, hm.CONFIG_INFO.pack(len(data),
                                                                 crc16_ccitt_false(data)))
        for offset in range(0, len(data), hm.CHUNK):
            self.request(Req.CONFIG_WRITE_CHUNK,
                         struct.pack("<H", offset) + data[offset:offset + hm.CHUNK])
        self._cache.config = None
        self.request(Req.CONFIG_WRITE_COMMIT)

    # -- the change road ----------------------------------------------------------------
    def transact(self, change: Change, *, operator: str | None = None,
                 patient: str | None = None, confirm: ConfirmFn | None = None,
                 progress: ProgressFn | None = None, cancel: threading.Event | None = None,
                 history: History | None = None, record: bool = True) -> TransactionResult:
        """The change road, after checking that the host link can carry the change: one
        beyond the limit is refused here, in words naming its size and the limit, before
        anything is sent and before the fitting history announces it (a false
        "interrupted" entry)."""
        refused = self._too_large(change, resolve=True)
        if refused is not None:
            return refused
        return super().transact(change, operator=operator, patient=patient, confirm=confirm,
                                progress=progress, cancel=cancel, history=history,
                                record=record)

    def _too_large(self, change: Change, *, resolve: bool = False) -> TransactionResult | None:
        """A FAILED result at the preview when the host link cannot carry ``change`` (with
        its stored configuration resolved from the live links when ``resolve``)."""
        from pdcp_studio.bus.hostlink.change import size_problem

        try:
            if resolve and change.store:
                from pdcp_studio.bus.session.change_road import resolve_store

                change = resolve_store(self.system(), change)
            why = size_problem(change)
        except PdcpError:  # a bus that does not answer, a configuration that does not
            return None    # encode: the road's own steps say so, as before
        if why is None:
            return None
        return TransactionResult(TxnStatus.FAILED, change.action, "preview", why)

    def carry_out(self, change: Change, progress: ProgressFn | None = None,
                  cancel: threading.Event | None = None) -> TransactionResult:
        """The arbitrator carries ``change`` out as one transaction (interlock, write, read
        back, restore on a mismatch, release): staged in chunks with a CRC, then run."""
        from pdcp_studio.bus.hostlink.change import decode_result, encode_change

        if cancel is not None and cancel.is_set():
            return TransactionResult(TxnStatus.DECLINED, change.action, "confirm", "cancelled")
        refused = self._too_large(change)
        if refused is not None:
            return refused
        data = encode_change(change)
        chunks = range(0, len(data), hm.CHUNK)
        try:
            self.request(Req.TRANSACT_BEGIN,
                         hm.CONFIG_INFO.pack(len(data), crc16_ccitt_false(data)))
            for n, offset in enumerate(chunks):
                if progress is not None:
                    progress(n, len(chunks) + 1, f"{change.action}: sending the change")
                self.request(Req.TRANSACT_CHUNK,
                             struct.pack("<H", offset) + data[offset:offset + hm.CHUNK])
            if progress is not None:
                progress(len(chunks), len(chunks) + 1, f"{change.action}: the arbitrator "
                                                       "carries it out")
            length, crc = hm.CONFIG_INFO.unpack(self.request(Req.TRANSACT_RUN,
                                                             timeout=self.transact_timeout))
        except HostLinkError as err:
            return TransactionResult(TxnStatus.FAILED, change.action, "write",
                                     f"the arbitrator refused the change: {err}")
        finally:
            self._changed_by(change)
        result_bytes = self._read_blob(Req.RESULT_READ, length, crc)
        result = decode_result(result_bytes)
        if progress is not None:
            progress(1, 1, result.summary())
        return result

    def _changed_by(self, change: Change) -> None:
        with self._cache.lock:
            self._cache.config = None
            self._cache.links_stale = True
            for action in change.links:
                self._cache.stale.update((action.link.output.device, action.link.input.device))
            self._cache.stale.update(p.device for p in change.parameters)

    def _read_blob(self, code: Req, length: int, crc: int) -> bytes:
        data = bytearray()
        while len(data) < length:
            body = self.request(code, struct.pack("<H", len(data)))
            hm.need(body, hm.CONFIG_INFO.size, f"{code.name} reply")
            if hm.CONFIG_INFO.unpack_from(body) != (length, crc):
                raise TransportError(f"{self.url}: the arbitrator's {code.name} changed while "
                                     "it was read")
            chunk = body[hm.CONFIG_INFO.size:]
            if not chunk:
                break
            data += chunk
        if len(data) != length or crc16_ccitt_false(data) != crc:
            raise TransportError(f"{self.url}: {code.name} gave {len(data)} bytes that do not "
                                 f"match the announced {length} and CRC 0x{crc:04X}")
        return bytes(data)

    def read_policy(self) -> Policy:
        """The arbitrator's profile-layer policy (GET_POLICY)."""
        return Policy(autoconfigure=bool(self.request(Req.GET_POLICY)[0] & 1))

    def read_anchor(self) -> Anchor | None:
        """The fitting history's anchor in the arbitrator's memory (ANCHOR_READ); None when
        it keeps none (or is a firmware from before anchors: UNKNOWN_REQUEST)."""
        return self._anchor(Req.ANCHOR_READ, b"")

    def write_anchor(self, anchor: Anchor) -> Anchor | None:
        """Store the fitting history's anchor (ANCHOR_WRITE); returns it as read back."""
        return self._anchor(Req.ANCHOR_WRITE, hr.pack_anchor(anchor))

    def _anchor(self, code: Req, body: bytes) -> Anchor | None:
        try:
            reply = self.request(code, body)
        except HostLinkError as err:
            if err.status is Status.UNKNOWN_REQUEST:
                return None
            raise
        try:
            return hr.unpack_optional_anchor(reply)
        except hm.MessageError as err:
            raise TransportError(f"{self.url}: {code.name} reply: {err}") from None


#: Options of other session kinds (memory, scan window, …) that mean nothing over a host link.
_SESSION_OPTIONS = ("reply_timeout", "settle_timeout", "monitor", "ack_timeout", "max_attempts",
                    "transact_timeout")


def open_hostlink_session(spec: BusSpec, **options: Any) -> HostLinkSession:
    """Open ``spec`` (a parsed ``serial:`` BusSpec), greet the arbitrator, check the version.

    Options meant for an in-process arbitrator (``memory``, ``scan_window``, …) are ignored:
    the arbitrator at the other end of the line owns its memory and its bus.
    """
    ignored = sorted(k for k in options if k not in _SESSION_OPTIONS)
    if ignored:
        log.debug("host link: ignoring options %s", ", ".join(ignored))
    options = {k: v for k, v in options.items() if k in _SESSION_OPTIONS}
    settle = options.pop("settle_timeout", None)
    session = HostLinkSession(spec.port, url=spec.url, baudrate=spec.baud, **options)
    if settle:
        try:
            session.wait_settled(settle)
        except BaseException:
            session.close()
            raise
    return session
