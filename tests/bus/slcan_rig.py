"""An SLCAN adapter on a pseudo-terminal, bridged to a python-can virtual channel, that a test
can pull out and plug back in: python-can's real ``slcan`` driver talks to it.

The adapter's port is a symlink (as udev's ``/dev/serial/by-id/…``) to the pseudo-terminal's
slave; pulling it closes the far end (the driver's reads fail as with a pulled USB adapter) and
removes the link; plugging it back opens a new pseudo-terminal behind the same path.
"""

from __future__ import annotations

import contextlib
import os
import pty
import select
import threading
import tty
from pathlib import Path

import can


class SlcanAdapter:
    def __init__(self, path: Path, channel: str) -> None:
        self.path = Path(path)
        self.bus = can.Bus(interface="virtual", channel=channel)
        self.frames_in = 0  # frames the PC sent through the adapter
        self._lock = threading.Lock()
        self._master: int | None = None
        self._slave: int | None = None
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="slcan adapter", daemon=True)
        self.plug()
        self._thread.start()

    def plug(self) -> None:
        master, slave = pty.openpty()
        tty.setraw(slave)
        with contextlib.suppress(FileNotFoundError):
            self.path.unlink()
        self.path.symlink_to(os.ttyname(slave))
        with self._lock:
            self._master, self._slave = master, slave

    def pull(self) -> None:
        with self._lock:
            master, slave = self._master, self._slave
            self._master = self._slave = None
        with contextlib.suppress(FileNotFoundError):
            self.path.unlink()
        for fd in (master, slave):
            if fd is not None:
                os.close(fd)

    def _run(self) -> None:
        buffer = b""
        while not self._stop.is_set():
            with self._lock:
                master = self._master
            if master is None:
                buffer = b""
                self._stop.wait(0.01)
                while self.bus.recv(0) is not None:  # the adapter is out: frames are lost
                    pass
                continue
            try:
                ready, _, _ = select.select([master], [], [], 0.005)
                if ready:
                    buffer += os.read(master, 4096)
            except OSError:  # pulled meanwhile
                continue
            while b"\r" in buffer:
                line, buffer = buffer.split(b"\r", 1)
                self._command(line.decode("ascii", "replace"))
            while (msg := self.bus.recv(0)) is not None:
                text = f"t{msg.arbitration_id:03X}{msg.dlc}{bytes(msg.data).hex().upper()}\r"
                with contextlib.suppress(OSError):
                    os.write(master, text.encode())

    def _command(self, line: str) -> None:
        if line.startswith("t") and len(line) >= 5:
            dlc = int(line[4])
            self.frames_in += 1
            self.bus.send(can.Message(arbitration_id=int(line[1:4], 16), is_extended_id=False,
                                      data=bytes.fromhex(line[5:5 + 2 * dlc])))

    def close(self) -> None:
        self._stop.set()
        self._thread.join(2)
        self.pull()
        self.bus.shutdown()
