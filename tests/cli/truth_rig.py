"""A prosthesis in three processes, as in a fitting room, whose arbitrator can be power-cycled.

Simulated devices run in one process (``pdcp-studio sim devices NAME|FILE --bus URL``), a
headless arbitrator in another (``pdcp-studio arbitrator --bus URL --host-serial pty --memory
FILE``), both on a python-can udp_multicast bus on loopback; the test drives the CLI over
``serial:/dev/pts/N``. :meth:`TruthRig.power_cycle` kills the arbitrator (SIGKILL: no goodbye,
as a battery pulled) and starts a new one on the same memory; the devices it finds bound reset
and bind again, and start-up runs on the stored configuration and policy.

Waiting is by condition (a line from the process, the arbitrator settled with every device
present), never by sleeping; the timeouts are generous for a busy 2-core machine.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import queue
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from pdcp_studio.bus.transaction import link_from_json
from pdcp_studio.cli.main import main
from pdcp_studio.errors import BusTimeoutError
from pdcp_studio.model.system import Link

#: Seconds a process gets to say it is up, and the arbitrator to bind and start up.
UP_S = 60.0
SETTLE_S = 60.0
#: Seconds the test's own host-link requests wait for a reply (the CLI keeps its own).
REPLY_S = 30.0
#: ``python -m pdcp_studio`` that SIGINT/SIGTERM stops even when the test run inherited
#: SIGINT ignored (a background ``pytest &``).
_STOPPABLE = ("import signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
              "from pdcp_studio.cli.main import main; sys.exit(main())")


class Child:
    """A ``pdcp-studio`` child process whose output is read line by line in a thread."""

    def __init__(self, args: list[str], *, stderr_lines: bool = False) -> None:
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join(
            [str(Path(__file__).resolve().parents[2]), env.get("PYTHONPATH", "")])
        # stderr on a pipe of its own: warnings written between the pieces of a stdout line
        # would otherwise land inside it ("host link on /dev/pts/4arbitrator: …").
        self.proc = subprocess.Popen([sys.executable, "-c", _STOPPABLE, *args],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True, env=env)
        self._stderr_lines = stderr_lines
        self.lines: list[str] = []
        self.errors: list[str] = []
        self._q: queue.SimpleQueue[str] = queue.SimpleQueue()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()
        self._err_reader = threading.Thread(target=self._read_errors, daemon=True)
        self._err_reader.start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self._q.put(line.rstrip("\n"))

    def _read_errors(self) -> None:
        assert self.proc.stderr is not None
        for line in self.proc.stderr:
            self.errors.append(line.rstrip("\n"))
            if self._stderr_lines:  # what it says on stderr is waited for too
                self._q.put(line.rstrip("\n"))

    def until(self, predicate: Any, timeout: float = UP_S) -> str | None:
        """The first line (from now on, or already read) for which ``predicate`` holds."""
        for line in self.lines:
            if predicate(line):
                return line
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            try:
                line = self._q.get(timeout=left)
            except queue.Empty:
                return None
            self.lines.append(line)
            if predicate(line):
                return line

    def kill(self) -> None:
        """SIGKILL: the process gets no chance to tidy up."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGKILL)
        self.proc.wait(30)

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(15)
            except subprocess.TimeoutExpired:
                self.kill()
        self._reader.join(5)
        self._err_reader.join(5)
        for pipe in (self.proc.stdout, self.proc.stderr):
            if pipe is not None:
                pipe.close()

    def text(self) -> str:
        """Everything it said so far: stdout, then stderr."""
        while True:
            try:
                self.lines.append(self._q.get_nowait())
            except queue.Empty:
                return "\n".join([*self.lines, "-- stderr:", *self.errors])


