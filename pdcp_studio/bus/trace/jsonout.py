"""Decoded frames as JSON records, written as one list that grows as frames come.

``frame_json`` writes the record ``DecodedFrame.as_json()`` describes without building the
dict: on a saturated bus the monitor's ``--json`` output is its hot path.
"""

from __future__ import annotations

import json
import os
from typing import Any

from pdcp_studio.bus.trace.frames import CACHE_SIZE, DecodedFrame, ref_json

json_str = json.encoder.encode_basestring_ascii
#: python-can's frame-kind fields of a classical base data frame, up to its DLC's value.
BASE_KIND = (', "is_extended_id": false, "is_remote_frame": false, "is_error_frame": false, '
             '"is_fd": false, "dlc": ')


def channel_json(channel: Any) -> str:
    """A frame's python-can ``channel`` as JSON (a number, a name or null)."""
    if channel is None or isinstance(channel, bool):
        return "null" if channel is None else str(channel).lower()
    if isinstance(channel, int):
        return str(channel)
    return json_str(str(channel))


def base_kind(dlc: int, channel: Any) -> str:
    """The end of a classical base data frame's record: the text's closing quote, its kind
    fields, the record's closing brace (what ``kind_json`` adds, for such a frame)."""
    return f'"{BASE_KIND}{int(dlc)}, "channel": {channel_json(channel)}}}'


def kind_json(msg: Any) -> str:
    """python-can's frame-kind fields of ``msg``, as the end of a JSON record ("" when
    there is no message)."""
    if msg is None:
        return ""
    return (f', "is_extended_id": {"true" if msg.is_extended_id else "false"}, '
            f'"is_remote_frame": {"true" if msg.is_remote_frame else "false"}, '
            f'"is_error_frame": {"true" if msg.is_error_frame else "false"}, '
            f'"is_fd": {"true" if msg.is_fd else "false"}, "dlc": {int(msg.dlc)}, '
            f'"channel": {channel_json(msg.channel)}')


def link_json(link: Any) -> str:
    return json.dumps({"output": ref_json(link[0]), "inputs": [ref_json(r) for r in link[1]]})


def frame_json(frame: DecodedFrame, links: dict[int, tuple[Any, str]] | None = None,
               msg: Any = None) -> str:
    """``json.dumps(frame.as_json())`` without building the dict (a monitor's hot path);
    with ``msg`` (the python-can frame) its kind fields follow (``kind_json``).

    ``links`` (a dict the caller keeps) remembers the JSON of link objects already seen:
    the decoder hands out the same link object for every frame of an output.
    """
    link = frame.link
    if link is None:
        link_text = "null"
    elif links is None:
        link_text = link_json(link)
    else:
        known = links.get(id(link))
        if known is None or known[0] is not link:
            if len(links) >= CACHE_SIZE:
                links.clear()
            known = links[id(link)] = (link, link_json(link))
        link_text = known[1]
    return (f'{{"timestamp": {frame.timestamp!r}, "time": {round(frame.time, 6)!r}, '
            f'"arbitration_id": {frame.arbitration_id}, "data": "{frame.data.hex()}", '
            f'"direction": {json_str(frame.direction)}, '
            f'"priority": {"null" if frame.priority is None else frame.priority}, '
            f'"node_id": {"null" if frame.node_id is None else frame.node_id}, '
            f'"function": {json_str(frame.function)}, "fields": {json_str(frame.fields)}, '
            f'"response": {"null" if frame.response is None else json_str(frame.response)}, '
            f'"error": {"null" if frame.error is None else json_str(frame.error)}, '
            f'"link": {link_text}, "text": {json_str(frame.line)}{kind_json(msg)}}}')


def utf8_buffer(out: Any) -> Any:
    """The byte buffer under a UTF-8 text stream (sys.stdout), else None: text written
    there as ``str.encode()`` reads exactly as if the stream had encoded it (and where
    a text stream writes "\\n" as it is: not on Windows)."""
    import codecs

    if os.linesep != "\n":
        return None
    encoding = getattr(out, "encoding", None)
    buffer = getattr(out, "buffer", None)
    if buffer is None or not isinstance(encoding, str):
        return None
    try:
        utf8 = codecs.lookup(encoding).name == "utf-8"
    except LookupError:
        return None
    return buffer if utf8 and getattr(out, "errors", "strict") == "strict" else None


class JsonFrameWriter:
    """Writes one JSON document ``{"frames": [...], "summary": {...}}`` as frames come:
    memory stays flat for any length.

    Nothing is written before the first frame (so a command that fails first prints
    nothing); ``close(summary)`` ends the list and adds the summary — also after a failure,
    so stdout stays one JSON document.
    """

    def __init__(self, stream: Any) -> None:
        self.stream, self.count = stream, 0
        self._links: dict[int, tuple[Any, str]] = {}
        #: The records go to the stream's byte buffer when it has one that encodes as
        #: UTF-8 (sys.stdout): a chunk of records is hundreds of kilobytes, and the text
        #: layer copies it twice more than ``str.encode`` does.
        self._buffer = utf8_buffer(stream)

    def write(self, frame: DecodedFrame, msg: Any = None) -> None:
        self.write_records([frame_json(frame, self._links, msg)])

    def write_to(self, records: list[str], frame: DecodedFrame, msg: Any = None) -> None:
        """Append ``frame``'s record to ``records`` (to be written by ``write_records``)."""
        records.append(frame_json(frame, self._links, msg))

    def write_records(self, records: list[str]) -> None:
        """Write records made by ``write_to`` or ``frame_json``, in order."""
        if records:
            head = '{"frames": [\n' if self.count == 0 else ",\n"
            buffer = self._buffer
            if buffer is not None:
                self.stream.flush()  # what was written as text first
                buffer.write(head.encode())
                buffer.write(",\n".join(records).encode())
            else:
                self.stream.write(head)
                self.stream.write(",\n".join(records))
            self.count += len(records)

    def close(self, summary: Any = None) -> None:
        end = json.dumps(summary if summary is not None else {})
        self.stream.write(f'\n], "summary": {end}}}\n' if self.count
                          else f'{{"frames": [], "summary": {end}}}\n')

