"""Small builders so that engine tests read like the thesis's figures.

``out(3, 0x1100, req=[2])`` is output channel 3 with profile 0x1100 that requires input 2;
``inp(1, 0x1110, terminal=True)`` is a terminal input whose terminal profile is its profile;
``dev(5, ...)`` is device VID 2, PID 2, serial 5 (the thesis rig's numbering);
``L(4, 1, 5, 2)`` is the link SN4.O1 → SN5.I2.
"""

from __future__ import annotations

import random
from pathlib import Path

from pdcp_studio.model import Channel, ChannelRef, Device, Direction, Link, SourceInfo, System
from pdcp_studio.storage.system_file import load_path

ROOT = Path(__file__).resolve().parents[2]
SYSTEMS = ROOT / "resources" / "systems"

U8_POS = 0x5000  # unsigned 8-bit position, no flags
SOLE = 0x0200
TERMINAL = 0x0100


def ref(serial: int, index: int, vid: int = 2, pid: int = 2) -> ChannelRef:
    return ChannelRef(vid, pid, serial, index)


def L(out_serial: int, out_index: int, in_serial: int, in_index: int) -> Link:
    """The link SN<out_serial>.O<out_index> → SN<in_serial>.I<in_index> (VID 2, PID 2)."""
    return Link(ref(out_serial, out_index), ref(in_serial, in_index))


def out(index: int, profile: int, type: int = U8_POS, req: tuple | list = (),
        des: tuple | list = ()) -> Channel:
    return Channel(index, Direction.OUTPUT, type, profile,
                   required_inputs=tuple(req), desired_inputs=tuple(des))


def inp(index: int, profile: int, type: int = U8_POS, *, sole: bool = False,
        terminal: bool = False, terminal_profile: int | None = None, req: tuple | list = (),
        des: tuple | list = ()) -> Channel:
    t = type | (SOLE if sole else 0) | (TERMINAL if terminal else 0)
    tp = terminal_profile if terminal_profile is not None else (profile if terminal else 0)
    return Channel(index, Direction.INPUT, t, profile, terminal_profile=tp,
                   required_inputs=tuple(req), desired_inputs=tuple(des))


def dev(serial: int, *channels: Channel, present: bool = True, vid: int = 2,
        pid: int = 2) -> Device:
    d = Device(vid, pid, serial, name=f"SN{serial}", present=present)
    for ch in channels:
        d.add_channel(ch)
    return d


def system(*devices: Device, links: tuple | list = ()) -> System:
    """Devices and links; linked inputs store their source, as on a configured bus."""
    s = System(devices, links)
    for link in sorted(links, reverse=True):
        o = s.channel(link.output)
        s.channel(link.input).source = SourceInfo(*link.output, o.type, o.profile)
    return s


def load(name: str) -> System:
    """A shipped system: ``load("appendix-d")``."""
    return load_path(SYSTEMS / f"{name}.json")


def shuffled(s: System, seed: int) -> System:
    """The same system with devices and each device's channels listed in another order."""
    rng = random.Random(seed)
    devices = [d for d in s.copy().devices.values()]
    rng.shuffle(devices)
    for d in devices:
        chans = list(d.channels.values())
        rng.shuffle(chans)
        d.channels = {c.index: c for c in chans}
    links = list(s.links)
    rng.shuffle(links)
    return System(devices, links)
