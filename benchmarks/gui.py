"""Desktop app performance (issue 5): start-up, a 254-device system, a responsive GUI.

1. Start-up: ``python -m pdcp_studio gui --bus sim:transradial`` (the simulated prosthesis, as
   bare ``pdcp-studio`` opens it; ``gui`` alone opens on the start page) from process spawn
   until the window is shown, laid out and bound to the bus — the app prints a line then
   (``PDCP_STUDIO_STARTUP_PROBE``) and exits. Target < 1.5 s, and within 1.5× a bare
   PySide6 window that imports python-can and networkx (``benchmarks/bare_window.py``, the
   parts the app needs): the two are started alternately, in one run, so both see the same
   machine load.
2. A 254-device system: load the file, lay it out, build the scene and render it once.
   Target < 1 s (layered layout, no force-directed step). The same system without links in
   the app's window: opened (a Checks finding per unfed input) and autoconfigure previewed
   (its steps with their words); each was seconds of a frozen window while every part's name
   was looked up by reading the whole system again.
3. The GUI thread while scans run on the simulated prosthesis: a 5 ms QTimer heartbeat;
   the longest gap between two beats. Target: never blocked > 50 ms.

4. The trace at full load: the monitor dock, its per-ID statistics and the live plot fed
   as the session bridge feeds them — decoded frames (``FrameSeen``, decoded off the GUI
   thread by ``bus.monitor.FrameDecoder``) and channel values in batches every 50 ms — at
   8,000 frames/s (a saturated 1 Mbit/s bus carries 7,400–10,500) for ``TRACE_SECONDS``;
   the longest gap between 5 ms heartbeats. Target: never blocked > 50 ms; the dock's
   ring stays at its capacity.

5. A large capture in the trace: BLF captures of 1,000,000 and 5,000,000 frames of
   ``benchmarks/trace.py``'s traffic (made once, cached in the temp folder) opened in the
   monitor dock, each in a process of its own: time to the first rows (target < 1 s), to
   every frame indexed, the GUI thread's longest gap while it loads (target < 50 ms), a
   filter and a search over all the frames, and the process's peak RSS (target < 150 MB
   whatever the length: the frames and texts are kept in temporary files).

Run: ``python benchmarks/gui.py [--only startup|big|scan|trace|capture] [--frames 1000000,5000000]
[--source] [--offline]`` (``--source``: start-up from source compiled on every run, not as
installed; ``--offline``: the app's start page and its window on a system file, no bus, timed
in the same rounds — the live window's cost without the simulated prosthesis)
(offscreen; prints the figures).
"""

from __future__ import annotations

import io
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pdcp_studio.bus.events import ChannelValue, FrameSeen
    from pdcp_studio.model.system import System

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
# The app decides the interpreter's switch interval at start-up (app/application.py); the
# in-process cases build its window without run_app, so they set it as it does.
from pdcp_studio.app.application import share_the_interpreter  # noqa: E402
from pdcp_studio.app.pyside_import_scan import spare_source_scan  # noqa: E402

share_the_interpreter()
spare_source_scan()  # as the app's start-up does: windows here are made without run_app

STARTUP_RUNS = 5
#: The bare window the app's start-up is measured against, and the ratio it must stay within.
BARE_WINDOW = ROOT / "benchmarks" / "bare_window.py"
STARTUP_RATIO_TARGET = 1.5
SCAN_SECONDS = 4.0
HEARTBEAT_MS = 5
#: The longest gap varies with machine load: measure several rounds and print each.
HEARTBEAT_ROUNDS = 3

#: One start-up: wall seconds from spawn to the probe line, the process's CPU seconds (user +
#: system, every thread) when it printed that line and when it exited, and the GUI thread's
#: CPU seconds when it printed that line.
Run = tuple[float, float, float, float]
#: When each phase of one start-up ended, as its probe line says
#: (``<phase>_s=<wall>/<cpu>/<gui cpu>``, from the program's first line): phase → (wall
#: seconds, the process's CPU seconds, the GUI thread's CPU seconds).
Phases = dict[str, tuple[float, float, float]]
#: The phases in the order they end (the app's; the bare window has the first three).
PHASES = ("imported", "built", "shown", "opened", "ready")


