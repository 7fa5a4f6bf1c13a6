"""Benchmark: the fitting-history archive on both engines (issue 25).

Prints, for SQLite (a file, WAL, synchronous=FULL) and PostgreSQL (the server at ``--url``,
else a throw-away cluster started like the tests' one, tests/pg_cluster.py):

- appends per second with four workstations (four processes) recording at once — plain
  appends (one commit each) and changes (announce + record: two commits each, as the change
  road does), with the chain verified afterwards (no fork, no loss);
- the time of ``history list --patient REF`` among 100,000 entries (5,000 patients, 20
  entries each): the archive's own query (median of 20) and the whole command as a process
  (Python's start included, median of 5).

Run: ``python benchmarks/archive.py [--entries N] [--url postgresql://…] [--seconds S]``.
The PostgreSQL URL must name a database ``archive init`` has set up, signed in as a fitter;
the fill writes N entries into it.
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

WORKSTATIONS = 4
PATIENTS = 5000


def body(n: int) -> dict:
    """An entry about the size of a real one (a transradial prosthesis, three links)."""
    devs = [{"vid": 2641, "pid": 513 + k, "serial": 200 + (n % 97) + k} for k in range(4)]
    link = {"output": {"vid": 2641, "pid": 513, "serial": 201, "index": 3, "type": "0x9300",
                       "profile": "0x2220"},
            "input": {"vid": 2641, "pid": 769, "serial": 301, "index": 1, "type": "0x9300",
                      "profile": "0x2220"}}
    return {"time": "2026-11-28T10:00:00Z", "bus": "serial:/dev/ttyUSB0",
            "action": f"apply autoconfigure {n}", "devices": devs,
            "links_before": [link] * 3, "links_after": [link] * 3,
            "config_crc_before": "0x68A3", "config_crc_after": "0x1234", "verified": True,
            "interlock": "held 1 device", "patient": f"P-{n % PATIENTS:05d}",
            "plan": {"actions": [{"op": "add", **link, "reason": "most similar free output"}] * 3},
            "outcome": {"status": "applied", "step": "", "reason": "", "notes": []},
            "effect": {"text": ["Hand: power grip now follows the control unit"] * 4}}


def _worker(url: str, seconds: float, pairs: bool, start: float, out) -> None:
    from pdcp_studio.storage.archive import open_archive

    done = 0
    with open_archive(url) as archive:
        while time.time() < start:
            time.sleep(0.001)
        end = start + seconds
        while time.time() < end:
            if pairs:
                token = archive.begin(body(done))
                archive.finish(token, body(done))
            else:
                archive.append(body(done))
            done += 1
    out.put(done)


def concurrent(url: str, seconds: float, pairs: bool) -> float:
    """Entries per second, ``WORKSTATIONS`` processes recording at once."""
    from pdcp_studio.storage.archive import open_archive

    ctx = multiprocessing.get_context("spawn")
    out = ctx.Queue()
    with open_archive(url) as archive:
        before = len(archive.entries())
    start = time.time() + 2.0  # every process connected before the clock starts
    procs = [ctx.Process(target=_worker, args=(url, seconds, pairs, start, out))
             for _ in range(WORKSTATIONS)]
    for p in procs:
        p.start()
    counts = [out.get(timeout=seconds + 120) for _ in procs]
    for p in procs:
        p.join()
    with open_archive(url) as archive:
        report = archive.verify()
        after = report.entries
    assert report.ok, report.reason
    assert after - before == sum(counts), (after - before, counts)  # nothing lost
    return sum(counts) / seconds


def fill(url: str, n: int) -> float:
    """Append ``n`` entries in batches; seconds taken."""
    from pdcp_studio.storage.archive import open_archive

    t0 = time.perf_counter()
    with open_archive(url) as archive:
        have = len(archive.entries())
        batch = 2000
        for first in range(have, n, batch):
            archive.append_many([body(i) for i in range(first, min(n, first + batch))])
    return time.perf_counter() - t0


def list_patient(url: str) -> tuple[float, float, int]:
    """(ms of the archive's query, ms of the command as a process, entries found)."""
    from pdcp_studio.storage.archive import EntryFilter, open_archive

    samples = []
    found = 0
    with open_archive(url) as archive:
        for k in range(20):
            t0 = time.perf_counter()
            found = len(archive.entries(EntryFilter(patient=f"P-{(k * 37) % PATIENTS:05d}")))
            samples.append((time.perf_counter() - t0) * 1000)
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(ROOT), *os.environ.get("PYTHONPATH", "").split(os.pathsep)])}
    command = []
    for _ in range(5):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "pdcp_studio", "history", "list", "--json",
                        "--patient", "P-00042", "--archive", url], check=True, env=env,
                       stdout=subprocess.DEVNULL)
        command.append((time.perf_counter() - t0) * 1000)
    return statistics.median(samples), statistics.median(command), found


def engine(name: str, url: str, entries: int, seconds: float) -> None:
    plain = concurrent(url, seconds, pairs=False)
    pairs = concurrent(url, seconds, pairs=True)
    print(f"{name}: {WORKSTATIONS} workstations at once: {plain:.0f} appends/s "
          f"(one commit each), {pairs:.0f} changes/s (announce + record); chain intact")
    took = fill(url, entries)
    query, command, found = list_patient(url)
    print(f"{name}: filled to {entries} entries in {took:.1f} s; history list --patient "
          f"({found} of {entries}): {query:.1f} ms the query, {command:.0f} ms the command")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--entries", type=int, default=100_000)
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--url", help="a PostgreSQL archive (else a throw-away cluster)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        os.environ["XDG_DATA_HOME"] = folder  # the journal, never the user's
        engine("sqlite", f"sqlite:///{folder}/history.sqlite", args.entries, args.seconds)
        if args.url:
            engine("postgresql", args.url, args.entries, args.seconds)
            return 0
        from tests.pg_cluster import ADMIN, FITTER, Cluster, pg_bindir

        bindir = pg_bindir()
        if bindir is None:
            print("postgresql: skipped (no initdb/pg_ctl found; give --url)")
            return 0
        cluster = Cluster(bindir, durable=True)
        try:
            from pdcp_studio.storage.archive.postgres import init_schema

            cluster.sql("CREATE DATABASE bench")
            init_schema(cluster.url(ADMIN, "bench"))
            cluster.sql(f"CREATE ROLE {FITTER} LOGIN IN ROLE pdcp_fitter")
            engine("postgresql", cluster.url(FITTER, "bench"), args.entries, args.seconds)
        finally:
            cluster.remove()
    return 0


if __name__ == "__main__":
    sys.exit(main())
