"""The arbitrator's non-volatile memory: its stored configuration, safe against power cuts.

A real arbitrator keeps the stored configuration (reference §3) in EEPROM or flash; a cut in
the middle of a write must leave the previous configuration readable. This store keeps two
slots in one file it owns and writes them in turn, like a double-buffered EEPROM:

``[slot A][slot B]``, each slot ``header + payload`` at a fixed offset. The header holds a
magic, a generation counter, the payload length and a CRC-32 over generation, length and
payload; the payload is the codec's byte string (``config_codec.dumps``), which carries its
own CRC-16 record. A write goes to the slot *not* holding the newest valid generation:
payload first, fsync, header last, fsync. Until the new header is whole, that slot fails its
CRC and the reader takes the other slot — the previous configuration, never a mix.

A slot may also hold the fitting history's anchor (:data:`FLAG_ANCHOR`, issue 28): the entry
that recorded the prosthesis's last change and its hash, right after the payload, under the
same CRC — written by the same two-slot write, so a cut leaves the old anchor with the old
configuration or the new with the new. A configuration or policy write keeps it.

Reading takes the valid slot with the highest generation; a damaged slot (magic present but
a bad length or checksum) is reported with a warning, and the other one is used.

A memory file is a memory image (or a new path, which starts empty): anything else is refused
when the store opens (:func:`memory_file_problem`), in words — a FIFO or a device, a stored-
configuration file (``--memory fig410.pdcfg``: never silently turned into a 1 MiB image; write
it with ``config write``) or a file PDCP Studio did not write.
"""

from __future__ import annotations

import logging
import os
import stat
import struct
import threading
import zlib
from collections.abc import Callable
from pathlib import Path

from pdcp_studio.errors import ConfigFormatError, PdcpError
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.storage.archive.chain import ANCHOR_SIZE, Anchor, pack_anchor, unpack_anchor
from pdcp_studio.storage.atomic import atomic_write_bytes
from pdcp_studio.storage.regular_file import kind, open_regular

log = logging.getLogger(__name__)

MAGIC = b"PDCM"
FORMAT_VERSION = 1
# magic, format version, policy flags, generation, payload length, CRC-32 (generation..payload,
# and the flags when any is set — so a memory without flags reads as before)
_HEADER = struct.Struct("<4sHHQII")
#: Policy flag: start-up and the duty cycle never autoconfigure (issue 17, ``--no-autoconfigure``).
FLAG_NO_AUTOCONFIGURE = 0x0001
#: The slot holds the fitting history's anchor (issue 28): its bytes follow the payload and the
#: CRC covers them too. A slot without the flag (every image written before) reads as before.
FLAG_ANCHOR = 0x0002
HEADER_SIZE = _HEADER.size
#: Room for the largest collection the codec accepts (``config_codec.MAX_INPUT_BYTES``, 1 MiB;
#: not imported from it: an empty memory, as a simulated prosthesis opens with, needs no codec).
SLOT_CAPACITY = 1 << 20
#: Payload bytes per write call (the step hook runs between them).
CHUNK = 512

#: Open flags that never wait on a FIFO swapped in for the file (no effect on a regular file).
_NO_WAIT = getattr(os, "O_BINARY", 0) | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0)

#: ``step_hook(step)`` is called between the writes of one save (tests cut the power there).
StepHook = Callable[[str], None]


class MemoryStoreError(PdcpError):
    """The memory cannot hold or store a configuration."""


def _blank(head: bytes) -> bool:
    return not head.strip(b"\0") or not head.strip(b"\xff")