def _probe(command: list[str], cwd: Path, phases: list[Phases] | None = None, *,
           live: bool = True) -> Run:
    """Spawn ``command`` (the app or the bare window) and time it to its probe line (the
    ends of its phases appended to ``phases``); ``live``: the line must say the window is
    bound to a bus."""
    env = dict(os.environ, PDCP_STUDIO_STARTUP_PROBE="1", QT_QPA_PLATFORM="offscreen")
    t0 = time.perf_counter()
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                            text=True, env=env, cwd=cwd)
    assert proc.stdout is not None
    line = proc.stdout.readline()
    t1 = time.perf_counter()
    _pid, status, usage = os.wait4(proc.pid, 0)  # wait() would not give its CPU time
    proc.returncode = os.waitstatus_to_exitcode(status)
    proc.stdout.close()
    if not line.startswith("startup_s=") or (live and "live=True" not in line):
        raise SystemExit(f"start-up probe of {command[1:]} failed: {line!r}")
    fields = dict(f.split("=", 1) for f in line.split() if "=" in f)
    if phases is not None:
        phases.append({name[:-2]: (float(wall), float(cpu), float(gui))
                       for name, value in fields.items() if name[:-2] in PHASES
                       for wall, cpu, gui in [value.split("/")]})
    return (t1 - t0, float(fields.get("cpu_s", "nan")), usage.ru_utime + usage.ru_stime,
            float(fields.get("gui_cpu_s", "nan")))


#: The same app without a bus, started in the same rounds (``--offline``): its start page,
#: and the window on the simulated prosthesis's own system file — what the live window costs
#: without the simulated prosthesis beside it in the process.
OFFLINE_STARTS = {
    "start page": ["gui"],
    "a system file, offline": ["gui", str(ROOT / "resources" / "systems" / "transradial.json")],
}


def startup(root: Path = ROOT, app_phases: list[Phases] | None = None,
            bare_phases: list[Phases] | None = None,
            offline: dict[str, list[Run]] | None = None) -> tuple[list[Run], list[Run]]:
    """``STARTUP_RUNS`` interleaved pairs: the app live on ``sim:transradial`` (from
    ``root``), then the bare window — one after the other, so each pair shares the load
    (and, with ``offline``, each of :data:`OFFLINE_STARTS` in the same round)."""
    app = [sys.executable, "-m", "pdcp_studio", "gui", "--bus", "sim:transradial"]
    bare = [sys.executable, str(BARE_WINDOW)]
    apps, bares = [], []
    for _ in range(STARTUP_RUNS):
        apps.append(_probe(app, root, app_phases))
        bares.append(_probe(bare, root, bare_phases))
        if offline is None:
            continue
        for name, args in OFFLINE_STARTS.items():
            offline.setdefault(name, []).append(
                _probe([sys.executable, "-m", "pdcp_studio", *args], root, live=False))
    return apps, bares


def _median(runs: list[Run], field: int) -> float:
    return statistics.median(r[field] for r in runs)


def _phases_text(runs: list[Phases]) -> str:
    """Each phase's median end (wall / process CPU seconds) and the median CPU seconds it
    took after the phase before it: the process's, the GUI thread's."""
    parts = []
    start = (0.0, 0.0, 0.0)
    for previous, phase in zip((None, *PHASES), PHASES, strict=False):
        had = [(r[phase], r[previous] if previous else start) for r in runs
               if phase in r and (previous is None or previous in r)]
        if not had:
            continue
        wall = statistics.median(end[0] for end, _ in had)
        cpu = statistics.median(end[1] for end, _ in had)
        took = statistics.median(end[1] - before[1] for end, before in had)
        gui = statistics.median(end[2] - before[2] for end, before in had)
        parts.append(f"{phase} {wall:.3f}/{cpu:.3f} (+{took:.3f}, GUI thread +{gui:.3f})")
    return ", ".join(parts)


