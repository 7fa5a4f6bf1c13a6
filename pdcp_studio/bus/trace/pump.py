"""The monitor's hot loop: frames in, decoded lines (or JSON records) out, as fast as a
saturated bus needs.

Most frames of a busy PDCP bus are channel data of outputs the decoder already knows, and
every frame of one such identifier reads the same but for its time and data bytes. The pump
decodes the first frame of an identifier through ``FrameDecoder`` and keeps what it
learned — the line's and the JSON record's fixed parts, whether the filter shows it, the
per-ID statistics entry — until the decoder learns something new (``FrameDecoder.version``).
The next frames of that identifier cost a dictionary look-up, the counts and the text of
their variable parts. Every other frame goes through the decoder as before. The output is
the same text, character for character, as decoding every frame one by one
(``tests/bus/test_trace_pump.py`` checks it on mixed traffic).
"""

from __future__ import annotations

from binascii import hexlify
from collections.abc import Callable, Iterable
from typing import Any

from pdcp_studio.bus.trace.decoder import FrameDecoder
from pdcp_studio.bus.trace.frames import CACHE_SIZE, CHANNEL_DATA, NOT_PDCP, DecodedFrame
from pdcp_studio.bus.trace.jsonout import (
    JsonFrameWriter,
    base_kind,
    frame_json,
    json_str,
    kind_json,
    link_json,
    utf8_buffer,
)
from pdcp_studio.protocol.codes import ResponseCode

#: Lines gathered before they are written in one call.
CHUNK = 512
#: Channel data frames handed to the bus-time meter at once.
METER_BATCH = 4096
_CHANNEL_DATA = "Channel data"
_FAILURE = ResponseCode.FAILURE.title


def json_times(t: float) -> tuple[str, str]:
    """A record's time as the list shows it (``%.6f``) and as JSON writes it:
    ``repr(round(t, 6))`` without rounding twice — the same digits where repr writes no
    exponent and 15 digits round-trip."""
    fixed = f"{t:.6f}"
    short = fixed.rstrip("0")
    if short[-1] == ".":
        short += "0"
    if not 1e-4 <= t < 1e9:
        short = repr(round(t, 6))
    return fixed, short


