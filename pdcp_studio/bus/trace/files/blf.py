"""BLF captures read as python-can's ``BLFReader`` reads them, in about a quarter of its time.

A replay of a BLF capture spent most of its time in python-can's reader: for every object it
unpacks three structs, converts the time through ``Decimal`` and builds a ``can.Message``.
``FastBLFReader`` is that reader with its loop over a container's objects (``_parse_data``)
replaced; the file header and the objects split between two containers stay python-can's
own code. The loop over the file's containers (``_containers``) is python-can's, but inflates
each to at most ``MAX_CONTAINER`` bytes (python-can's inflates whatever a container holds: a
damaged or hostile file could take gigabytes). In the new loop over a container's objects:

- the most common object, a classical CAN frame (CAN_MESSAGE, CAN_MESSAGE2) with a
  version-1 header, is unpacked by one struct (python-can's three layouts in a row);
- its time is ``ticks / 100000`` (or ``/ 10**9``) plus the file's start: Python divides two
  integers correctly rounded, and ``float(Decimal(ticks) * Decimal("1e-5"))`` is the same
  correctly rounded quotient (the product of a 20-digit integer and 1e-5 is exact in
  Decimal's 28 digits), so the float is the same to the last bit;
- a data frame not marked extended becomes a ``PlainFrame``: the attributes of the
  ``can.Message`` python-can would build (``data`` as ``bytes``), without its constructor;
  ``to_message()`` builds that message (a recorder writes one);
- every other object (extended and remote frames, CAN FD, error frames, version-2 headers,
  types python-can skips) is read the way python-can's loop reads it, field by field;
- a container's frames come as one list, flattened in C by ``__iter__`` (``batches()``
  gives the lists), so no generator is resumed per frame.

The frames are python-can's, in the same order, with the same times
(``tests/bus/test_blf_read.py`` compares both readers on files python-can writes, on hand-built
object streams, with hypothesis, and on truncated and corrupted files). A damaged file gives
the frames python-can's reader gives and then fails where it fails, as a ``BLFParseError``
that adds to python-can's reason the byte of the file the reader had reached (a container
is read whole). An object declaring 0 bytes, which would keep python-can's loop running
forever, fails there.

It relies on ``BLFReader._parse_data`` and ``_parse_container`` (python-can 4.x);
``COMPATIBLE`` is False where python-can has neither, and the monitor then reads with
python-can's own reader.
"""

from __future__ import annotations

import struct
import zlib
from collections.abc import Iterator
from itertools import chain
from typing import Any

from can import Message
from can.io import blf
from can.io.blf import (
    CAN_ERROR_EXT,
    CAN_ERROR_EXT_STRUCT,
    CAN_FD_MESSAGE,
    CAN_FD_MESSAGE_64,
    CAN_FD_MSG_64_STRUCT,
    CAN_FD_MSG_STRUCT,
    CAN_MESSAGE,
    CAN_MESSAGE2,
    CAN_MSG_EXT,
    CAN_MSG_STRUCT,
    DIR,
    LOG_CONTAINER,
    LOG_CONTAINER_STRUCT,
    NO_COMPRESSION,
    OBJ_HEADER_BASE_STRUCT,
    OBJ_HEADER_V1_STRUCT,
    OBJ_HEADER_V2_STRUCT,
    REMOTE_FLAG,
    ZLIB_DEFLATE,
    BLFParseError,
    BLFReader,
)
from can.util import dlc2len

#: A version-1 object header and a classical CAN frame, as one struct: signature, header
#: size, header version, object size, object type | flags, client index, object version,
#: timestamp | channel, flags, dlc, arbitration id, data.
_V1_CAN_MSG = struct.Struct("<" + "".join(
    s.format.lstrip("<") for s in (OBJ_HEADER_BASE_STRUCT, OBJ_HEADER_V1_STRUCT, CAN_MSG_STRUCT)))
_ID_MASK = 0x1FFFFFFF
#: A container inflates to no more than this (python-can and Vector write 128 KiB ones):
#: a damaged or hostile one that says more is refused, not inflated into memory.
MAX_CONTAINER = 1 << 24
#: python-can's reader has the two methods this one builds on.
COMPATIBLE = all(callable(getattr(BLFReader, name, None))
                 for name in ("_parse_data", "_parse_container"))


class PlainFrame:
    """A classical data frame with an 11-bit identifier, read from a BLF capture: what
    the ``can.Message`` python-can's reader builds for it holds, as plain attributes."""

    __slots__ = ("arbitration_id", "channel", "data", "dlc", "is_rx", "timestamp")
    is_extended_id = False
    is_remote_frame = False
    is_error_frame = False
    is_fd = False
    bitrate_switch = False
    error_state_indicator = False
    timestamp: float
    arbitration_id: int
    data: bytes
    dlc: int
    channel: int
    is_rx: bool

    def to_message(self) -> Message:
        """The ``can.Message`` python-can's ``BLFReader`` yields for this frame."""
        return Message(timestamp=self.timestamp, arbitration_id=self.arbitration_id,
                       is_extended_id=False, is_remote_frame=False, is_rx=self.is_rx,
                       dlc=self.dlc, data=self.data, channel=self.channel)

    def __repr__(self) -> str:
        return repr(self.to_message())


