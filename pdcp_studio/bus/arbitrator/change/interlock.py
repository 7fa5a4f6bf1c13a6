"""Reference §5's motion interlock: the devices that feed a terminal channel held still
(Suspend Device, bounded and renewed) while links change under a worn prosthesis.

Transactions and the profile layer's own plans use it alike, through :func:`holding` and an
:class:`Interlock` — the few things it needs of the arbitrator.
"""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Callable, Iterator
from dataclasses import dataclass

from pdcp_studio.bus.transaction import INTERLOCK_MS
from pdcp_studio.errors import PdcpError
from pdcp_studio.model.refs import DeviceKey


@dataclass(frozen=True)
class Interlock:
    """Suspend and release a device; how often a suspension is renewed (asked each time: a
    test shortens it); the arbitrator's name for the renewer's thread."""

    suspend: Callable[[DeviceKey, int], None]
    release: Callable[[DeviceKey], None]
    renew_s: Callable[[], float]
    name: str


class Renewer:
    """Renews the interlock's bounded suspension until stopped."""

    def __init__(self, suspend: Callable[[DeviceKey, int], None], keys: list[DeviceKey],
                 interval: float, name: str) -> None:
        self._suspend, self._keys, self._interval = suspend, keys, interval
        self._stop = threading.Event()
        self.failures: list[str] = []
        self._thread = threading.Thread(target=self._run, name=f"pdcp {name} interlock",
                                        daemon=True)
        if keys:
            self._thread.start()

    def _run(self) -> None:
        while not self._stop.wait(self._interval):
            for key in self._keys:
                try:
                    self._suspend(key, INTERLOCK_MS)
                except PdcpError as err:
                    self.failures.append(f"renewing the suspension of {key}: {err}")

    def stop(self) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(timeout=5.0)


class HoldRefused(PdcpError):
    """A device did not suspend for the motion interlock; those held before it are released."""

    def __init__(self, key: DeviceKey, why: PdcpError) -> None:
        self.key, self.why = key, why
        super().__init__(f"device {key} did not suspend ({why})")


@contextlib.contextmanager
def holding(interlock: Interlock, keys: list[DeviceKey], notes: list[str]
            ) -> Iterator[list[DeviceKey]]:
    """Each of ``keys`` suspended (bounded, renewed) around a block, every one held released
    afterwards whatever happens; HoldRefused when one does not suspend. Renewal and release
    failures are added to ``notes`` (a lost release ends on its own within ``INTERLOCK_MS``)."""
    held: list[DeviceKey] = []
    try:
        for key in keys:
            try:
                interlock.suspend(key, INTERLOCK_MS)
            except PdcpError as err:
                raise HoldRefused(key, err) from err
            held.append(key)
        renewer = Renewer(interlock.suspend, held, interlock.renew_s(), interlock.name)
        try:
            yield held
        finally:
            renewer.stop()
            notes += renewer.failures
    finally:
        for key in held:
            try:
                interlock.release(key)
            except PdcpError as err:
                notes.append(f"release of {key} failed ({err}); its suspension ends within "
                             f"{INTERLOCK_MS} ms on its own")


__all__ = ["HoldRefused", "Interlock", "Renewer", "holding"]
