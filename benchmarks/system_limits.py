"""The largest system file PDCP Studio accepts, opened in the app (issue 15, contracts §1).

A system file holds at most 254 devices, 2,048 channels and 2,048 links, 2 MiB, 16 levels
(``storage/system_file.py``). This builds the largest such system — 254 devices, 2,048 channels
(outputs feeding inputs), every link an input can take — writes it, then in the app: loads it,
lays it out, builds the scene and renders it once (target < 1 s, as the 254-device case of
``benchmarks/gui.py``). It also times the refusals at the limits: a 2 MiB + 1 byte file, a pipe
of endless bytes, JSON nested 100,000 deep (each must be refused in well under a second).

Run: ``python benchmarks/system_limits.py`` (offscreen; prints the figures).
"""

from __future__ import annotations

import os
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pdcp_studio.model.system import System

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

RUNS = 3


def largest_system() -> System:
    """254 devices and 2,048 channels: odd channels outputs, even ones inputs fed by them."""
    from pdcp_studio.model.refs import Direction
    from pdcp_studio.model.system import Channel, Device, Link, System
    from pdcp_studio.storage.system_file import MAX_CHANNELS, MAX_DEVICES

    s = System()
    per, extra = divmod(MAX_CHANNELS, MAX_DEVICES)
    devices = []
    for i in range(MAX_DEVICES):
        d = Device(10, 1 + i % 7, i + 1, name=f"Device {i + 1} of the largest system")
        for c in range(1, per + (1 if i < extra else 0) + 1):
            d.add_channel(Channel(c, Direction.OUTPUT if c % 2 else Direction.INPUT,
                                  type=0x9000, profile=0x4222 + 2 * (c % 5),
                                  descriptor=f"Channel {c}, 32 characters long."))
        s.add_device(d)
        devices.append(d)
    for i, d in enumerate(devices):  # each input fed by the next device's output channel
        nxt = devices[(i + 1) % len(devices)]
        for c, ch in d.channels.items():
            out = c - 1
            if ch.is_input and out in nxt.channels and not nxt.channels[out].is_input:
                s.add_link(Link(nxt.ref(out), d.ref(c)))
    return s


def open_in_app(path: Path) -> dict[str, float]:
    from PySide6.QtGui import QImage, QPainter
    from PySide6.QtWidgets import QApplication

    QApplication.instance() or QApplication([])
    import networkx  # noqa: F401  (the app preloads it while connecting; not counted here)

    from pdcp_studio.app.documents import files
    from pdcp_studio.app.documents.document import Document
    from pdcp_studio.app.graph.scene import BusScene
    from pdcp_studio.app.graph.view import GraphView

    runs = []
    for _ in range(RUNS):
        t0 = time.perf_counter()
        opened = files.open_path(path)
        t1 = time.perf_counter()
        doc = Document(opened.system)
        scene = BusScene(doc)
        t2 = time.perf_counter()
        view = GraphView(scene)
        view.resize(1400, 900)
        view.fit_all()
        image = QImage(1400, 900, QImage.Format.Format_ARGB32)
        image.fill(0xFFFFFFFF)
        painter = QPainter(image)
        view.render(painter)
        painter.end()
        t3 = time.perf_counter()
        runs.append({"load": t1 - t0, "scene": t2 - t1, "render": t3 - t2, "total": t3 - t0,
                     "devices": len(doc.system.devices),
                     "channels": sum(len(d.channels) for d in doc.system.devices.values()),
                     "links": len(doc.system.links)})
    return min(runs, key=lambda r: r["total"])


def refusal_s(make: Callable[[Path], Path]) -> tuple[float, str]:
    """Seconds until load_path refuses what ``make(dir)`` returns, and the message."""
    from pdcp_studio.errors import SystemFileError
    from pdcp_studio.storage import system_file

    path = make(Path(tempfile.mkdtemp()))
    t0 = time.perf_counter()
    try:
        system_file.load_path(path)
    except SystemFileError as err:
        return time.perf_counter() - t0, str(err)
    raise SystemExit(f"{path} was accepted")


def _too_big(d: Path) -> Path:
    from pdcp_studio.storage.system_file import MAX_FILE_BYTES

    p = d / "big.json"
    p.write_bytes(b" " * (MAX_FILE_BYTES + 1))
    return p


def _endless_pipe(d: Path) -> Path:
    p = d / "pipe.json"
    os.mkfifo(p)

    def feed() -> None:
        try:
            with open(p, "wb") as out:
                while True:
                    out.write(b" " * 65536)
        except BrokenPipeError:
            pass

    threading.Thread(target=feed, daemon=True).start()
    return p


def _deep(d: Path) -> Path:
    p = d / "deep.json"
    p.write_text("[" * 100_000 + "]" * 100_000)
    return p


def main() -> None:
    from pdcp_studio.app.documents import files

    path = Path(tempfile.mkdtemp()) / "largest.pdcpsys.json"
    files.save_system(largest_system(), path)
    r = open_in_app(path)
    print(f"largest accepted system file: {r['devices']} devices, {r['channels']} channels, "
          f"{r['links']} links, {path.stat().st_size:,} bytes — load {r['load'] * 1000:.0f} ms, "
          f"layout+scene {r['scene'] * 1000:.0f} ms, render {r['render'] * 1000:.0f} ms, "
          f"total {r['total'] * 1000:.0f} ms (target < 1000 ms; best of {RUNS})")
    for name, make in (("2 MiB + 1 byte file", _too_big), ("endless pipe", _endless_pipe),
                       ("nested 100,000 deep", _deep)):
        seconds, message = refusal_s(make)
        print(f"refused {name} in {seconds * 1000:.0f} ms: {message.split(': ', 1)[1]}")


if __name__ == "__main__":
    main()
