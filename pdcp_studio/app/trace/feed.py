"""The live frames: queued as the session reports them, turned into the ring's column chunks
and per-ID statistics a batch at a time. Qt-free.

``add`` only queues (the session decoded the frames off the GUI thread); the dock's timer
calls ``ingest`` with a bounded slice, so a backlog is taken with the window's other events
in between.
"""

from __future__ import annotations

import shutil
import tempfile
import weakref
from collections.abc import Callable, Iterable
from typing import Any

from pdcp_studio.app.trace.disk import FileTexts
from pdcp_studio.app.trace.store import ChunkBuilder, FrameStore, IdStats, Tables, line_head


def live_tables(owner: object) -> Tables:
    """String tables whose decoded texts are in a temporary folder removed with ``owner``."""
    folder = tempfile.mkdtemp(prefix="pdcp-live-")
    texts = FileTexts(folder)
    weakref.finalize(owner, _remove_texts, texts, folder)
    return Tables(texts)


def _remove_texts(texts: FileTexts, folder: str) -> None:
    texts.close()
    shutil.rmtree(folder, ignore_errors=True)


class LiveFeed:
    """The live ring (``store``, bounded to ``capacity`` frames, its texts on disk until
    ``owner`` goes), its statistics, the frames queued for it, and the link map the
    session's frames taught (``links``).

    ``taking(frames)`` sees every batch before it becomes rows (to record it)."""

    def __init__(self, owner: object, capacity: int,
                 taking: Callable[[list[Any]], None]) -> None:
        # The ring is bounded by ``capacity``; its decoded texts, which a long session keeps
        # adding, are on disk (a bounded window of them in memory), removed with ``owner``.
        tables = live_tables(owner)
        self.store = FrameStore(tables, max_rows=capacity)
        self.stats = IdStats(tables)
        self._builder = ChunkBuilder(tables)
        self._taking = taking
        self.incoming: list[Any] = []
        self.frames_seen = 0  # live frames counted since the last clear, kept or not
        #: node ID → (output, inputs): the system's links, and "node N" for outputs only
        #: the session's decoder named
        self.links: dict[int, tuple[Any, tuple[Any, ...]]] = {}

    @property
    def channel_nodes(self) -> set[int]:
        """Node IDs of output channels: their frames are channel data."""
        return self._builder.channel_nodes

    @channel_nodes.setter
    def channel_nodes(self, nodes: Iterable[int]) -> None:
        self._builder.channel_nodes = set(nodes)

    def add(self, frames: Iterable[Any]) -> None:
        """Queue a batch of ``FrameSeen`` (taken by the next ``ingest``)."""
        self.incoming.extend(frames)

    def ingest(self, limit: int | None = None) -> None:
        """Turn the queued frames (at most ``limit`` of them) into rows and statistics."""
        if not self.incoming:
            return
        if limit is not None and len(self.incoming) > limit:
            frames, self.incoming = self.incoming[:limit], self.incoming[limit:]
        else:
            frames, self.incoming = self.incoming, []
        self._taking(frames)
        add = self._builder.add
        for f in frames:
            add(f.timestamp, f.arbitration_id, f.data if type(f.data) is bytes else bytes(f.data),
                line_head(f.text or ""))
        chunk = self._builder.take()
        for node in self._builder.channel_nodes - self.links.keys():
            self.links[node] = (f"node {node}", ())  # named by the session's decoder
        self.frames_seen += len(frames)
        self.stats.update(chunk)
        self.store.append(chunk)

    def learn_output(self, node: int, link: tuple[Any, tuple[Any, ...]]) -> None:
        """Frames from ``node`` are channel data of this output and its inputs."""
        self._builder.channel_nodes.add(node)
        self.links[node] = link

    def drop(self) -> None:
        """Forget the queued frames, the ring and its statistics."""
        self.incoming.clear()
        self.store.clear()
        self.stats.clear()

    def forget_links(self) -> None:
        """Node IDs were reassigned (a reset, a hot-swap): the link map no longer holds."""
        self._builder.channel_nodes.clear()
        self.links.clear()
