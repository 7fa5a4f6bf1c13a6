"""Replay: a capture decoded frame by frame, as the monitor showed it live."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from pdcp_studio.bus.trace.capture import read_capture
from pdcp_studio.bus.trace.decoder import FrameDecoder
from pdcp_studio.bus.trace.frames import DecodedFrame


def replay(path: str | Path, decoder: FrameDecoder | None = None) -> Iterator[DecodedFrame]:
    """Decode a capture frame by frame (pass a decoder to read its statistics afterwards)."""
    decoder = decoder if decoder is not None else FrameDecoder()
    for msg in read_capture(path, plain_frames=True):
        yield decoder.decode_message(msg)