def print_startup() -> None:
    """Start-up as installed: a copy of the package with its bytecode compiled, as pip and
    the packaged app have it; with ``--source``, a copy without bytecode whose every run
    compiles the app's ~1 MB of source again (an editable checkout under
    PYTHONDONTWRITEBYTECODE). Either way nothing is written into the source tree. Then
    the ratio to the bare window, from the medians and pair by pair."""
    import compileall
    import shutil

    source = "--source" in sys.argv
    copy = Path(tempfile.mkdtemp(prefix="pdcp-startup-"))
    env_before = os.environ.get("PYTHONDONTWRITEBYTECODE")
    try:
        shutil.copytree(ROOT / "pdcp_studio", copy / "pdcp_studio",
                        ignore=shutil.ignore_patterns("__pycache__"))  # resources copied too
        if source:
            os.environ["PYTHONDONTWRITEBYTECODE"] = "1"
        else:
            compileall.compile_dir(copy / "pdcp_studio", quiet=1)
        app_phases: list[Phases] = []
        bare_phases: list[Phases] = []
        offline: dict[str, list[Run]] | None = {} if "--offline" in sys.argv else None
        runs, bare = startup(copy, app_phases, bare_phases, offline)
    finally:
        if env_before is None:
            os.environ.pop("PYTHONDONTWRITEBYTECODE", None)
        shutil.rmtree(copy, ignore_errors=True)
    how = "source compiled on every run" if source else "bytecode compiled, as installed"
    times = [r[0] for r in runs]
    print(f"start-up to window shown, laid out, live on sim:transradial ({how}): "
          f"median {statistics.median(times):.3f} s, best {min(times):.3f} s, "
          f"worst {max(times):.3f} s over {len(times)} runs (target < 1.5 s); process CPU "
          f"median {_median(runs, 1):.3f} s to that line, {_median(runs, 2):.3f}"
          f" s to exit, the GUI thread's {_median(runs, 3):.3f} s to that line; "
          f"{_load()}", flush=True)
    ratio = _median(runs, 0) / _median(bare, 0)
    pairs = sorted(a[0] / b[0] for a, b in zip(runs, bare, strict=True))
    print(f"bare PySide6 window importing python-can and networkx, interleaved with the runs "
          f"above: median {_median(bare, 0):.3f} s (process CPU {_median(bare, 1):.3f} s, the "
          f"GUI thread's {_median(bare, 3):.3f} s); the app takes {ratio:.2f}× its time "
          f"(pair by pair {pairs[0]:.2f}–{pairs[-1]:.2f}×, median "
          f"{statistics.median(pairs):.2f}×), {_median(runs, 1) / _median(bare, 1):.2f}× its "
          f"process CPU (target ≤ {STARTUP_RATIO_TARGET}×: "
          f"{'met' if ratio <= STARTUP_RATIO_TARGET else 'NOT met'}); {_load()}", flush=True)
    print("phases, median end in wall/process CPU s since the program's first line (+ CPU s "
          "since the phase before): "
          f"app {_phases_text(app_phases)}; bare window {_phases_text(bare_phases)}",
          flush=True)
    if offline:
        print("the same app without a bus, in the same rounds: " + "; ".join(
            f"{name} median {_median(done, 0):.3f} s, {_median(done, 0) / _median(bare, 0):.2f}× "
            f"the bare window (process CPU {_median(done, 1):.3f} s)"
            for name, done in offline.items()), flush=True)


def big_system(n: int = 254) -> System:
    """n devices: pairs of sensors feeding a control unit feeding a hand."""
    from pdcp_studio.model.refs import Direction
    from pdcp_studio.model.system import Channel, Device, Link, System

    s = System()
    for g in range(n // 4):
        sensors = []
        for k in range(2):
            d = Device(10, 1, g * 2 + k + 1, name=f"EMG sensor {g}.{k}")
            d.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4222 + 2 * k))
            s.add_device(d)
            sensors.append(d)
        c = Device(10, 2, g + 1, name=f"Control unit {g}")
        c.add_channel(Channel(1, Direction.INPUT, type=0x9200, profile=0x4222))
        c.add_channel(Channel(2, Direction.INPUT, type=0x9200, profile=0x4224))
        c.add_channel(Channel(3, Direction.OUTPUT, type=0x9000, profile=0x2220))
        c.add_channel(Channel(4, Direction.OUTPUT, type=0x9000, profile=0x2240))
        s.add_device(c)
        t = Device(10, 3, g + 1, name=f"Hand {g}")
        t.add_channel(Channel(1, Direction.INPUT, type=0x9300, profile=0x2220))
        t.add_channel(Channel(2, Direction.INPUT, type=0x9300, profile=0x2240))
        s.add_device(t)
        s.add_link(Link(sensors[0].ref(1), c.ref(1)))
        s.add_link(Link(sensors[1].ref(1), c.ref(2)))
        s.add_link(Link(c.ref(3), t.ref(1)))
        s.add_link(Link(c.ref(4), t.ref(2)))
    for extra in range(n - 4 * (n // 4)):
        d = Device(10, 9, extra + 1, name=f"Spare sensor {extra}")
        d.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4600))
        s.add_device(d)
    return s


