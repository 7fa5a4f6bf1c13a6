"""A PC killed in the middle of a change (issue 8): the archive stays intact and the
prosthesis holds the old or the new configuration, never a mix.

Each child process opens a simulated prosthesis whose arbitrator memory is a file, says
"ready", and on "go" runs transactions back to back — alternating two stored configurations
(with the live links that go with them), each recorded in ONE fitting history shared by all
children — until the parent SIGKILLs it at a random moment. 60 kill points, eight children at a
time. Afterwards the shared archive must verify, and every memory file must read as exactly one
of the configurations written (or the empty one it started with).
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from pdcp_studio.bus.memory import MemoryStore
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
#: The kill comes this long after "go" at most (a few transactions' time on a busy machine).
MAX_DELAY_S = 0.4

CHILD = r"""
import sys
from pdcp_studio.bus.session import open_session
from pdcp_studio.bus.transaction import Change
from pdcp_studio.storage import config_codec
from pdcp_studio.storage.history import History

memory, history_path, a_path, b_path = sys.argv[1:5]
configs = [config_codec.load_path(a_path), config_codec.load_path(b_path)]
session = open_session("sim:thesis-test2", memory=memory)
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


def _run_and_kill(seed: int, tmp: Path, history: Path, a: Path, b: Path) -> Path:
    memory = tmp / f"memory-{seed}.bin"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.Popen([sys.executable, "-c", CHILD, str(memory), str(history), str(a),
                             str(b)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL, text=True, env=env)
    try:
        assert proc.stdout.readline().strip() == "ready"
        proc.stdin.write("go\n")
        proc.stdin.flush()
        time.sleep(random.Random(seed).uniform(0.0, MAX_DELAY_S))
        proc.send_signal(signal.SIGKILL)
    finally:
        proc.kill()
        proc.wait(30)
        proc.stdout.close()
        proc.stdin.close()
    return memory


def test_killed_at_random_points_the_archive_and_the_prosthesis_stay_whole(tmp_path):
    a, b = tmp_path / "a.pdcfg", tmp_path / "b.pdcfg"
    config_codec.save_path(_collection(3), a)
    config_codec.save_path(_collection(1), b)
    allowed = {config_codec.dumps(_collection(3)), config_codec.dumps(_collection(1)), None}
    history = tmp_path / "history.sqlite3"
    History(history).close()
    started = time.monotonic()
    with ThreadPoolExecutor(PARALLEL) as pool:
        memories = list(pool.map(lambda s: _run_and_kill(s, tmp_path, history, a, b),
                                 range(KILL_POINTS)))
    elapsed = time.monotonic() - started
    for memory in memories:
        store = MemoryStore(memory)
        got = store.read_bytes()
        assert got in allowed, f"{memory}: a mix of the old and the new configuration"
    with History(history) as h:
        report = h.verify()
        entries = h.entries()
    assert report.ok, report.reason
    assert len(entries) >= KILL_POINTS // 4, "most children never finished a transaction"
    assert {e["outcome"]["status"] for e in entries} <= {"applied", "nothing"}
    print(f"{KILL_POINTS} kill points, {len(entries)} transactions recorded, "
          f"{elapsed:.1f} s")
