"""The set-up pool: devices are read there (requests to different devices overlap), and the
wire work the dispatch thread must not wait for (departures, re-made links) runs there.

A job submitted through :meth:`JobPool.submit` counts as business (the arbitrator is not
settled, start-up waits) until it returns; set-ups are counted by the set-up part itself,
through :meth:`JobPool.run`.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor


class JobPool:
    """A thread pool and the count of its jobs in flight (guarded by the arbitrator's lock)."""

    def __init__(self, workers: int, name: str, lock: threading.RLock) -> None:
        self._executor = ThreadPoolExecutor(workers, thread_name_prefix=f"pdcp {name} setup")
        self._lock = lock
        self._jobs = 0  # jobs in flight besides set-ups (departures …)

    def run(self, job: Callable[[], None]) -> None:
        """Put ``job`` on the pool, uncounted; RuntimeError once the pool is shut down."""
        self._executor.submit(job)

    def submit(self, job: Callable[[], None]) -> None:
        """Run ``job`` on the pool, counted until it returns (dropped when closing)."""
        with self._lock:
            self._jobs += 1
        try:
            self._executor.submit(self._counted, job)
        except RuntimeError:  # closing
            self._done()

    def _counted(self, job: Callable[[], None]) -> None:
        try:
            job()
        finally:
            self._done()

    def _done(self) -> None:
        with self._lock:
            self._jobs -= 1

    def busy(self) -> bool:
        """Under the lock: counted jobs are in flight."""
        return bool(self._jobs)

    def shutdown(self) -> None:
        """Stop taking jobs and drop the queued ones (running ones finish on their own)."""
        self._executor.shutdown(wait=False, cancel_futures=True)


__all__ = ["JobPool"]
