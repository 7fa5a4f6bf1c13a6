"""Issue 24 item 5: a configuration written through the change road over a 128000-baud line
moves no more than it needs — at most 3.5× its size plus the device table — because the
preview and the record come from the arbitrator's tables and the stored configuration
(``benchmarks/host_link.py`` prints the same figures next to the physical minimum)."""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")

BENCH = Path(__file__).resolve().parents[2] / "benchmarks" / "host_link.py"


def test_a_configuration_through_the_change_road_moves_at_most_3_5_times_plus_the_table():
    spec = importlib.util.spec_from_file_location("host_link_bench", BENCH)
    assert spec is not None and spec.loader is not None
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    road = bench.run_road(bench.RATE)
    print(road)
    assert road["ok"], road
    assert 1500 <= road["size"] <= 2500
    assert road["bytes"] <= 3.5 * road["size"] + road["table"], road