class FastBLFReader(BLFReader):
    """python-can's ``BLFReader`` with a faster loop over each container's objects: yields
    a ``PlainFrame`` for each classical 11-bit data frame and a ``can.Message`` (as
    python-can's) for every other frame."""

    def __iter__(self) -> Iterator[Any]:  # type: ignore[override]
        return chain.from_iterable(self.batches())

    def batches(self) -> Iterator[list[Any]]:
        """The frames, a list per container (flattened in C by ``__iter__``: no generator
        resumed per frame). A damaged file raises ``BLFParseError`` naming how far into
        the file the reader had got, after the frames before the damage."""
        try:
            yield from self._containers()
        except (BLFParseError, struct.error, zlib.error) as err:
            where = "" if self.file.closed else f" (before byte {self.file.tell()})"
            raise BLFParseError(f"{err or type(err).__name__}{where}") from err

    def _containers(self) -> Iterator[list[Any]]:
        """python-can's ``BLFReader.__iter__`` (the objects of the file, containers
        inflated), with each container inflated to at most ``MAX_CONTAINER`` bytes."""
        read = self.file.read
        while True:
            data = read(OBJ_HEADER_BASE_STRUCT.size)
            if not data:
                break
            signature, _, _, obj_size, obj_type = OBJ_HEADER_BASE_STRUCT.unpack(data)
            if signature != b"LOBJ":
                raise BLFParseError()
            obj_data = read(obj_size - OBJ_HEADER_BASE_STRUCT.size)
            read(obj_size % 4)  # padding
            if obj_type != LOG_CONTAINER:
                continue
            method, _ = LOG_CONTAINER_STRUCT.unpack_from(obj_data)
            container_data = obj_data[LOG_CONTAINER_STRUCT.size:]
            if method == NO_COMPRESSION:
                data = container_data
            elif method == ZLIB_DEFLATE:
                inflater = zlib.decompressobj()
                data = inflater.decompress(container_data, MAX_CONTAINER)
                if inflater.unconsumed_tail:
                    raise BLFParseError(f"a container inflating to more than "
                                        f"{MAX_CONTAINER:,} bytes (damaged?)")
            else:
                blf.LOG.warning("Unknown compression method (%d)", method)
                continue
            yield from self._parse_container(data)  # type: ignore[misc]  # lists
        self.stop()

    def _parse_data(self, data: bytes) -> Iterator[list[Any]]:  # type: ignore[override]
        """The frames of ``data`` (one container, after the tail of the one before) as
        python-can's ``BLFReader._parse_data`` reads them, in one list; ``self._pos``:
        where the first object not read starts (it ends in the next container)."""
        unpack_v1_can = _V1_CAN_MSG.unpack_from
        unpack_base = OBJ_HEADER_BASE_STRUCT.unpack_from
        new = object.__new__
        frame_type = PlainFrame
        start_timestamp = self.start_timestamp
        max_pos = len(data)
        pos = start = 0
        frames: list[Any] = []
        append = frames.append
        try:
            while True:
                start = pos
                if pos + 48 <= max_pos:
                    (signature, _, header_version, obj_size, obj_type, flags, _, _, ticks,
                     channel, msg_flags, dlc, can_id, can_data) = unpack_v1_can(data, pos)
                    if (signature == b"LOBJ" and header_version == 1 and obj_size
                            and (obj_type == CAN_MESSAGE or obj_type == CAN_MESSAGE2)):
                        next_pos = pos + obj_size
                        if next_pos > max_pos:
                            break  # it ends in the next container
                        timestamp = (ticks / 100_000 if flags == 1
                                     else ticks / 1_000_000_000) + start_timestamp
                        if can_id > _ID_MASK or msg_flags & REMOTE_FLAG:
                            append(Message(
                                timestamp=timestamp, arbitration_id=can_id & _ID_MASK,
                                is_extended_id=bool(can_id & CAN_MSG_EXT),
                                is_remote_frame=bool(msg_flags & REMOTE_FLAG),
                                is_rx=not msg_flags & DIR, dlc=dlc, data=can_data[:dlc],
                                channel=channel - 1))
                        else:
                            frame = new(frame_type)
                            frame.timestamp = timestamp
                            frame.arbitration_id = can_id  # no bit above an identifier's 29
                            frame.data = can_data[:dlc]
                            frame.dlc = dlc
                            frame.channel = channel - 1
                            frame.is_rx = not msg_flags & DIR
                            append(frame)
                        pos = next_pos
                        continue
                # Anything else, as python-can reads it.
                try:
                    pos = data.index(b"LOBJ", pos, pos + 8)  # after the padding
                except ValueError:
                    if pos + 8 > max_pos:
                        break  # not enough data in this container
                    raise BLFParseError("Could not find next object") from None
                signature, header_size, header_version, obj_size, obj_type = \
                    unpack_base(data, pos)
                next_pos = pos + obj_size
                if next_pos > max_pos:
                    break
                if not obj_size:
                    raise BLFParseError(f"an object of 0 bytes at {pos} of a container")
                message = self._other_object(data, pos, header_size, header_version,
                                             obj_size, obj_type)
                if message is not None:
                    append(message)
                pos = next_pos
        except struct.error:
            pass  # the container ends inside a struct: python-can's _parse_container's case
        except BLFParseError:
            self._pos = start
            if frames:
                yield frames  # the frames before the damage, then the failure
            raise
        self._pos = start
        if frames:
            yield frames

    def _other_object(self, data: bytes, pos: int, header_size: int, header_version: int,
                      obj_size: int, obj_type: int) -> Message | None:
        """The message python-can's loop yields for the object at ``pos`` (None for one it
        skips)."""
        pos += OBJ_HEADER_BASE_STRUCT.size
        if header_version == 1:
            flags, _, _, ticks = OBJ_HEADER_V1_STRUCT.unpack_from(data, pos)
            pos += OBJ_HEADER_V1_STRUCT.size
        elif header_version == 2:
            flags, _, _, ticks = OBJ_HEADER_V2_STRUCT.unpack_from(data, pos)
            pos += OBJ_HEADER_V2_STRUCT.size
        else:
            blf.LOG.warning("Unknown object header version (%d)", header_version)
            return None
        timestamp = (ticks / 100_000 if flags == 1 else ticks / 1_000_000_000) \
            + self.start_timestamp
        if obj_type == CAN_MESSAGE or obj_type == CAN_MESSAGE2:
            channel, flags, dlc, can_id, can_data = CAN_MSG_STRUCT.unpack_from(data, pos)
            return Message(timestamp=timestamp, arbitration_id=can_id & _ID_MASK,
                           is_extended_id=bool(can_id & CAN_MSG_EXT),
                           is_remote_frame=bool(flags & REMOTE_FLAG),
                           is_rx=not bool(flags & DIR), dlc=dlc, data=can_data[:dlc],
                           channel=channel - 1)
        if obj_type == CAN_ERROR_EXT:
            members = CAN_ERROR_EXT_STRUCT.unpack_from(data, pos)
            channel, dlc, can_id, can_data = members[0], members[5], members[7], members[9]
            return Message(timestamp=timestamp, is_error_frame=True,
                           is_extended_id=bool(can_id & CAN_MSG_EXT),
                           arbitration_id=can_id & _ID_MASK, dlc=dlc, data=can_data[:dlc],
                           channel=channel - 1)
        if obj_type == CAN_FD_MESSAGE:
            (channel, flags, dlc, can_id, _, _, fd_flags, valid_bytes,
             can_data) = CAN_FD_MSG_STRUCT.unpack_from(data, pos)
            return Message(timestamp=timestamp, arbitration_id=can_id & _ID_MASK,
                           is_extended_id=bool(can_id & CAN_MSG_EXT),
                           is_remote_frame=bool(flags & REMOTE_FLAG),
                           is_fd=bool(fd_flags & 0x1), is_rx=not bool(flags & DIR),
                           bitrate_switch=bool(fd_flags & 0x2),
                           error_state_indicator=bool(fd_flags & 0x4), dlc=dlc2len(dlc),
                           data=can_data[:valid_bytes], channel=channel - 1)
        if obj_type == CAN_FD_MESSAGE_64:
            members = CAN_FD_MSG_64_STRUCT.unpack_from(data, pos)
            channel, dlc, valid_bytes, can_id, fd_flags = (
                members[0], members[1], members[2], members[4], members[6])
            direction, ext_data_offset = members[12], members[13]
            # python-can's issue 1905: valid_bytes may exceed the data present; zero-padded.
            length = min(valid_bytes, (ext_data_offset or obj_size) - header_size
                         - CAN_FD_MSG_64_STRUCT.size)
            at = pos + CAN_FD_MSG_64_STRUCT.size
            return Message(timestamp=timestamp, arbitration_id=can_id & _ID_MASK,
                           is_extended_id=bool(can_id & CAN_MSG_EXT),
                           is_remote_frame=bool(fd_flags & 0x0010),
                           is_fd=bool(fd_flags & 0x1000), is_rx=not direction,
                           bitrate_switch=bool(fd_flags & 0x2000),
                           error_state_indicator=bool(fd_flags & 0x4000), dlc=dlc2len(dlc),
                           data=data[at:at + length].ljust(valid_bytes, b"\x00"),
                           channel=channel - 1)
        return None  # a type python-can skips (markers, statistics, other buses)
