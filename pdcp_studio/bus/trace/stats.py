"""What the monitor counts: frames by function and by identifier, errors, bus time, and
whether the traffic is PDCP's at all."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from typing import Any

from pdcp_studio.bus.trace.bustime import BusTimeMeter
from pdcp_studio.bus.trace.frames import NOT_PDCP

#: Per-ID statistics key extended identifiers above every base one.
EXTENDED_KEY = 1 << 29
#: Frames a capture needs, none of them PDCP's, before it is called ``not PDCP``.
NOT_PDCP_MIN_FRAMES = 20

#: Identifiers the per-ID statistics follow one by one; frames of any others are counted
#: together (a base bus has 2,048 identifiers, extended frames could bring 2^29).
MAX_TRACKED_IDS = 4096


@dataclass
class MonitorStats:
    """Frames by function and by identifier, errors, and the bus time they took.

    Every structure is bounded whatever the number of frames: counters by function name
    (a fixed vocabulary plus one entry per undecodable reason kind), per-ID entries up to
    ``MAX_TRACKED_IDS`` (``other_ids`` counts the rest).
    """

    frames: int = 0
    by_function: Counter[str] = field(default_factory=Counter)
    undecodable: int = 0
    failures: int = 0  # responses with code 0 (failure)
    bulk_errors: int = 0
    meter: BusTimeMeter = field(default_factory=BusTimeMeter)
    #: arbitration ID (extended ones + 0x20000000) → [count, first time, last time, last data]
    by_id: dict[int, list[Any]] = field(default_factory=dict)
    other_ids: int = 0
    #: Frames that fit PDCP in context (a response to its request, a completed bulk packet,
    #: channel data of a known output): what tells a PDCP bus from another one.
    in_context: int = 0

    @property
    def errors(self) -> int:
        return self.undecodable + self.failures + self.bulk_errors

    def note_id(self, key: int, timestamp: float, data: bytes) -> None:
        entry = self.by_id.get(key)
        if entry is not None:
            entry[0] += 1
            entry[2] = timestamp
            entry[3] = data
        elif len(self.by_id) < MAX_TRACKED_IDS:
            self.by_id[key] = [1, timestamp, timestamp, data]
        else:
            self.other_ids += 1

    def id_stats(self) -> list[dict[str, Any]]:
        """Per identifier: count, mean period in seconds (None below two frames), last data."""
        rows = []
        for key, (count, first, last, data) in sorted(self.by_id.items()):
            extended = key >= EXTENDED_KEY
            rows.append({"arbitration_id": key - EXTENDED_KEY if extended else key,
                         "extended": extended, "count": count,
                         "period_s": (last - first) / (count - 1) if count > 1 else None,
                         "last_data": data.hex()})
        return rows

    def span_s(self) -> float:
        """The capture's real span: its earliest frame to its latest, of every kind the
        per-ID statistics follow (the bus-time meter sees base frames only)."""
        meter = self.meter
        firsts = [e[1] for e in self.by_id.values()]
        lasts = [e[2] for e in self.by_id.values()]
        if meter.first_timestamp is not None and meter.last_timestamp is not None:
            firsts.append(meter.first_timestamp)
            lasts.append(meter.last_timestamp)
        return max(0.0, max(lasts) - min(firsts)) if firsts else 0.0

    def load(self, elapsed_s: float | None = None) -> float | None:
        """The bus load over ``elapsed_s`` (default: the real span); None when there is no
        time to compare with or the timestamps are denser than the bit rate allows (then
        they are not a real bus's: no load is made up)."""
        span = self.span_s() if elapsed_s is None else elapsed_s
        if span <= 0:
            return None
        load = self.meter.bus_time_s / span
        return load if load <= 1.0 else None

    def verdict_word(self) -> str:
        """``pdcp``, ``not-pdcp`` or ``empty`` (contracts §2: the summary's verdict)."""
        if self.frames == 0:
            return "empty"
        return "not-pdcp" if self.verdict() == NOT_PDCP else "pdcp"

    def verdict(self) -> str | None:
        """``not PDCP`` when plenty of frames came and none of them fitted PDCP in context."""
        nothing_decoded = 0 < self.frames == self.undecodable  # a short foreign capture
        if self.by_function.get(NOT_PDCP) or (self.in_context == 0 and (
                self.frames >= NOT_PDCP_MIN_FRAMES or nothing_decoded)):
            return NOT_PDCP
        return None

    def as_json(self, elapsed_s: float | None = None) -> dict[str, Any]:
        return {"frames": self.frames, "by_function": dict(self.by_function.most_common()),
                "undecodable": self.undecodable, "failures": self.failures,
                "bulk_errors": self.bulk_errors, "bus_time_us": round(self.meter.bus_time_us, 1),
                "span_s": self.span_s() if elapsed_s is None else elapsed_s,
                "bus_load": self.load(elapsed_s), "verdict": self.verdict_word(),
                "ids": self.id_stats(), "other_ids": self.other_ids}

    def summary(self, elapsed_s: float | None = None, top_ids: int = 12) -> str:
        load = self.load(elapsed_s)
        span = self.span_s() if elapsed_s is None else elapsed_s
        dense = load is None and span > 0 and self.meter.bus_time_s > 0
        if self.frames == 0:
            head = "0 frames: empty (no frame to read)"
        elif self.verdict() == NOT_PDCP:
            head = (f"{self.frames} frames, {NOT_PDCP}: no frame fits PDCP's protocol "
                    "(a capture of another bus?), so none is counted as an error")
        else:
            head = (f"{self.frames} frames, {self.errors} errors ({self.undecodable} "
                    f"undecodable, {self.failures} failure responses, {self.bulk_errors} "
                    "bulk faults)")
        lines = [head, f"bus time {self.meter.bus_time_us / 1000:.3f} ms over {span:.3f} s"
                 + (f" (bus load {100 * load:.2f} %)" if load is not None else
                    " (no bus load: the timestamps are denser than the bit rate allows)"
                    if dense else "")]
        lines += [f"  {n:7d}  {name}" for name, n in self.by_function.most_common()]
        busiest = sorted(self.id_stats(), key=lambda r: -r["count"])[:top_ids]
        if busiest:
            lines.append(f"busiest of {len(self.by_id)} identifiers"
                         + (f" (+{self.other_ids} frames of others)" if self.other_ids else "")
                         + ": count, mean period, last data")
        for row in busiest:
            ident = (f"{row['arbitration_id']:08X}" if row["extended"]
                     else f"{row['arbitration_id']:03X}")
            period = ("-" if row["period_s"] is None
                      else f"{row['period_s'] * 1000:.3f} ms")
            lines.append(f"  {ident:>8}  {row['count']:7d}  {period:>12}  "
                         f"{row['last_data'].upper() or '(empty)'}")
        return "\n".join(lines)
