"""A PC killed in the middle of a change (issue 8): the archive stays intact and the
prosthesis holds the old or the new configuration, never a mix.

Each child process opens a simulated prosthesis whose arbitrator memory is a file, says
"ready", and on "go" runs transactions back to back — alternating two stored configurations
(with the live links that go with them), each recorded in ONE fitting history shared by all
children — until the parent SIGKILLs it at a random moment. 60 kill points, eight children at a
time. Afterwards the shared archive must verify, and every memory file must read as exactly one
of the configurations written (or the empty one it started with). Every change a child
announced is in the archive after ``recover``: finished, or ``interrupted``.
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from pdcp_studio.bus.arbitrator.memory import MemoryStore
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.storage import config_codec
from pdcp_studio.storage.history import History

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="needs SIGKILL")

KILL_POINTS = 60
PARALLEL = 8
#: The kill comes this long after "go" at most (a few transactions' time on a busy machine);
#: the bound grows (up to ``MAX_DELAY_LIMIT_S``) while children die before finishing one: a
#: loaded machine's transactions are slower, and kills that all land before the first would
#: test nothing.
MAX_DELAY_S = 0.4
MAX_DELAY_LIMIT_S = 4.0

CHILD = r"""
import sys
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.transaction import Change
from pdcp_studio.storage import config_codec
from pdcp_studio.storage.history import History

memory, history_path, a_path, b_path = sys.argv[1:5]
configs = [config_codec.load_path(a_path), config_codec.load_path(b_path)]
session = open_session("sim:thesis-test2", memory=memory, data_rate_hz=0)
links = session.system().links
history = History(history_path)
print("ready", flush=True)
sys.stdin.readline()
n = 0
while True:
    cfg = configs[n % 2]
    keep = {(sl.output.ref, sl.input.ref) for sl in cfg.configurations[0].links}
    change = Change.links_to(session.system().links,
                             [lk for lk in links if (lk.output, lk.input) in keep],
                             f"kill test {n}")
    change.configuration = cfg
    session.transact(change, history=history, operator="kill test")
    print("done", flush=True)
    n += 1
