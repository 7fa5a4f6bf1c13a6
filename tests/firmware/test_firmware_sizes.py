"""The firmware's flash and RAM in firmware/README.md (and docs/host-link.md §7, which
tests/protocol/test_hostlink_doc.py ties to the README) are what its map files say today:
both targets are built and measured (``make -C firmware sizes``)."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TOOLS = ("make", "arm-none-eabi-gcc", "avr-gcc")

pytestmark = pytest.mark.skipif(
    any(shutil.which(t) is None for t in TOOLS),
    reason="needs make, arm-none-eabi-gcc and avr-gcc (Debian: apt-get install make "
           "gcc-arm-none-eabi libnewlib-arm-none-eabi gcc-avr avr-libc binutils-avr)")


def _readme_row(start: str) -> list[int]:
    readme = (ROOT / "firmware" / "README.md").read_text(encoding="utf-8")
    row = next(x for x in readme.splitlines() if x.startswith(start))
    return [int(c.strip(" *").replace(",", "")) for c in row.split("|")[2:6]]


def test_the_readmes_sizes_are_the_map_files():
    # one build at a time in build/, as firmware/run-qemu.sh does (another worker's emulator
    # may be building it now)
    build = ROOT / "firmware" / "build"
    build.mkdir(exist_ok=True)
    lock = ["flock", str(build / ".lock")] if shutil.which("flock") else []
    out = subprocess.run([*lock, "make", "-s", "-C", str(ROOT / "firmware"), "sizes"],
                         capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    measured: dict[tuple[str, str], tuple[int, int]] = {}
    for line in out.stdout.splitlines():
        found = re.match(r"(arm|avr): (\S+)\s+(\d+)\s+(\d+)$", line)
        if found:
            measured[found[1], found[2]] = (int(found[3]), int(found[4]))
    for name, start in (("total", "| **total**"), ("src/hostlink.c", "| `hostlink.c`")):
        arm, avr = measured["arm", name], measured["avr", name]
        assert _readme_row(start) == [*arm, *avr], f"firmware/README.md's {name} row"