def memory_file_problem(path: str | os.PathLike[str], capacity: int = SLOT_CAPACITY, *,
                        content_only: bool = False) -> str | None:
    """Why ``path`` cannot be an arbitrator memory, in words; None when it can.

    A new path, an empty file, or slot A's header with the magic (or blank, as an erased or
    never-finished first write leaves it; slot B's magic then) is a memory. Read without
    waiting: a FIFO or a device is refused by what it is. ``content_only``: a path that
    cannot be read (a folder, a FIFO, no permission) is no problem here — each read then
    fails and the arbitrator reports its memory unreadable, as when it fails later.
    """
    try:
        mode = os.stat(path).st_mode
        if not stat.S_ISREG(mode):
            return None if content_only else f"is {kind(mode)}, not a memory file"
        with open_regular(path) as handle:
            head = handle.read(HEADER_SIZE)
            if not head or head[:4] == MAGIC:
                return None
            if _blank(head):
                handle.seek(HEADER_SIZE + capacity)
                other = handle.read(HEADER_SIZE)
                return None if not other or other[:4] == MAGIC or _blank(other) else \
                    "slot B holds no memory header"
            handle.seek(0)
            whole = handle.read(SLOT_CAPACITY + 1)
    except FileNotFoundError:
        return None
    except OSError as err:
        return None if content_only else f"cannot read: {err.strerror or err}"
    from pdcp_studio.storage import config_codec

    try:
        config_codec.loads(whole)
    except ConfigFormatError:
        return ("is not a memory image (no PDCM header): not a file PDCP Studio's arbitrator "
                "wrote; give a memory file, or a new path to start an empty memory")
    return ("is a stored-configuration file (.pdcfg), not a memory image; give a memory "
            "file (or a new path), then write the configuration with "
            "`config write FILE --bus URL --yes`")


class _FileBackend:
    def __init__(self, path: Path, capacity: int) -> None:
        self.path = path
        problem = memory_file_problem(path, capacity, content_only=True)
        if problem is not None:
            raise MemoryStoreError(f"memory {path}: {problem}")
        if not path.exists():
            atomic_write_bytes(path, b"")  # a new, empty memory: both slots blank

    def read(self, offset: int, size: int) -> bytes:
        with open_regular(self.path) as handle:
            handle.seek(offset)
            return handle.read(size)

    def write(self, offset: int, data: bytes) -> None:
        fd = os.open(self.path, os.O_WRONLY | _NO_WAIT)
        try:
            os.lseek(fd, offset, os.SEEK_SET)
            view = memoryview(data)
            while view:
                view = view[os.write(fd, view):]
        finally:
            os.close(fd)

    def sync(self) -> None:
        fd = os.open(self.path, os.O_RDONLY | _NO_WAIT)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


class _RamBackend:
    """The same layout in a bytearray (an arbitrator started without ``--memory``)."""

    def __init__(self) -> None:
        self.image = bytearray()

    def read(self, offset: int, size: int) -> bytes:
        return bytes(self.image[offset:offset + size])

    def write(self, offset: int, data: bytes) -> None:
        if len(self.image) < offset + len(data):
            self.image.extend(bytes(offset + len(data) - len(self.image)))
        self.image[offset:offset + len(data)] = data

    def sync(self) -> None:
        pass


def _crc(generation: int, payload: bytes, flags: int = 0, anchor: bytes = b"") -> int:
    extra = struct.pack("<H", flags) if flags else b""
    return zlib.crc32(struct.pack("<QI", generation, len(payload)) + payload + extra + anchor)