def big_open_render() -> dict[str, float]:
    from PySide6.QtGui import QImage, QPainter
    from PySide6.QtWidgets import QApplication

    QApplication.instance() or QApplication([])
    import networkx  # noqa: F401  (the app preloads it while connecting; not counted here)

    from pdcp_studio.app.documents import files
    from pdcp_studio.app.documents.document import Document
    from pdcp_studio.app.graph.scene import BusScene
    from pdcp_studio.app.graph.view import GraphView

    path = Path(tempfile.mkdtemp()) / "big.json"
    files.save_system(big_system(254), path)
    runs = []
    for _ in range(3):
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
        runs.append({"load": t1 - t0, "layout+scene": t2 - t1, "render": t3 - t2,
                     "total": t3 - t0, "devices": len(doc.system.devices),
                     "links": len(doc.system.links)})
    return min(runs, key=lambda r: r["total"])


def big_window() -> dict[str, float]:
    """The 254-device system with no links, in the app's window: opening it (the Checks list
    has a finding per unfed input, every part named) and previewing autoconfigure (a table
    row and a ghost link with its tooltip per step), each on the GUI thread. Best of 3."""
    from PySide6.QtWidgets import QApplication

    app = QApplication.instance() or QApplication([])
    import networkx  # noqa: F401  (the app preloads it; not counted here)

    from pdcp_studio.app.documents import files
    from pdcp_studio.app.window.main_window import MainWindow

    system = big_system(254)
    for link in list(system.links):
        system.remove_link(link)
    path = Path(tempfile.mkdtemp()) / "big-unlinked.json"
    files.save_system(system, path)
    runs = []
    for _ in range(3):
        window = MainWindow()
        window.quiet = True
        window.show()
        app.processEvents()
        t0 = time.perf_counter()
        window.open_path(path)
        t1 = time.perf_counter()
        app.processEvents()
        t2 = time.perf_counter()
        plan = window.preview_plan("autoconfigure")
        t3 = time.perf_counter()
        runs.append({"open": t1 - t0, "preview": t3 - t2, "steps": len(plan.actions)})
        window.doc.mark_saved()
        window.close()
        window.deleteLater()
        app.processEvents()
    return {"open": min(r["open"] for r in runs), "preview": min(r["preview"] for r in runs),
            "steps": runs[0]["steps"]}


