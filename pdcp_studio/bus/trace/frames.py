"""One decoded frame as the monitor shows it, and the words its direction and function use.

A named tuple: immutable, and cheap to build for every frame of a saturated bus.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

from pdcp_studio.model.refs import ChannelRef

TO_BA, FROM_BA, CHANNEL_DATA = "device→BA", "BA→device", "channel data"
UNDECODABLE = "undecodable"
UNATTRIBUTED = "unattributed"
NOT_PDCP = "not PDCP"
#: node ID → (output channel, the inputs linked to it); the caller may keep updating it.
LinkMap = Mapping[int, tuple[ChannelRef, Sequence[ChannelRef]]]
#: An output and the inputs it feeds, as a frame names them (a ``ChannelRef``, or
#: ``node N#i`` for a channel of a device the monitor knows only by node ID).
Link = tuple[ChannelRef | str, tuple[ChannelRef | str, ...]]
#: Decoded messages, descriptions and texts kept for frames seen again (cleared when full).
CACHE_SIZE = 8192
new_frame = tuple.__new__  # builds a DecodedFrame from a full tuple, skipping __new__'s keywords


class DecodedFrame(NamedTuple):
    """One frame as the monitor shows it; ``line`` is the text, ``as_json()`` the record.

    A named tuple: immutable, and cheap to build for every frame of a saturated bus.
    """

    timestamp: float
    time: float  # seconds since the decoder's first frame
    arbitration_id: int
    data: bytes
    direction: str  # TO_BA, FROM_BA, CHANNEL_DATA or "" when the identifier is not PDCP's
    priority: int | None
    node_id: int | None
    function: str  # a function title, "Channel data" or UNDECODABLE
    fields: str
    error: str | None = None  # why it is undecodable, or a bulk-transfer fault
    response: str | None = None  # the response code's name
    link: Link | None = None
    message: Any = None
    #: The line without its time, when the decoder composed it already.
    head: str = ""

    @property
    def who(self) -> str:
        if self.node_id is None:
            return f"0x{self.arbitration_id:03X}"
        if self.direction == FROM_BA:
            return "BA→all" if self.node_id == 0 else f"BA→#{self.node_id}"
        return f"#{self.node_id} data" if self.direction == CHANNEL_DATA else f"#{self.node_id}→BA"

    @property
    def line(self) -> str:
        return f"{self.time:11.6f}  {self.head or self.text_head}"

    @property
    def text_head(self) -> str:
        """The line after its time."""
        prio = "P?" if self.priority is None else f"P{self.priority}"
        text = f"{prio}  {self.who} {self.function}"
        return f"{text}  {self.fields}" if self.fields else text

    def __str__(self) -> str:
        return self.line

    def as_json(self) -> dict[str, Any]:
        link = None if self.link is None else {
            "output": ref_json(self.link[0]), "inputs": [ref_json(r) for r in self.link[1]]}
        return {"timestamp": self.timestamp, "time": round(self.time, 6),
                "arbitration_id": self.arbitration_id, "data": self.data.hex(),
                "direction": self.direction, "priority": self.priority,
                "node_id": self.node_id, "function": self.function, "fields": self.fields,
                "response": self.response, "error": self.error, "link": link,
                "text": self.line}


def ref_json(ref: ChannelRef | str) -> Any:
    """A channel as a frame's or a node map's JSON names it."""
    return ref.as_json() if isinstance(ref, ChannelRef) else ref
