"""Replay: a capture opened for decoding as the monitor showed it live — the CLI's
``monitor --replay`` and the app's trace read captures through ``CaptureReplay``.

Opening a capture prepares its decoder before the first frame is decoded: the node map
saved beside it (``nodemap.py``) when there is one, else what its first frames teach
(``inference.py``: a capture from another tool, or one that starts mid-session); and
whether it is PDCP's traffic at all (a foreign capture is shown as plain CAN, whatever its
length). Then the frames come straight from the reader (``reader.py``), which says where
a damaged capture was cut (``truncated``, ``damage``).
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from pdcp_studio.bus.trace.decoder import FrameDecoder
from pdcp_studio.bus.trace.frames import DecodedFrame

#: Frames read ahead to learn the node map and tell a PDCP capture from another bus's.
PROBE_FRAMES = 2000


def _probe(head: list[Any], decoder: FrameDecoder) -> FrameDecoder:
    """A copy of what ``decoder`` knows, having decoded ``head``."""
    probe = FrameDecoder(dict(decoder.links))
    probe.meter_on = False
    probe.context_checked = decoder.context_checked
    probe.load_node_map(decoder.node_map())
    probe.heard.update(decoder.heard)
    for msg in head:
        probe.decode_message(msg)
    return probe


def _foreign(probe: FrameDecoder, count: int) -> bool:
    from pdcp_studio.bus.trace.frames import UNATTRIBUTED
    from pdcp_studio.bus.trace.stats import NOT_PDCP_MIN_FRAMES

    stats = probe.stats
    if not count or stats.in_context:
        return False
    shown_as_pdcp = stats.frames - stats.undecodable - stats.by_function[UNATTRIBUTED]
    return count >= NOT_PDCP_MIN_FRAMES or shown_as_pdcp == 0


def is_foreign(head: list[Any], decoder: FrameDecoder) -> bool:
    """True when ``head`` (a capture's first frames) holds frames and none fits PDCP in
    context for what ``decoder`` knows (its node map, its inferences). A short capture
    (under ``NOT_PDCP_MIN_FRAMES``) has few chances to show context: there one frame shown
    as a PDCP message (a device's beacon, a bind request) is enough."""
    return bool(head) and _foreign(_probe(head, decoder), len(head))


def prepare(decoder: FrameDecoder, head: list[Any], *, learn: bool = True) -> None:
    """Ready ``decoder`` for a capture whose first frames are ``head``: learn devices and
    channels from them (``learn``: the capture has no saved node map), and show it as plain
    CAN if it is not PDCP's."""
    from pdcp_studio.bus.trace.knowledge import INFERRED

    if learn:
        decoder.learn_from_traffic(head)
    probe = _probe(head, decoder) if head else None
    decoder.foreign = probe is not None and _foreign(probe, len(head))
    if decoder.foreign:
        decoder.learner = None
    elif learn and probe is not None and probe.outputs and INFERRED not in \
            probe.outputs.values():
        # The capture's set-up explains every channel its first frames show (it writes
        # their Channel Node Ids before they stream): the decoder learns them from it, and
        # a node heard later is more likely a stray frame than a channel set up unseen.
        decoder.learner = None
        for node in [n for n, owner in decoder.outputs.items() if owner == INFERRED]:
            del decoder.outputs[node]
        decoder.relearn()


class CaptureReplay:
    """A capture opened for decoding (CaptureError if it cannot be read).

    ``frames``: the python-can frames to feed ``decoder`` (or iterate ``decoded()``);
    ``reader``: its ``CaptureReader`` (``format``, ``truncated``, ``damage`` once read);
    ``node_map_source``: the saved node map's path, or None (learned from the traffic).
    ``cancel`` (a ``threading.Event``): once set, the next read raises
    ``reader.ReadCancelled`` (the app's Stop button).
    """

    def __init__(self, path: str | Path, decoder: FrameDecoder | None = None, *,
                 plain_frames: bool = True, cancel: Any = None) -> None:
        from pdcp_studio.bus.trace.files.capture import CaptureError
        from pdcp_studio.bus.trace.files.nodemap import NODE_MAP_SUFFIX, read_node_map
        from pdcp_studio.bus.trace.files.reader import CaptureReader

        self.decoder = decoder if decoder is not None else FrameDecoder()
        self.decoder.context_checked = True  # a capture may hold another bus's frames
        node_map = read_node_map(path)
        self.node_map_source: str | None = None
        if node_map is not None:
            where = f"{path}{NODE_MAP_SUFFIX}"
            try:
                self.decoder.load_node_map(node_map, where)
            except ValueError as err:
                raise CaptureError(where, str(err).removeprefix(f"{where}: ")) from err
            self.node_map_source = where
        self.reader = CaptureReader(path, plain_frames=plain_frames, cancel=cancel)
        rest = iter(self.reader)
        try:
            head = list(itertools.islice(rest, PROBE_FRAMES))
            prepare(self.decoder, head, learn=node_map is None)
        except BaseException:
            self.reader.close()
            raise
        #: The rest straight from the reader: no generator between it and the caller.
        self.frames: Iterator[Any] = itertools.chain(head, rest)

    def decoded(self) -> Iterator[DecodedFrame]:
        decode = self.decoder.decode_message
        for msg in self.frames:
            yield decode(msg)

    def node_map_words(self) -> str | None:
        return node_map_words(self.decoder, self.node_map_source)

    def close(self) -> None:
        self.reader.close()

    def __enter__(self) -> CaptureReplay:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def replay(path: str | Path, decoder: FrameDecoder | None = None) -> Iterator[DecodedFrame]:
    """Decode a capture frame by frame (pass a decoder to read its statistics afterwards);
    a capture cut short gives its frames up to the cut, then CaptureError says where."""
    from pdcp_studio.bus.trace.files.capture import CaptureError

    with CaptureReplay(path, decoder) as opened:
        yield from opened.decoded()
        if opened.reader.damage is not None:
            raise CaptureError(path, opened.reader.damage.split(": ", 1)[1])


def node_map_words(decoder: FrameDecoder, source: str | None) -> str | None:
    """Where the decoder's node map came from, as the summary says it ("node map: from
    FILE.nodemap.json" / "from the capture's set-up: …" / "inferred from traffic: …");
    None for a foreign capture or no frames."""
    if decoder.foreign or not decoder.stats.frames:
        return None
    if source is not None:
        return f"node map: from {source}"
    from pdcp_studio.bus.trace.knowledge import INFERRED

    inferred = sum(1 for owner in decoder.outputs.values() if owner == INFERRED)
    set_up = len(decoder.outputs) - inferred
    learner = decoder.learner
    if inferred and learner is not None:
        devices = len(learner.devices | set(decoder.devices))
        also = (f" ({_count(len(decoder.devices), 'device')} and "
                f"{_count(set_up, 'channel')} from the capture's set-up)"
                if decoder.devices or set_up else "")
        return (f"node map: inferred from traffic: {_count(devices, 'device')}, "
                f"{_count(inferred + set_up, 'channel')}{also}")
    if decoder.devices or set_up:
        return (f"node map: from the capture's set-up: "
                f"{_count(len(decoder.devices), 'device')}, {_count(set_up, 'channel')}")
    if decoder.links:
        return "node map: from the links given"
    return "node map: none (no set-up in the capture, nothing to infer from)"

def _count(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"

