"""The bus monitor as one import: the decoder, its frames and statistics, the JSON output,
and reading, writing and replaying captures.

Each lives in a module of its own in this room (``decoder``, ``frames``, ``stats``,
``jsonout``, ``reader`` (every capture, by content), ``capture``, ``recorder``, ``nodemap``,
``inference`` (the node map from traffic), ``replay``; ``blf`` reads BLF, ``pump`` is the
CLI's hot loop); this module names them for callers that want the monitor whole.
Importing it stays cheap: python-can loads only when a capture is read or written.
"""

from __future__ import annotations

from pdcp_studio.bus.trace.decoder import FrameDecoder
from pdcp_studio.bus.trace.files.capture import (
    CAPTURE_SUFFIXES,
    PARTIAL_SUFFIX,
    CaptureError,
    CaptureWriteError,
    open_capture,
    read_capture,
)
from pdcp_studio.bus.trace.files.nodemap import (
    NODE_MAP_FORMAT,
    NODE_MAP_SUFFIX,
    read_node_map,
    write_node_map,
)
from pdcp_studio.bus.trace.files.reader import CaptureReader
from pdcp_studio.bus.trace.files.recorder import MAX_LOG_CHANNEL, Recorder
from pdcp_studio.bus.trace.files.replay import CaptureReplay, node_map_words, replay
from pdcp_studio.bus.trace.frames import (
    CACHE_SIZE,
    CHANNEL_DATA,
    FROM_BA,
    NOT_PDCP,
    TO_BA,
    UNATTRIBUTED,
    UNDECODABLE,
    DecodedFrame,
    LinkMap,
)
from pdcp_studio.bus.trace.inference import TrafficLearner
from pdcp_studio.bus.trace.jsonout import JsonFrameWriter, frame_json, utf8_buffer
from pdcp_studio.bus.trace.stats import (
    EXTENDED_KEY,
    MAX_TRACKED_IDS,
    NOT_PDCP_MIN_FRAMES,
    MonitorStats,
)

__all__ = [
    "CACHE_SIZE", "CAPTURE_SUFFIXES", "CHANNEL_DATA", "EXTENDED_KEY", "FROM_BA",
    "MAX_LOG_CHANNEL", "MAX_TRACKED_IDS", "NODE_MAP_FORMAT", "NODE_MAP_SUFFIX", "NOT_PDCP",
    "NOT_PDCP_MIN_FRAMES", "PARTIAL_SUFFIX", "TO_BA", "UNATTRIBUTED", "UNDECODABLE",
    "CaptureError", "CaptureReader", "CaptureReplay", "CaptureWriteError", "DecodedFrame",
    "FrameDecoder", "JsonFrameWriter", "LinkMap", "MonitorStats", "Recorder",
    "TrafficLearner", "frame_json", "node_map_words", "open_capture", "read_capture",
    "read_node_map", "replay", "utf8_buffer", "write_node_map",
]