def print_big() -> None:
    big = big_open_render()
    print(f"254-device system: {big['devices']} devices, {big['links']} links — load "
          f"{big['load'] * 1000:.0f} ms, layout+scene {big['layout+scene'] * 1000:.0f} ms, "
          f"render {big['render'] * 1000:.0f} ms, total {big['total'] * 1000:.0f} ms "
          "(target < 1000 ms)", flush=True)
    win = big_window()
    print(f"the same without links, in the app's window (best of 3): opened in "
          f"{win['open'] * 1000:.0f} ms (every input a finding in Checks, every part named), "
          f"autoconfigure previewed in {win['preview'] * 1000:.0f} ms ({win['steps']} steps, "
          "each a table row and a ghost link with its words) — the GUI thread is busy "
          "throughout; load average "
          f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores", flush=True)


def heartbeat_during_scans() -> dict[str, float]:
    from PySide6.QtCore import QElapsedTimer, QTimer
    from PySide6.QtWidgets import QApplication

    app = QApplication.instance() or QApplication([])
    from pdcp_studio.app.window.main_window import MainWindow

    window = MainWindow()
    window.quiet = True
    window.show()
    ready = {"ok": False}
    window.ready.connect(lambda: ready.update(ok=True))
    window.connect_bus("sim:transradial")
    deadline = time.monotonic() + 20
    while not ready["ok"] and time.monotonic() < deadline:
        app.processEvents()
        time.sleep(0.005)
    if not window.live.is_live:
        raise SystemExit("the simulated prosthesis did not connect: "
                         + window.statusBar().currentMessage())
    # The trace docks are made just after the window is up (start-up's last step, ~30 ms on
    # the GUI thread once their imports are done on a thread): the scans come after it.
    while "monitor" not in window._leaf_docks and time.monotonic() < deadline:
        app.processEvents()
        time.sleep(0.005)
    bridge = window.live.bridge
    gaps: list[float] = []
    clock = QElapsedTimer()
    clock.start()
    last = {"t": clock.nsecsElapsed()}
    scans = {"done": 0}
    end = time.monotonic() + SCAN_SECONDS

    def beat() -> None:
        now = clock.nsecsElapsed()
        gaps.append((now - last["t"]) / 1e6)
        last["t"] = now

    def scanned(_system: object) -> None:
        scans["done"] += 1
        if time.monotonic() < end:
            bridge.scan()

    bridge.scanned.connect(scanned)
    timer = QTimer()
    timer.setInterval(HEARTBEAT_MS)
    timer.timeout.connect(beat)
    timer.start()
    bridge.scan()
    QTimer.singleShot(int(SCAN_SECONDS * 1000), app.quit)
    app.exec()  # the real event loop, as in the app
    timer.stop()
    window.doc.mark_saved()
    window.close()
    gaps = gaps[1:]
    return {"scans": scans["done"], "beats": len(gaps), "max_gap_ms": max(gaps),
            "p99_gap_ms": sorted(gaps)[int(len(gaps) * 0.99) - 1]}


def print_scans() -> None:
    for n in range(1, HEARTBEAT_ROUNDS + 1):
        hb = heartbeat_during_scans()
        print(f"GUI thread, round {n}: {hb['scans']} scans in {SCAN_SECONDS:.0f} s, longest gap "
              f"between {HEARTBEAT_MS} ms heartbeats {hb['max_gap_ms']:.1f} ms, p99 "
              f"{hb['p99_gap_ms']:.1f} ms over {hb['beats']} beats (target: never > 50 ms); "
              f"{_load()}", flush=True)


class _Heart:
    """5 ms heartbeats on the GUI thread: each gap, and how much of it the thread spent
    waiting for a CPU (Linux's per-thread scheduler statistics; 0 elsewhere). On a shared
    2-core machine a gap can be the machine's other work, not the app's: both are printed."""

    def __init__(self) -> None:
        from array import array

        from PySide6.QtCore import QElapsedTimer, QTimer

        # arrays of doubles: a list of floats would add 3 MB to the peak RSS measured over the
        # 52,000 beats of a 5,000,000-frame capture
        self.gaps = array("d")
        self.waits = array("d")  # ms of each gap spent runnable but not running
        self._clock = QElapsedTimer()
        self._timer = QTimer()
        self._timer.setInterval(HEARTBEAT_MS)
        self._timer.timeout.connect(self._beat)
        self._sched: io.FileIO | None
        try:
            self._sched = open("/proc/thread-self/schedstat", "rb", buffering=0)
        except OSError:
            self._sched = None

    def _waited_ns(self) -> int:
        if self._sched is None:
            return 0
        self._sched.seek(0)
        return int(self._sched.read().split()[1])

    def start(self) -> None:
        self._clock.start()
        self._last, self._wait0 = self._clock.nsecsElapsed(), self._waited_ns()
        self._timer.start()

    def _beat(self) -> None:
        now, waited = self._clock.nsecsElapsed(), self._waited_ns()
        self.gaps.append((now - self._last) / 1e6)
        self.waits.append((waited - self._wait0) / 1e6)
        self._last, self._wait0 = now, waited

    def stop(self) -> dict[str, float]:
        """The longest gap, its p99, and the longest once the waits for a CPU are taken out
        (the first beat, which counts from ``start``, is left out)."""
        self._timer.stop()
        if self._sched is not None:
            self._sched.close()
        gaps, waits = self.gaps[1:], self.waits[1:]
        ordered = sorted(gaps)
        longest = max(range(len(gaps)), key=gaps.__getitem__)
        return {"max_gap_ms": ordered[-1], "p99_gap_ms": ordered[int(len(ordered) * 0.99) - 1],
                "max_gap_cpu_wait_ms": waits[longest],
                "max_gap_at_s": (sum(self.gaps[:longest + 2])) / 1000,  # when it ended
                "max_gap_less_cpu_wait_ms": max(g - w for g, w in zip(gaps, waits, strict=True)),
                "beats": len(gaps)}


def _gap_text(r: dict[str, float]) -> str:
    return (f"longest gap between {HEARTBEAT_MS} ms heartbeats {r['max_gap_ms']:.1f} ms (ending "
            f"{r['max_gap_at_s']:.1f} s in; of it {r['max_gap_cpu_wait_ms']:.0f} ms waiting for a "
            f"CPU), p99 {r['p99_gap_ms']:.1f} ms; "
            f"longest without the waits for a CPU {r['max_gap_less_cpu_wait_ms']:.1f} ms "
            "(target: never > 50 ms)")


TRACE_SECONDS = 6.0
TRACE_RATE = 8000
TRACE_BATCH_MS = 50
TRACE_RING = 100_000  # the dock's default ring of live frames
TRACE_SIGNALS = 3  # signals in the live plot


def trace_at_full_load() -> dict[str, float]:
    """Heartbeat gaps while the monitor dock and live plot take 8,000 frames/s."""
    import threading

    from PySide6.QtCore import QEventLoop, QTimer
    from PySide6.QtWidgets import QApplication

    app = QApplication.instance() or QApplication([])
    from pdcp_studio.app.live.plot import LivePlot
    from pdcp_studio.app.trace.dock import MonitorDock
    from pdcp_studio.bus.events import ChannelValue, FrameSeen
    from pdcp_studio.bus.trace.monitor import FrameDecoder
    from pdcp_studio.model.refs import ChannelRef

    sys.path.insert(0, str(ROOT / "benchmarks"))
    from trace import node_map, traffic

    _devices, outputs = node_map()
    refs = {chan: ChannelRef(0x0A0 + dev - 10, 0x10, 1000 + dev - 10, index)
            for chan, dev, index, *_ in outputs}
    dock = MonitorDock(capacity=TRACE_RING)
    plot = LivePlot()
    plot.set_channel(refs[outputs[0][0]])
    for chan, *_ in outputs[1:TRACE_SIGNALS]:
        plot.add_channel(refs[chan])
    dock.resize(900, 500)
    plot.resize(600, 300)
    dock.show()
    plot.show()
    settle = QEventLoop()  # in the app both are shown and painted before the bus gets busy:
    QTimer.singleShot(300, settle.quit)  # their first paint is not counted here
    settle.exec()
    frames = traffic(int(TRACE_SECONDS * TRACE_RATE) + 10_000)
    batches: list[tuple[list[FrameSeen], list[ChannelValue]]] = []
    lock = threading.Lock()
    stop = threading.Event()

    def session_thread() -> None:
        """Decodes off the GUI thread, as the session's arbitrator does."""
        decoder = FrameDecoder()
        per_batch = TRACE_RATE * TRACE_BATCH_MS // 1000
        t0 = time.perf_counter()
        i = 0
        while not stop.is_set() and i + per_batch <= len(frames):
            seen, values = [], []
            for arbitration_id, data, extended in frames[i:i + per_batch]:
                now = time.time()
                frame = decoder.decode(arbitration_id, data, now, is_extended_id=extended)
                seen.append(FrameSeen(now, arbitration_id, data, frame.line))
                ref = refs.get(arbitration_id & 0xFF)
                if ref is not None and frame.function == "Channel data":
                    values.append(ChannelValue(ref, float(int.from_bytes(data[:2], "little")),
                                               now))
            with lock:
                batches.append((seen, values))
            i += per_batch
            delay = t0 + (i / TRACE_RATE) - time.perf_counter()
            if delay > 0:
                time.sleep(delay)

    def deliver() -> None:  # the bridge's queued signal, on the GUI thread
        with lock:
            ready = batches[:]
            batches.clear()
        for seen, values in ready:
            dock.add_frames(seen)
            plot.add_values(values)
            delivered["frames"] += len(seen)

    delivered = {"frames": 0}
    heart = _Heart()
    feed = QTimer()
    feed.setInterval(TRACE_BATCH_MS)
    feed.timeout.connect(deliver)
    worker = threading.Thread(target=session_thread)
    worker.start()
    heart.start()
    feed.start()
    t0 = time.perf_counter()
    cpu0 = time.thread_time()  # the GUI thread's own CPU time: a figure the load cannot skew
    QTimer.singleShot(int(TRACE_SECONDS * 1000), app.quit)
    app.exec()
    wall = time.perf_counter() - t0
    gui_cpu = time.thread_time() - cpu0
    stop.set()
    worker.join()
    beats = heart.stop()
    feed.stop()

    result = {"frames": delivered["frames"], "rate": delivered["frames"] / wall,
              "gui_cpu_ms_per_s": gui_cpu / wall * 1000,
              "rss_mb": _peak_rss_mb(),
              **beats, "ring": len(dock.live_store), "capacity": dock.capacity,
              "plot_points": sum(len(x.ts) for x in plot.series),
              "signals": len(plot.series)}
    dock.close()
    plot.close()
    dock.deleteLater()  # its timers stop with it: the next round measures its own dock
    plot.deleteLater()
    app.processEvents()
    return result


def print_trace() -> None:
    for n in range(1, HEARTBEAT_ROUNDS + 1):
        r = trace_at_full_load()
        print(f"trace at full load, round {n}: {r['frames']:,} frames in {TRACE_SECONDS:.0f} s "
              f"({r['rate']:,.0f} frames/s; bus bound 7,400–10,500) into the monitor dock and "
              f"live plot — {_gap_text(r)};"
              f" GUI thread busy {r['gui_cpu_ms_per_s']:.0f} ms of CPU a second;"
              f" ring {r['ring']:,} of {r['capacity']:,} rows, plot {r['signals']} signals with "
              f"{r['plot_points']:,} values; peak RSS {r['rss_mb']:.0f} MB; {_load()}")


CAPTURE_SIZES = (1_000_000, 5_000_000)
#: Peak RSS of the whole app process with a capture open, whatever its length.
CAPTURE_RSS_TARGET_MB = 150


def capture_path(frames: int) -> Path:
    """The benchmark capture of ``benchmarks/trace.py`` (written there once, then cached)."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from trace import traffic, write_capture

    cache = Path(tempfile.gettempdir()) / "pdcp-trace-bench"
    cache.mkdir(exist_ok=True)
    path = cache / f"mixed-{frames}-v1.blf"
    if not path.exists():
        partial = path.with_name(path.name + ".tmp.blf")
        write_capture(partial, traffic(frames))
        partial.replace(path)
    return path


def capture_in_the_trace(frames: int) -> dict[str, float]:
    """Open the capture in the monitor dock: first rows, full index, gaps, filter, search."""

    from PySide6.QtCore import QEventLoop, QTimer
    from PySide6.QtWidgets import QApplication

    QApplication.instance() or QApplication([])
    from pdcp_studio.app.trace import dock as monitor_dock
    from pdcp_studio.app.trace.dock import MonitorDock

    path = capture_path(frames)
    dock = MonitorDock()
    dock.resize(1200, 600)
    dock.show()
    for thread in monitor_dock._WARM:  # in the app the dock is made long before a capture
        thread.join()  # is opened: its readers are imported by then
    settle = QEventLoop()  # ... and shown and painted: its first paint is not counted here
    QTimer.singleShot(500, settle.quit)
    settle.exec()
    heart = _Heart()
    heart.start()
    marks: dict[str, float] = {}

    def wait_for(key: str, limit_s: float = 600.0) -> None:
        """Run the event loop, as the app does, until ``marks[key]`` is set (checked each
        millisecond, so it may also be set at once)."""
        loop = QEventLoop()
        poll = QTimer()
        t_start = time.perf_counter()

        def check() -> None:
            if "first" not in marks and dock.model.rowCount():
                marks["first"] = time.perf_counter() - t0
            if key in marks or time.perf_counter() - t_start > limit_s:
                loop.quit()

        poll.timeout.connect(check)
        poll.start(1)
        loop.exec()
        poll.stop()

    t0 = time.perf_counter()
    dock.loaded.connect(lambda _p: marks.setdefault("loaded", time.perf_counter() - t0))
    cpu0 = time.thread_time()
    dock.load_capture(path)
    wait_for("loaded")
    load_cpu = time.thread_time() - cpu0
    beats = heart.stop()
    frames = dock.model.rowCount()
    t1 = time.perf_counter()
    dock.filtered.connect(lambda: marks.setdefault("filtered", time.perf_counter() - t1))
    dock.set_filter(function="Device Beacon")
    wait_for("filtered")
    filter_s, shown = marks["filtered"], dock.model.rowCount()
    dock.set_filter()
    t2 = time.perf_counter()
    dock.found.connect(lambda row: (marks.setdefault("row", row),
                                    marks.setdefault("search", time.perf_counter() - t2)))
    dock.find_frame("Bind Device Request Response", forward=False)  # from the end backwards
    wait_for("search")
    search_s = marks["search"]
    result = {"frames": frames, "first_s": marks["first"], "loaded_s": marks["loaded"],
              **beats,
              "gui_cpu_ms_per_s": load_cpu / marks["loaded"] * 1000,
              "filter_s": filter_s, "filtered": shown, "search_s": search_s,
              "found_row": marks.get("row", -1),
              "rss_mb": _peak_rss_mb(),
              "mb": path.stat().st_size / 1e6}
    dock.close()
    return result


def print_capture() -> None:
    """Each size in a process of its own, so each peak RSS is that capture's alone."""
    sizes: tuple[int, ...] = CAPTURE_SIZES
    if "--frames" in sys.argv:
        sizes = tuple(int(n) for n in sys.argv[sys.argv.index("--frames") + 1].split(","))
    for frames in sizes:
        capture_path(frames)  # written here: making it holds every frame, the app need not
        subprocess.run([sys.executable, __file__, "--capture-frames", str(frames)], check=True)


def print_one_capture(frames: int) -> None:
    r = capture_in_the_trace(frames)
    print(f"capture in the trace: {r['frames']:,} frames ({r['mb']:.0f} MB BLF) — first rows "
          f"after {r['first_s'] * 1000:.0f} ms (target < 1 s), all indexed after "
          f"{r['loaded_s']:.1f} s ({r['frames'] / r['loaded_s']:,.0f} frames/s); GUI thread "
          f"while loading: {_gap_text(r)}, busy {r['gui_cpu_ms_per_s']:.0f} ms of CPU a second; filter over all frames {r['filter_s'] * 1000:.0f} ms "
          f"({r['filtered']:,} rows), search from the end {r['search_s'] * 1000:.0f} ms "
          f"(row {r['found_row']:,}); peak RSS of the process {r['rss_mb']:.0f} MB (target "
          f"< {CAPTURE_RSS_TARGET_MB} MB whatever the length; frames and texts in temporary "
          f"files); {_load()}", flush=True)


def _peak_rss_mb() -> float:
    """This process's peak RSS in MB: the kernel's high-water mark of its own memory
    (``VmHWM``). ``getrusage``'s ``ru_maxrss`` is not used: Linux carries it over ``exec``
    from the parent that forked the process, so a capture's process would report the
    whole benchmark's peak."""
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def _load() -> str:
    """The machine's load while measuring: gaps depend on it, CPU figures do not."""
    return f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores"


def main() -> None:
    if "--capture-frames" in sys.argv:
        print_one_capture(int(sys.argv[sys.argv.index("--capture-frames") + 1]))
        return
    if "--only" in sys.argv and sys.argv[-1] == "trace":
        print_trace()
        return
    if "--only" in sys.argv and "capture" in sys.argv:
        print_capture()
        return
    if "--only" in sys.argv and sys.argv[-1] == "scan":
        print_scans()
        return
    if "--only" in sys.argv and sys.argv[sys.argv.index("--only") + 1] == "startup":
        print_startup()
        return
    if "--only" in sys.argv and sys.argv[sys.argv.index("--only") + 1] == "big":
        print_big()
        return
    print_startup()
    print_big()
    print_scans()
    print_trace()
    print_capture()


if __name__ == "__main__":
    main()
