"""Opening the simulated prosthesis (issue 11, the bus side of the app's start-up).

``open_session("sim:transradial")`` runs on a thread of the app from its first moments to
the window going live: it is the start-up's critical path. This script opens it in a fresh
process as the app does (python-can already imported, the app's 1 ms switch interval) and
prints, for the first open (imports of the arbitrator's modules included) and for later
opens: CPU seconds of the whole process, wall seconds, frames on the bus, and voluntary
context switches (each a thread that slept and was woken: a queue or lock hand-over).
``--busy`` adds a thread that keeps the interpreter busy, as the GUI thread does while the
window is built; then every hand-over of a frame between threads waits for the lock. Each
open's CPU is also split by thread (the opening thread, the arbitrator's dispatch, set-up and
profile threads, the device host's), read from each thread's own clock before it is closed.

The physical bound: the devices' bind requests, the arbitrator's set-up reads and start-up's
link writes are ~450 frames of 8 bytes, 60 ms on a 1 Mbit/s bus; the in-process bus has no
wire, so what is left is Python's work per frame and per thread hop.

Run: ``python benchmarks/sim_open.py [--runs N] [--busy] [--url sim:NAME] [--compare REF]``;
``--compare REF`` (a git commit, e.g. the one before a change) measures that version too,
interleaved with this one run by run (the machine's speed drifts), and prints both.
"""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RUNS = 5
LATER_OPENS = 3
SWITCH_INTERVAL_S = 0.001  # as app/application.share_the_interpreter sets it


def _usage() -> tuple[float, int]:
    ru = resource.getrusage(resource.RUSAGE_SELF)
    return ru.ru_utime + ru.ru_stime, ru.ru_nvcsw


def _role(thread: threading.Thread) -> str:
    """A thread's job in a name without the URL or a pool number: ``setup``, ``devices``…"""
    words = thread.name.split()
    role = words[-1].rstrip("_0123456789") if len(words) > 1 else "other"
    return {"arbitrator": "dispatch"}.get(role, role)


def _thread_cpu(older: set[threading.Thread]) -> dict[str, float]:
    """CPU seconds of each role's threads, those not in ``older`` and still running."""
    cpu: dict[str, float] = {}
    for thread in threading.enumerate():
        if thread in older or thread.ident is None:
            continue
        try:
            used = time.clock_gettime(time.pthread_getcpuclockid(thread.ident))
        except (OSError, AttributeError):  # a thread that has just ended
            continue
        cpu[_role(thread)] = cpu.get(_role(thread), 0.0) + used
    return cpu


def _busy(stop: threading.Event) -> None:
    """A thread that wants the interpreter all the time (the GUI thread building a window)."""
    n = 0
    while not stop.is_set():
        for i in range(200):
            n += i * i


def one_process(url: str, busy: bool) -> None:
    """Child: open and close ``url`` 1 + LATER_OPENS times; print one line per open."""
    sys.setswitchinterval(SWITCH_INTERVAL_S)
    import can  # noqa: F401  (the app has it imported by then)

    stop = threading.Event()
    if busy:
        threading.Thread(target=_busy, args=(stop,), daemon=True).start()
    for n in range(1 + LATER_OPENS):
        before = set(threading.enumerate())
        cpu0, csw0 = _usage()
        opener0 = time.thread_time()
        t0 = time.perf_counter()
        from pdcp_studio.bus.session.opening import open_session

        session = open_session(url)
        wall = time.perf_counter() - t0
        cpu1, csw1 = _usage()
        threads = {"opener": time.thread_time() - opener0, **_thread_cpu(before)}
        arb, host = session.arbitrator.conn, session.host.conn  # type: ignore[attr-defined]
        frames = arb.sent + host.sent
        t1 = time.perf_counter()
        session.close()
        close = time.perf_counter() - t1
        print(f"open={n} cpu={cpu1 - cpu0:.4f} wall={wall:.4f} frames={frames} "
              f"wakeups={csw1 - csw0} close={close:.4f} "
              + " ".join(f"cpu_{role}={s:.4f}" for role, s in sorted(threads.items())),
              flush=True)
    stop.set()


def _export(ref: str, into: Path) -> Path:
    """The package (and its resources) as of git commit ``ref``, compiled, under ``into``."""
    import compileall
    import tarfile

    archive = into / "tree.tar"
    subprocess.run(["git", "archive", "-o", str(archive), ref, "pdcp_studio", "resources"],
                   cwd=ROOT, check=True)
    with tarfile.open(archive) as tar:
        tar.extractall(into, filter="fully_trusted")
    compileall.compile_dir(into / "pdcp_studio", quiet=1)
    return into


def main() -> None:
    if "--child" in sys.argv:
        one_process(sys.argv[sys.argv.index("--child") + 1], "--busy" in sys.argv)
        return
    import tempfile

    runs = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else RUNS
    url = sys.argv[sys.argv.index("--url") + 1] if "--url" in sys.argv else "sim:transradial"
    busy = "--busy" in sys.argv
    ref = sys.argv[sys.argv.index("--compare") + 1] if "--compare" in sys.argv else None
    with tempfile.TemporaryDirectory(prefix="pdcp-sim-open-") as tmp:
        trees = {"this version": ROOT}
        if ref is not None:
            trees[ref] = _export(ref, Path(tmp))
        rows: dict[str, tuple[list[dict[str, float]], list[dict[str, float]]]] = {
            name: ([], []) for name in trees}
        for _ in range(runs):
            for name, root in trees.items():
                out = subprocess.run([sys.executable, __file__, "--child", url]
                                     + (["--busy"] if busy else []), capture_output=True,
                                     text=True, env=dict(os.environ, PYTHONPATH=str(root)),
                                     cwd=root, timeout=120, check=True).stdout
                for line in out.splitlines():
                    row = {k: float(v) for k, v in (kv.split("=") for kv in line.split())}
                    rows[name][0 if row["open"] == 0 else 1].append(row)

    def show(label: str, got: list[dict[str, float]]) -> None:
        med = {k: statistics.median(r.get(k, 0.0) for r in got) for k in got[0]}
        roles = ", ".join(f"{k[4:]} {v * 1000:.1f}" for k, v in med.items()
                          if k.startswith("cpu_"))
        print(f"    {label}: CPU {med['cpu']:.3f} s, wall {med['wall']:.3f} s, "
              f"{med['frames']:.0f} frames, {med['wakeups']:.0f} thread wake-ups, "
              f"close {med['close']:.3f} s (medians of {len(got)}); CPU ms by thread: {roles}")

    print(f"open_session({url!r}){' beside a busy thread' if busy else ''}, switch interval "
          f"{SWITCH_INTERVAL_S * 1000:g} ms; bound: the frames' 60 ms on a 1 Mbit/s wire")
    for name, (first, later) in rows.items():
        print(f"  {name}:")
        show("first open (imports included)", first)
        show("later opens", later)


if __name__ == "__main__":
    main()