class MemoryStore:
    """Two-slot non-volatile store of one ``ConfigCollection``; thread-safe.

    ``path`` None keeps the slots in RAM (same code path, nothing survives the process).
    """

    def __init__(self, path: str | Path | None = None, *, capacity: int = SLOT_CAPACITY,
                 step_hook: StepHook | None = None) -> None:
        self.path = Path(path) if path is not None else None
        self.capacity = capacity
        self.step_hook = step_hook
        self.warnings: list[str] = []
        self._lock = threading.Lock()
        self._backend = (_FileBackend(self.path, capacity) if self.path is not None
                         else _RamBackend())

    # -- layout ---------------------------------------------------------------------------
    def _offset(self, slot: int) -> int:
        return slot * (HEADER_SIZE + self.capacity)

    def _step(self, name: str) -> None:
        if self.step_hook is not None:
            self.step_hook(name)

    def _slot(self, slot: int) -> tuple[int, bytes] | str | None:
        """(generation, payload) if valid; None if blank; a reason string if damaged."""
        got = self._slot_flags(slot)
        return got[:2] if isinstance(got, tuple) else got

    def _slot_flags(self, slot: int) -> tuple[int, bytes, int, bytes] | str | None:
        """(generation, payload, flags, anchor bytes) if valid; None if blank; a reason if
        damaged. The anchor's bytes (empty without :data:`FLAG_ANCHOR`) follow the payload."""
        head = self._backend.read(self._offset(slot), HEADER_SIZE)
        if len(head) < HEADER_SIZE or head[:4] != MAGIC:
            return None if _blank(head) else "no slot header"
        _, version, flags, generation, length, crc = _HEADER.unpack(head)
        if version != FORMAT_VERSION:
            return f"unknown format version {version}"
        if length > self.capacity:
            return f"length {length} exceeds the slot capacity {self.capacity}"
        payload = self._backend.read(self._offset(slot) + HEADER_SIZE, length)
        anchor = b""
        if flags & FLAG_ANCHOR:
            if length + ANCHOR_SIZE > self.capacity:
                return f"length {length} leaves no room for the anchor"
            anchor = self._backend.read(self._offset(slot) + HEADER_SIZE + length, ANCHOR_SIZE)
            if len(anchor) != ANCHOR_SIZE:
                return f"checksum mismatch (generation {generation})"
        if len(payload) != length or _crc(generation, payload, flags, anchor) != crc:
            return f"checksum mismatch (generation {generation})"
        from pdcp_studio.storage import config_codec

        try:
            if payload or not anchor:  # an anchor alone: no configuration stored yet
                config_codec.loads(payload)
        except ConfigFormatError as err:
            return f"configuration does not decode: {err}"
        if anchor:
            try:
                unpack_anchor(anchor)
            except ValueError as err:
                return f"anchor does not decode: {err}"
        return generation, payload, flags, anchor

    def _scan(self) -> tuple[int | None, int, bytes | None, list[str]]:
        """(slot of the newest valid copy, its generation, its payload, damage notes)."""
        best: tuple[int | None, int, bytes | None] = (None, -1, None)
        notes: list[str] = []
        for slot in (0, 1):
            got = self._slot(slot)
            if isinstance(got, str):
                notes.append(f"slot {'AB'[slot]} is damaged ({got})")
            elif got is not None and got[0] > best[1]:
                best = (slot, got[0], got[1])
        return best[0], best[1], best[2], notes

    def _warn(self, notes: list[str], used: str) -> None:
        for note in notes:
            text = f"memory {self.path or '(RAM)'}: {note}; {used}"
            self.warnings.append(text)
            log.warning("%s", text)

    # -- API ------------------------------------------------------------------------------
    @property
    def generation(self) -> int:
        """Generation of the configuration a read returns (0: none or a plain file)."""
        with self._lock:
            return max(self._scan()[1], 0)

    def read_bytes(self) -> bytes | None:
        """The stored codec bytes (None when nothing is stored)."""
        with self._lock:
            slot, generation, payload, notes = self._scan()
            if payload is not None:
                if notes:
                    self._warn(notes, f"using slot {'AB'[slot or 0]} (generation {generation})")
                return payload or None  # a slot that holds only the anchor: nothing stored
            if notes:
                self._warn(notes, "no valid configuration is stored")
            return None

    def read(self) -> ConfigCollection:
        """The stored configuration collection (empty when nothing is stored)."""
        payload = self.read_bytes()
        if payload is None:
            return ConfigCollection()
        from pdcp_studio.storage import config_codec

        return config_codec.loads(payload)

    def write(self, configs: ConfigCollection) -> int:
        """Store ``configs`` in the older slot (the policy is kept); returns the new
        generation. The written slot is read back and checked before this returns."""
        from pdcp_studio.storage import config_codec

        payload = config_codec.dumps(configs)
        if len(payload) > self.capacity:
            raise MemoryStoreError(f"the configuration takes {len(payload)} bytes; the memory "
                                   f"holds {self.capacity} per slot")
        with self._lock:
            return self._write_locked(payload, None)

    def read_policy(self) -> dict[str, bool]:
        """The profile-layer policy stored beside the configuration (issue 17)."""
        with self._lock:
            flags = self._flags()
        return {"autoconfigure": not flags & FLAG_NO_AUTOCONFIGURE}

    def write_policy(self, policy: dict[str, bool]) -> int:
        """Store the policy with the current configuration (a safe two-slot write)."""
        from pdcp_studio.storage import config_codec

        with self._lock:
            flags = self._flags() & ~FLAG_NO_AUTOCONFIGURE
            if not policy.get("autoconfigure", True):
                flags |= FLAG_NO_AUTOCONFIGURE
            _, _, payload, _ = self._scan()
            if payload is None:
                payload = config_codec.dumps(ConfigCollection())
            return self._write_locked(payload, flags)

    def read_anchor(self) -> Anchor | None:
        """The fitting history's anchor stored beside the configuration (reference §5
        Decision): the entry that recorded the last change and its hash; None when this
        memory holds none (written before anchors, or never changed)."""
        with self._lock:
            got = self._current()
        if not isinstance(got, tuple) or not got[3]:
            return None
        return unpack_anchor(got[3])

    def write_anchor(self, anchor: Anchor) -> int:
        """Store ``anchor`` with the current configuration and policy (a safe two-slot
        write); returns the new generation."""
        data = pack_anchor(anchor)
        with self._lock:
            _, _, payload, _ = self._scan()
            # no configuration stored yet: the slot holds the anchor alone (length 0), so a
            # read still says "none stored" as before
            return self._write_locked(payload or b"", None, data)

    def _current(self) -> tuple[int, bytes, int, bytes] | str | None:
        slot, _, _, _ = self._scan()
        return self._slot_flags(slot) if slot is not None else None

    def _flags(self) -> int:
        got = self._current()
        return got[2] if isinstance(got, tuple) else 0

    def _write_locked(self, payload: bytes, flags: int | None,
                      anchor: bytes | None = None) -> int:
        slot, generation, _, _ = self._scan()
        current = self._current()
        if flags is None:
            flags = current[2] if isinstance(current, tuple) else 0
        if anchor is None:  # a configuration or policy write keeps the anchor
            anchor = current[3] if isinstance(current, tuple) else b""
        flags = (flags | FLAG_ANCHOR) if anchor else (flags & ~FLAG_ANCHOR)
        if len(payload) + len(anchor) > self.capacity:
            raise MemoryStoreError(f"the configuration takes {len(payload)} bytes; with the "
                                   f"fitting history's anchor the memory holds "
                                   f"{self.capacity - len(anchor)} per slot")
        new_generation = generation + 1 if generation >= 0 else 1
        if slot is None:
            if self._slot(0) == "no slot header":  # not ours: never write over it
                raise MemoryStoreError(f"{self.path} is neither an arbitrator memory nor a "
                                       "stored configuration; refusing to overwrite it")
        target = 1 if slot == 0 else 0
        base = self._offset(target)
        for start in range(0, len(payload), CHUNK):
            self._backend.write(base + HEADER_SIZE + start, payload[start:start + CHUNK])
            self._step("payload")
        if anchor:
            self._backend.write(base + HEADER_SIZE + len(payload), anchor)
            self._step("anchor")
        self._backend.sync()
        self._step("payload synced")
        head = _HEADER.pack(MAGIC, FORMAT_VERSION, flags, new_generation, len(payload),
                            _crc(new_generation, payload, flags, anchor))
        half = HEADER_SIZE // 2
        self._backend.write(base, head[:half])
        self._step("header half")
        self._backend.write(base + half, head[half:])
        self._backend.sync()
        self._step("header synced")
        self._check(target, new_generation, payload)
        return new_generation

    def erase(self) -> int:
        """Store an empty collection (itself a safe, two-slot write); returns its generation."""
        return self.write(ConfigCollection())

    # -- helpers --------------------------------------------------------------------------
    def _check(self, slot: int, generation: int, payload: bytes) -> None:
        got = self._slot(slot)
        if not isinstance(got, tuple) or got != (generation, payload):
            raise MemoryStoreError(f"memory {self.path or '(RAM)'}: slot {'AB'[slot]} did not read "
                               f"back as written ({got if isinstance(got, str) else 'mismatch'})")
