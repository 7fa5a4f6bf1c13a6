"""Synthetic traces for the trace tests: a million frames built column-wise in milliseconds."""

from __future__ import annotations

import numpy as np

from pdcp_studio.app.trace.store import CHUNK_ROWS, F_CHANNEL, F_HEX, Chunk, FrameStore
from pdcp_studio.protocol.codes import FunctionCode

#: The one odd frame, near the end of every synthetic trace (search finds it).
NEEDLE_ID = 0x123
NEEDLE_DATA = bytes.fromhex("DEADBEEF")
BEACON_EVERY = 100  # node 5 beacons; the rest is channel data of node 6
BROADCAST_EVERY = 1000  # BA→all (a release to every node)


def synthetic_store(n: int, rate_hz: float = 8000.0, t0: float = 1000.0,
                    store: FrameStore | None = None, distinct_every: int = 0) -> FrameStore:
    """``n`` frames at ``rate_hz``: channel data of node 6 (a 16-bit counter), a beacon of
    node 5 every ``BEACON_EVERY`` frames, a broadcast every ``BROADCAST_EVERY``, and one
    frame with ID ``NEEDLE_ID`` and data ``NEEDLE_DATA`` 17 frames from the end. Appended
    to ``store`` (a new one by default); with ``distinct_every`` every such channel-data
    frame gets a text of its own (``… value <frame number>``), as parameter values do."""
    store = FrameStore() if store is None else store
    t = store.tables
    beacon_text = t.texts.add("P0  #5→BA Device Beacon")
    data_text = t.texts.add("P0  #6 data Channel data  Hand output 1 → Control unit input 1")
    release_text = t.texts.add("P0  BA→all Release Device")
    needle_text = t.texts.add("P0  0x123 undecodable: not a PDCP identifier")
    beacon_fn = t.function_by_byte[FunctionCode.BEACON]
    release_fn = t.function_by_byte[FunctionCode.RELEASE]
    needle_at = n - 17
    for start in range(0, n, CHUNK_ROWS):
        k = min(CHUNK_ROWS, n - start)
        idx = np.arange(start, start + k)
        beacon = idx % BEACON_EVERY == 0
        broadcast = idx % BROADCAST_EVERY == 1
        data = np.zeros((k, 8), dtype=np.uint8)
        data[:, 0] = idx & 0xFF
        data[:, 1] = (idx >> 8) & 0xFF
        data[beacon, 0] = FunctionCode.BEACON
        data[broadcast, 0] = FunctionCode.RELEASE
        aid = np.full(k, 6, dtype=np.uint32)
        aid[beacon] = 5
        aid[broadcast] = 0x100
        dlc = np.full(k, 2, dtype=np.uint8)
        dlc[beacon | broadcast] = 1
        func = np.full(k, t.channel_data, dtype=np.uint16)
        func[beacon] = beacon_fn
        func[broadcast] = release_fn
        text = np.full(k, data_text, dtype=np.uint32)
        text[beacon] = beacon_text
        text[broadcast] = release_text
        if distinct_every:
            own = np.flatnonzero((idx % distinct_every == 2) & ~beacon & ~broadcast)
            add = t.texts.add
            text[own] = [add(f"P0  #6 data Channel data  value {i}") for i in (own + start)]
        flags = np.full(k, F_CHANNEL | F_HEX, dtype=np.uint8)
        flags[beacon | broadcast] = 0
        if start <= needle_at < start + k:
            j = needle_at - start
            aid[j], dlc[j], text[j], flags[j] = NEEDLE_ID, 4, needle_text, 0
            data[j, :4] = np.frombuffer(NEEDLE_DATA, dtype=np.uint8)
            func[j] = t.function_by_byte[0xDE]
        store.append(Chunk(t0 + idx / rate_hz, aid, dlc, data, func, text, flags))
    return store
