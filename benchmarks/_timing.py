"""The timing loop the benchmark scripts share (imported from the script's own folder)."""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable


def median_and_best(fn: Callable[[], object], runs: int) -> tuple[float, float]:
    """Run ``fn`` ``runs`` times; the median and best wall time in milliseconds."""
    samples = []
    for _ in range(runs):
        t0 = time.perf_counter()
        fn()
        samples.append((time.perf_counter() - t0) * 1000)
    return statistics.median(samples), min(samples)