class TruthRig:
    """Devices and a power-cyclable arbitrator; ``url`` is the current host link."""

    def __init__(self, bus: str, memory: Path) -> None:
        self.bus, self.memory, self.count = bus, memory, 0
        self.devices: Child | None = None
        self.arbitrator: Child | None = None
        self.url = ""

    @classmethod
    @contextlib.contextmanager
    def running(cls, bus: str, memory: Path, devices: str, *, count: int
                ) -> Iterator[TruthRig]:
        """The rig with ``devices`` (a built-in prosthesis or a system file) set up."""
        rig = cls(bus, memory)
        try:
            rig.start_devices(devices, count)
            rig.start_arbitrator()
            yield rig
        finally:
            rig.close()

    # -- processes ------------------------------------------------------------------------
    def start_devices(self, what: str, count: int) -> None:
        """Run the devices of a built-in prosthesis or a system file (stopping any before)."""
        if self.devices is not None:
            self.devices.stop()
            if self.arbitrator is not None:
                self.wait_all_left()
        self.count = count
        self.devices = Child(["sim", "devices", what, "--bus", self.bus], stderr_lines=True)
        line = self.devices.until(lambda s: s.startswith("simulating "))
        assert line is not None and f"simulating {count} device(s)" in line, \
            self.devices.text()

    def start_arbitrator(self) -> None:
        self.arbitrator = Child(["arbitrator", "--bus", self.bus, "--host-serial", "pty",
                                 "--memory", str(self.memory)])
        line = self.arbitrator.until(lambda s: s.startswith("host link on "))
        assert line is not None, self.arbitrator.text()
        self.url = "serial:" + line.split(" on ", 1)[1].strip()
        self.wait_set_up()

    def power_cycle(self) -> None:
        """Kill the arbitrator and start a new one on the same memory; returns once every
        device has bound again and start-up has run."""
        assert self.arbitrator is not None
        self.arbitrator.kill()
        self.arbitrator.stop()
        self.start_arbitrator()

    def wait_set_up(self, timeout: float = SETTLE_S) -> None:
        """Until the arbitrator says it is settled (start-up done) with ``count`` devices
        present, asked over the host link (a slow reply on a busy machine is asked again)."""
        deadline = time.monotonic() + timeout
        present: list[Any] = []
        while True:
            left = deadline - time.monotonic()
            try:
                with self.session() as session:
                    present = [d for d in session.system().devices.values() if d.present]
                    if len(present) == self.count and session.wait_settled(max(left, 0.1)) \
                            and len([d for d in session.system().devices.values()
                                     if d.present]) == self.count:
                        return
            except BusTimeoutError:
                pass
            assert left > 0, (f"{len(present)} of {self.count} device(s) present, not "
                              "settled:\n" + (self.arbitrator.text() if self.arbitrator
                                              else ""))
            time.sleep(0.1)  # a poll interval, not a synchronisation

    def wait_all_left(self, timeout: float = SETTLE_S) -> None:
        """Until the arbitrator has noticed that every device of the stopped process is gone
        (their beacons stopped), so the next devices join a bus it sees as empty."""
        deadline = time.monotonic() + timeout
        with self.session() as session:
            while any(d.present for d in session.system().devices.values()):
                assert time.monotonic() < deadline, "the stopped devices did not leave"
                time.sleep(0.1)  # a poll interval, not a synchronisation

    def close(self) -> None:
        for child in (self.arbitrator, self.devices):
            if child is not None:
                child.stop()

    # -- reading it -----------------------------------------------------------------------
    def links(self) -> set[Link]:
        """The links as the arbitrator has them now (settled first)."""
        with self.session() as session:
            assert session.wait_settled(SETTLE_S)
            return set(session.system().links)

    def session(self) -> Any:
        """A session over the current host link, patient with a busy machine."""
        from pdcp_studio.bus.session.opening import open_session

        return open_session(self.url, reply_timeout=REPLY_S)


def cli(*args: str) -> tuple[int, str, str]:
    """Run ``pdcp-studio ARGS`` in this process: (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(list(args))
        except SystemExit as exc:  # argparse
            code = int(exc.code or 0)
    return code, out.getvalue(), err.getvalue()


def cli_json(*args: str) -> tuple[int, dict[str, Any]]:
    code, out, err = cli(*args, "--json")
    try:
        return code, json.loads(out)
    except json.JSONDecodeError as exc:
        raise AssertionError(f"exit {code}, not one JSON document: {out!r}\n{err}") from exc


def links_of(docs: list[dict[str, Any]]) -> set[Link]:
    return {link_from_json(d) for d in docs}


def after_power_on(links_now: set[Link], power_on: dict[str, Any]) -> set[Link]:
    """The links ``next_power_on`` says start-up leaves: now + added − removed."""
    return (links_now | links_of(power_on["links_added"])) - links_of(power_on["links_removed"])