class TracePump:
    """Feeds frames to a decoder and writes what ``show`` lets through to ``out``.

    ``json``: one JSON list of frame records (``JsonFrameWriter``) instead of lines.
    ``recorder``: also writes every frame to a capture. ``on_error(frame)``: called for
    undecodable frames. ``flush_each_chunk``: flush ``out`` after each chunk (live).
    """

    def __init__(self, decoder: FrameDecoder, out: Any, *, json: bool = False,
                 show: Callable[[DecodedFrame], bool] | None = None, recorder: Any = None,
                 on_error: Callable[[DecodedFrame], None] | None = None,
                 flush_each_chunk: bool = False) -> None:
        self.decoder, self.out, self.show = decoder, out, show
        self.recorder, self.on_error = recorder, on_error
        self.flush_each_chunk = flush_each_chunk
        self.json = JsonFrameWriter(out) if json else None
        #: Lines as UTF-8 bytes, written to the stream's byte buffer: a line with an arrow
        #: in it is a str of 2-byte characters, and encoding those costs more than making
        #: the line (JSON records are ASCII, so they stay str).
        self._bytes_out = None if json else utf8_buffer(out)
        self._parts: list[Any] = []
        #: arbitration ID → (stats entry or None, shown, line head, JSON parts or None)
        self._heads: dict[int, tuple[Any, ...]] = {}
        #: id(a cached frame's text) → (that text, the JSON record's fixed parts)
        self._json_cache: dict[int, tuple[str, str, str]] = {}
        #: (arbitration ID, data) → what a beacon or request seen before reads and counts as
        #: (see ``FrameDecoder.repeatable``)
        self._repeats: dict[tuple[int, bytes], tuple[Any, ...]] = {}
        self._version = -1

    # -- output -----------------------------------------------------------------------------

    def flush(self) -> None:
        """Write what is gathered (``out`` itself is flushed by the caller or per chunk)."""
        parts = self._parts
        if parts:
            if self.json is not None:
                self.json.write_records(parts)
            elif self._bytes_out is not None:
                self.out.flush()  # what was written as text first
                write = self._bytes_out.write
                write(b"\n".join(parts))  # no copy of the chunk to add its last newline
                write(b"\n")
            else:
                self.out.write("\n".join(parts) + "\n")
            parts.clear()

    def _chunk_full(self) -> None:
        """A chunk is gathered: write it (and flush ``out`` when asked to per chunk)."""
        self.flush()
        if self.flush_each_chunk:
            self.out.flush()

    def close(self, summary: Any = None) -> None:
        """Write the rest; a JSON document is ended with ``summary`` (also after a
        failure: one document)."""
        self.flush()
        if self.json is not None:
            self.json.close(summary)

    # -- the loop ---------------------------------------------------------------------------

    def run(self, frames: Iterable[Any], on_other: Callable[[Any], None]) -> None:
        """Decode every frame of ``frames``; anything that is not a frame (``None`` for a
        quiet poll, reports) goes to ``on_other`` after what is gathered is written."""
        decoder = self.decoder
        stats = decoder.stats
        decode = decoder.decode_message
        heads = self._heads
        parts = self._parts
        append = parts.append
        recorder, show, on_error = self.recorder, self.show, self.on_error
        as_json = self.json is not None
        as_bytes = self._bytes_out is not None
        meter_on = decoder.meter_on
        # Channel data counted here, handed to the statistics at quiet moments and at the
        # end (nothing the decoder decides reads them), and to the bus-time meter in batches.
        ids: list[int] = []
        payloads: list[Any] = []
        fast = untracked = 0
        managed = managed_at_decode = 0  # frames counted here / when one was last decoded
        timestamp = 0.0
        repeats = self._repeats
        # One time base for every line: seconds since the first frame (the decoder's t0).
        # Before the first frame is decoded there is none yet; the fast paths below only
        # see identifiers decoded before, so t0 is taken as soon as the decoder has it (read
        # once at the start, it stayed 0 and those lines showed the epoch).
        t0 = decoder.t0 or 0.0
        t0_known = decoder.t0 is not None
        if self._version != decoder.version:
            heads.clear()
            repeats.clear()
            self._version = decoder.version
        json_cache = self._json_cache
        # (DLC, channel) → the end of a classical data frame's JSON record (its kind fields)
        kinds: dict[tuple[int, Any], str] = {}

        # The frames of a known identifier counted here: channel data of a PDCP capture, or
        # every classical data frame of a foreign one (shown as plain CAN).
        foreign = decoder.foreign
        fast_function = NOT_PDCP if foreign else _CHANNEL_DATA

        def settle() -> None:
            nonlocal ids, payloads, fast, untracked
            stats.frames += fast
            stats.by_function[fast_function] += fast
            if not foreign:
                stats.in_context += fast
            stats.other_ids += untracked
            if meter_on and ids:
                meter = stats.meter
                last = meter.last_timestamp
                meter.add_batch(ids, payloads, timestamp)
                if managed == managed_at_decode and last is not None:
                    meter.last_timestamp = last  # the last frame went through the decoder
                ids, payloads = [], []
            fast = untracked = 0

        try:
            for msg in frames:
                try:
                    arbitration_id = msg.arbitration_id
                except AttributeError:  # not a frame: a quiet poll or a report
                    if fast or ids:
                        settle()
                    self.flush()
                    if self.flush_each_chunk:
                        self.out.flush()
                    on_other(msg)
                    if self._version != decoder.version:
                        heads.clear()
                        repeats.clear()
                        self._version = decoder.version
                    continue
                head = heads.get(arbitration_id)
                if head is not None and not (msg.is_extended_id or msg.is_remote_frame
                                             or msg.is_error_frame or msg.is_fd):
                    data = msg.data
                    if len(data) <= 8:
                        if recorder is not None:
                            recorder.write_message(msg)
                        timestamp = msg.timestamp or 0.0
                        fast += 1
                        managed += 1
                        if meter_on:
                            ids.append(arbitration_id)
                            payloads.append(data)
                            if len(ids) >= METER_BATCH:
                                stats.meter.add_batch(ids, payloads, timestamp)
                                ids, payloads = [], []
                        entry = head[0]
                        if entry is not None:
                            entry[0] += 1
                            entry[2] = timestamp
                            entry[3] = data
                        else:
                            untracked += 1
                        if head[1]:
                            t = timestamp - t0
                            if as_bytes:
                                append(b"%11.6f  %b%b" % (t, head[4], hexlify(data, b" ").upper()
                                                          or b"(empty)"))
                                if len(parts) >= CHUNK:
                                    self._chunk_full()
                                continue
                            upper = data.hex(" ").upper() or "(empty)"
                            if as_json:
                                j = head[3]
                                fixed = f"{t:.6f}"  # json_times(t), inline: the hot path
                                short = fixed.rstrip("0")
                                if short[-1] == "." or not 1e-4 <= t < 1e9:
                                    short = json_times(t)[1]
                                kind_key = (msg.dlc, msg.channel)
                                kind = kinds.get(kind_key)
                                if kind is None:
                                    kind = kinds[kind_key] = base_kind(*kind_key)
                                append(f'{{"timestamp": {timestamp!r}, "time": {short}{j[0]}'
                                       f'{data.hex()}{j[1]}{upper}{j[2]}{fixed:>11}{j[3]}'
                                       f'{upper}{kind}')
                            else:
                                append(f"{t:11.6f}  {head[2]}{upper}")
                            if len(parts) >= CHUNK:
                                self._chunk_full()
                        continue
                key = frame = None
                if not (msg.is_extended_id or msg.is_remote_frame or msg.is_error_frame
                        or msg.is_fd):
                    data = msg.data
                    key = (arbitration_id, bytes(data))
                    rep = repeats.get(key)
                    if rep is not None and len(data) <= 8:
                        # A frame seen before: as the decoder would, from what it said then
                        # (it still follows requests and checks that a response fits).
                        if recorder is not None:
                            recorder.write_message(msg)
                        fits = decoder._context(rep[0])
                        timestamp = msg.timestamp or 0.0
                        managed += 1
                        stats.frames += 1
                        if meter_on:
                            ids.append(arbitration_id)
                            payloads.append(data)
                            if len(ids) >= METER_BATCH:
                                stats.meter.add_batch(ids, payloads, timestamp)
                                ids, payloads = [], []
                        entry = rep[1]
                        if entry is not None:
                            entry[0] += 1
                            entry[2] = timestamp
                            entry[3] = key[1]
                        else:
                            stats.other_ids += 1
                        if not fits:  # a response nobody asked for (now)
                            frame = decoder._unattributed({
                                "timestamp": timestamp, "time": timestamp - t0,
                                "arbitration_id": arbitration_id, "data": key[1]})
                    if frame is None and rep is not None and len(data) <= 8:
                        stats.by_function[rep[2]] += 1
                        if rep[7]:
                            stats.failures += 1
                        if rep[3]:
                            t = timestamp - t0
                            if as_json:
                                j = rep[5]
                                fixed = f"{t:.6f}"  # json_times(t), inline
                                short = fixed.rstrip("0")
                                if short[-1] == "." or not 1e-4 <= t < 1e9:
                                    short = json_times(t)[1]
                                kind_key = (msg.dlc, msg.channel)
                                kind = kinds.get(kind_key)
                                if kind is None:
                                    kind = kinds[kind_key] = base_kind(*kind_key)
                                append(f'{{"timestamp": {timestamp!r}, "time": {short}{j[1]}'
                                       f'{fixed:>11}{j[2]}{kind}')
                            elif as_bytes:
                                append(b"%11.6f  %b" % (t, rep[6]))
                            else:
                                append(f"{t:11.6f}  {rep[4]}")
                            if len(parts) >= CHUNK:
                                self._chunk_full()
                        continue
                if frame is None:
                    managed_at_decode = managed
                    if recorder is not None:
                        recorder.write_message(msg)
                    frame = decode(msg)
                    if not t0_known and decoder.t0 is not None:
                        t0, t0_known = decoder.t0, True
                if frame.error is not None and on_error is not None:
                    on_error(frame)
                shown = show is None or show(frame)
                if shown:
                    cached_head = frame.head
                    # A line composed for one frame only (a foreign capture's extended or
                    # error frame) is not worth caching the JSON record of.
                    if not cached_head or (as_json and foreign):
                        if as_json:
                            self.json.write_to(parts, frame, msg)  # type: ignore[union-attr]
                        elif as_bytes:
                            append(frame.line.encode())
                        else:
                            append(frame.line)
                    elif as_json:
                        j = json_cache.get(id(cached_head))
                        if j is None or j[0] is not cached_head:
                            if len(json_cache) >= CACHE_SIZE:
                                json_cache.clear()
                            j = json_cache[id(cached_head)] = self._json_parts(frame)
                        fixed, short = json_times(frame.time)
                        append(f'{{"timestamp": {frame.timestamp!r}, "time": '
                               f'{short}{j[1]}{fixed:>11}{j[2]}"{kind_json(msg)}}}')
                    elif as_bytes:
                        append(b"%11.6f  %b" % (frame.time, cached_head.encode()))
                    else:
                        append(f"{frame.time:11.6f}  {cached_head}")
                    if len(parts) >= CHUNK:
                        self._chunk_full()
                if self._version != decoder.version:
                    heads.clear()
                    repeats.clear()
                    self._version = decoder.version
                    t0 = decoder.t0 or 0.0
                elif frame.direction == CHANNEL_DATA and frame.message is None:
                    heads[arbitration_id] = self._head(frame, shown)
                elif foreign and key is not None and len(key[1]) <= 8:
                    heads[arbitration_id] = self._plain_head(frame, shown)
                elif key is not None and frame.head and frame.message is not None:
                    again = decoder.repeatable(*key)
                    if again is frame.message:
                        if len(repeats) >= CACHE_SIZE:
                            repeats.clear()
                        repeats[key] = (again, stats.by_id.get(arbitration_id),
                                        frame.function, shown, frame.head,
                                        self._json_parts(frame) if as_json else None,
                                        frame.head.encode(), frame.response == _FAILURE)
        finally:
            if fast or ids:
                settle()

    @staticmethod
    def _json_parts(frame: DecodedFrame) -> tuple[str, str, str]:
        """A cached frame's JSON record around its times: the same for every frame that
        shares its text (``frame.head``)."""
        record = frame_json(frame)
        time_text = f"{frame.time:11.6f}"
        start = record.index(', "arbitration_id": ')
        end = record.rindex('"text": "') + len('"text": "')
        assert record[end:end + len(time_text)] == time_text
        return frame.head, record[start:end], record[end + len(time_text):-2]

    def _plain_head(self, frame: DecodedFrame, shown: bool) -> tuple[Any, ...]:
        """What every frame of ``frame``'s identifier shares in a foreign capture (plain
        CAN: ``_head``'s parts for a line ``P?  0x123 not PDCP  [123] <data>``)."""
        arbitration_id = frame.arbitration_id
        head = f"P?  0x{arbitration_id:03X} {NOT_PDCP}  [{arbitration_id:03X}] "
        if not frame.text_head.startswith(head):  # pragma: no cover - the decoder's _raw
            raise RuntimeError(f"unexpected plain line {frame.text_head!r}")
        entry = self.decoder.stats.by_id.get(arbitration_id)
        parts = None
        if self.json is not None:
            parts = (f', "arbitration_id": {arbitration_id}, "data": "',
                     f'", "direction": "", "priority": null, "node_id": null, "function": '
                     f'{json_str(NOT_PDCP)}, "fields": "[{arbitration_id:03X}] ',
                     '", "response": null, "error": null, "link": null, "text": "',
                     json_str("  " + head)[1:-1])
        return entry, shown, head, parts, head.encode()

    def _head(self, frame: DecodedFrame, shown: bool) -> tuple[Any, ...]:
        """What every channel data frame of ``frame``'s identifier shares."""
        arbitration_id = frame.arbitration_id
        texts = self.decoder.channel_texts(arbitration_id)
        if texts is None:  # pragma: no cover - decode_message just cached it
            raise RuntimeError(f"no channel texts for 0x{arbitration_id:03X}")
        link, fields, head = texts
        entry = self.decoder.stats.by_id.get(arbitration_id)
        parts = None
        if self.json is not None:
            parts = (f', "arbitration_id": {arbitration_id}, "data": "',
                     f'", "direction": {json_str(CHANNEL_DATA)}, "priority": {frame.priority}, '
                     f'"node_id": {frame.node_id}, "function": {json_str(_CHANNEL_DATA)}, '
                     f'"fields": {json_str(fields)[:-1]}',
                     f'", "response": null, "error": null, "link": {link_json(link)}, '
                     '"text": "',
                     json_str("  " + head)[1:-1])
        return entry, shown, head, parts, head.encode()