"""


def _collection(n_links: int) -> ConfigCollection:
    def ch(serial: int, index: int, ctype: int, profile: int) -> StoredChannel:
        return StoredChannel(index, 2, 2, serial, ctype, profile)

    all_links = [
        StoredLink(ch(5, 2, 0x5200, 0x2110), ch(4, 1, 0x5000, 0x2120), 1),
        StoredLink(ch(6, 1, 0x7100, 0x1110), ch(5, 3, 0x5100, 0x1100), 2),
        StoredLink(ch(6, 2, 0x7200, 0x1220), ch(5, 5, 0x5200, 0x1220), 3),
    ]
    return ConfigCollection([StoredConfiguration(1, all_links[:n_links])])


def _run_and_kill(seed: int, tmp: Path, history: Path, a: Path, b: Path,
                  max_delay: list[float] | None = None) -> Path:
    memory = tmp / f"memory-{seed}.bin"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.Popen([sys.executable, "-c", CHILD, str(memory), str(history), str(a),
                             str(b)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL, text=True, env=env)
    try:
        assert proc.stdout.readline().strip() == "ready"
        proc.stdin.write("go\n")
        proc.stdin.flush()
        bound = max_delay[0] if max_delay is not None else MAX_DELAY_S
        delay = random.Random(seed).uniform(0.0, bound)
        time.sleep(delay)
        proc.send_signal(signal.SIGKILL)
    finally:
        proc.kill()
        proc.wait(30)
        finished = proc.stdout.read().count("done")
        proc.stdout.close()
        proc.stdin.close()
    if max_delay is not None and not finished and delay >= bound / 2:  # it had its chance
        max_delay[0] = min(max_delay[0] * 1.25, MAX_DELAY_LIMIT_S)
    return memory


def test_killed_at_random_points_the_archive_and_the_prosthesis_stay_whole(tmp_path):
    a, b = tmp_path / "a.pdcfg", tmp_path / "b.pdcfg"
    config_codec.save_path(_collection(3), a)
    config_codec.save_path(_collection(1), b)
    allowed = {config_codec.dumps(_collection(3)), config_codec.dumps(_collection(1)), None}
    history = tmp_path / "history.sqlite3"
    History(history).close()
    started = time.monotonic()
    max_delay = [MAX_DELAY_S]
    with ThreadPoolExecutor(PARALLEL) as pool:
        memories = list(pool.map(
            lambda s: _run_and_kill(s, tmp_path, history, a, b, max_delay),
            range(KILL_POINTS)))
    elapsed = time.monotonic() - started
    for memory in memories:
        store = MemoryStore(memory)
        got = store.read_bytes()
        assert got in allowed, f"{memory}: a mix of the old and the new configuration"
    with History(history) as h:
        assert h.verify().ok  # intact before the interrupted changes are recorded …
        recovered = h.recover()
        report = h.verify()  # … and after
        entries = h.entries()
        left = h._db.execute("SELECT COUNT(*) FROM pending").fetchone()[0]
    assert report.ok, report.reason
    assert left == 0
    assert len(entries) >= KILL_POINTS // 4, "most children never finished a transaction"
    assert {e["outcome"]["status"] for e in entries} <= {"applied", "interrupted"}
    assert all(entries[i - 1]["outcome"]["status"] == "interrupted" for i in recovered)
    print(f"{KILL_POINTS} kill points, {len(entries)} transactions recorded "
          f"({len(recovered)} interrupted), {elapsed:.1f} s, kills within "
          f"{max_delay[0]:.2f} s")


HOST_LINK_POINTS = 12


@pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")
def test_a_client_killed_during_a_change_over_the_host_link_leaves_old_or_new_links(tmp_path):
    """The arbitrator carries a TRANSACT out whole: killing the PC's CLI at random moments of
    ``apply clear|autoconfigure --yes`` leaves the live links all old or all new."""
    from pdcp_studio.model import parameters as P
    from pdcp_studio.storage.history import History as Archive
    from tests.road_rigs import served

    archive = tmp_path / "history.sqlite3"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path),
           "PDCP_STUDIO_HISTORY": str(archive)}
    with served("thesis-test2", tmp_path / "memory.bin") as (arbitrator, _host, url):
        full = sorted(arbitrator.system().links)
        assert len(full) == 3
        rng = random.Random(8)
        flips = 0
        entered = threading.Event()
        real = arbitrator.transact

        def transact(*args, **kwargs):  # the arbitrator's side of TRANSACT: note its start
            entered.set()
            return real(*args, **kwargs)

        arbitrator.transact = transact
        for n in range(HOST_LINK_POINTS):
            entered.clear()
            mode = "clear" if arbitrator.system().links else "autoconfigure"
            proc = subprocess.Popen([sys.executable, "-m", "pdcp_studio", "apply", mode,
                                     "--bus", url, "--yes"], stdout=subprocess.DEVNULL,
                                    stderr=subprocess.DEVNULL, env=env)
            if n % 3 == 0:  # a third at any moment, the rest around the request itself
                time.sleep(rng.uniform(0.0, 1.0))
            else:
                entered.wait(30)
                time.sleep(rng.uniform(0.0, 0.08))
            proc.kill()
            proc.wait(30)
            assert arbitrator.wait_settled(10)
            links = sorted(arbitrator.system().links)
            assert links in (full, []), f"kill point {n}: a mix of old and new links: {links}"
            flips += (links == []) == (mode == "clear")
            for link in full:  # the devices agree with the arbitrator
                want = b"\x01" if links else b"\x00"
                assert arbitrator.get_parameter(link.input.device, P.CH_DATA_ENABLED,
                                                link.input.index) == want
        print(f"{HOST_LINK_POINTS} host-link kill points, {flips} changes made")
    with Archive(archive) as h:
        h.recover()
        assert h.verify().ok
        statuses = [e["outcome"]["status"] for e in h.entries()]
    assert set(statuses) <= {"applied", "interrupted"}
    print(f"history: {statuses.count('applied')} applied, {statuses.count('interrupted')} "
          "interrupted")
