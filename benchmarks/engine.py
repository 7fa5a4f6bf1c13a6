"""Profile-layer speed on generated prostheses of 25, 100 and 254 devices (issue 3).

Targets on the 2-core CI machine: a 254-device autoconfigure under 150 ms in the process
and the whole ``pdcp-studio plan autoconfigure --system X --json`` command under 1 s; time
growing no faster than n·log n from 25 to 254 devices. Also times the start-up procedure
with replacements (a stored configuration, a reset, a tenth of the devices swapped for
similar ones). Prints the median and best of several runs.

    python benchmarks/engine.py [--sizes 25,100,254] [--runs R] [--seed S]
"""

from __future__ import annotations

import argparse
import math
import random
import subprocess
import sys
import tempfile
from functools import partial
from pathlib import Path
from typing import Any

from _timing import median_and_best

from pdcp_studio.engine import configuration_from_system, plan_autoconfigure, plan_startup
from pdcp_studio.model import Channel, ConfigCollection, Device, Direction, System
from pdcp_studio.storage import system_file

AUTOCONFIGURE_TARGET_MS = 150.0
COMMAND_TARGET_MS = 1000.0
SOLE, TERMINAL = 0x0200, 0x0100
TYPES = (0x5000, 0x7000, 0x9000, 0x8400, 0x4000, 0xD000)


def _profile(rng: random.Random, root: int) -> int:
    """A standard (even-component) profile under ``root``, 2–4 levels deep."""
    depth = rng.choice((2, 3, 3, 4))
    comps = [root] + [rng.choice((2, 4, 6, 8)) for _ in range(depth - 1)]
    return sum(c << (12 - 4 * i) for i, c in enumerate(comps))


def make_device(rng: random.Random, serial: int, kind: str) -> Device:
    """One device of a prosthesis: sensor, control unit or terminal device (~8 channels)."""
    d = Device(0x0A51, {"sensor": 1, "control": 2, "terminal": 3}[kind], serial,
               name=f"{kind} {serial}")
    index = 0

    def add(direction: Direction, root: int, flags: int = 0, **kw: Any) -> Channel:
        nonlocal index
        index += 1
        t = rng.choice(TYPES) | (flags if direction is Direction.INPUT else 0)
        return d.add_channel(Channel(index, direction, t, _profile(rng, root), **kw))

    if kind == "sensor":
        for _ in range(rng.randint(4, 10)):
            add(Direction.OUTPUT, 0x4)
    elif kind == "control":
        ins = [add(Direction.INPUT, 0x4, SOLE if rng.random() < 0.5 else 0).index
               for _ in range(rng.randint(3, 6))]
        for _ in range(rng.randint(3, 6)):
            add(Direction.OUTPUT, 0x2, required_inputs=tuple(sorted(rng.sample(ins, 2))),
                desired_inputs=tuple(sorted(rng.sample(ins, 1))))
    else:
        for _ in range(rng.randint(4, 9)):
            ch = add(Direction.INPUT, 0x2, TERMINAL | (SOLE if rng.random() < 0.7 else 0))
            ch.terminal_profile = ch.profile
        if rng.random() < 0.3:  # a combined terminal + sensor device (encoders)
            add(Direction.OUTPUT, 0x4)
    return d


def make_system(n_devices: int, seed: int) -> System:
    rng = random.Random(seed)
    kinds = rng.choices(("sensor", "control", "terminal"), weights=(4, 2, 4), k=n_devices)
    return System(make_device(rng, serial, kind) for serial, kind in enumerate(kinds, 1))


def swapped(system: System, seed: int) -> System:
    """After a reset with a tenth of the devices replaced by similar ones (new serials)."""
    rng = random.Random(seed)
    s = system.copy()
    s.clear_links()  # the arbitrator forgets; the devices keep their source fields
    keys = sorted(s.devices)
    for key in rng.sample(keys, max(1, len(keys) // 10)):
        old = s.devices[key]
        old.present = False
        kind = old.name.split()[0]
        s.add_device(make_device(random.Random(rng.random()), 1000 + old.serial, kind))
    return s


def _command_ms(path: Path, runs: int) -> tuple[float, float]:
    cmd = [sys.executable, "-m", "pdcp_studio", "plan", "autoconfigure", "--system", str(path),
           "--json"]
    return median_and_best(lambda: subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL), runs)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="25,100,254")
    ap.add_argument("--runs", type=int, default=15)
    ap.add_argument("--seed", type=int, default=3)
    args = ap.parse_args()
    sizes = [int(n) for n in args.sizes.split(",")]

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            s = make_system(n, args.seed + n)
            channels = sum(len(d.channels) for d in s.devices.values())
            plan = plan_autoconfigure(s)
            auto = median_and_best(partial(plan_autoconfigure, s), args.runs)

            configured = s.copy()
            plan.apply(configured)
            stored = ConfigCollection([configuration_from_system(configured)])
            after = swapped(configured, args.seed)
            start_plan = plan_startup(after, stored)
            replaced = sum(a.rule.value == "replacement" for a in start_plan.actions)
            start = median_and_best(partial(plan_startup, after, stored), args.runs)

            path = Path(tmp) / f"system-{n}.json"
            system_file.save_path(s, path)
            cmd = _command_ms(path, max(3, args.runs // 3))
            rows.append((n, channels, len(plan.final_links), auto, replaced, start, cmd))

    n0, a0, s0 = rows[0][0], rows[0][3][0], rows[0][5][0]
    print(f"{'devices':>7} {'channels':>8} {'links':>5} | {'autoconf ms':>11} {'best':>6} "
          f"{'x25':>5} | {'startup ms':>10} {'repl':>4} {'x25':>5} | {'command ms':>10} | "
          f"{'n·log n x25':>11}")
    ok = True
    for n, ch, links, auto, repl, start, cmd in rows:
        nlogn = (n * math.log(n)) / (n0 * math.log(n0))
        print(f"{n:>7} {ch:>8} {links:>5} | {auto[0]:>11.1f} {auto[1]:>6.1f} "
              f"{auto[0] / a0:>5.1f} | {start[0]:>10.1f} {repl:>4} {start[0] / s0:>5.1f} | "
              f"{cmd[0]:>10.0f} | {nlogn:>11.1f}")
        if n >= 254:
            ok &= auto[0] < AUTOCONFIGURE_TARGET_MS and cmd[0] < COMMAND_TARGET_MS
    last = rows[-1]
    print(f"targets at {last[0]} devices: autoconfigure {last[3][0]:.1f} ms "
          f"(< {AUTOCONFIGURE_TARGET_MS:.0f}), command {last[6][0]:.0f} ms "
          f"(< {COMMAND_TARGET_MS:.0f}): {'met' if ok else 'MISSED'}")
    growth = last[3][0] / a0
    bound = (last[0] * math.log(last[0])) / (n0 * math.log(n0))
    print(f"growth {n0}→{last[0]}: autoconfigure x{growth:.1f}, n·log n x{bound:.1f}: "
          f"{'within' if growth <= bound else 'FASTER THAN'} n·log n")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
