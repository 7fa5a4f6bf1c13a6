"""docs/host-link.md is the specification a firmware author implements: its hex examples must be
the implementation's own bytes, and it must cover every request, event and status."""

from __future__ import annotations

import re
from pathlib import Path

from pdcp_studio.protocol.hostlink import FrameReader
from pdcp_studio.protocol.hostlink_messages import Event, Req, Status

from .hostlink_examples import examples, render

DOC = Path(__file__).resolve().parents[2] / "docs" / "host-link.md"


def _example_block() -> str:
    text = DOC.read_text(encoding="utf-8")
    section = text.split("## 6. Hex examples", 1)[1]
    return section.split("```text\n", 1)[1].split("\n```", 1)[0]


def test_the_documents_hex_examples_are_the_implementations_bytes():
    assert _example_block() == render()


def test_every_example_parses_back_to_its_frame():
    for label, wire in examples():
        frames = FrameReader().feed(wire)
        assert len(frames) == 1 and frames[0].encode() == wire, label


def test_every_request_event_and_status_is_documented_with_an_example():
    labels = {label.split()[0] for label, _ in examples()}
    assert {r.name for r in Req} <= labels
    assert {e.name for e in Event} <= labels
    text = DOC.read_text(encoding="utf-8")
    for status in Status:
        assert re.search(rf"\| 0x{status.value:02X} \| {status.name} \|", text), status.name
    for req in Req:
        assert re.search(rf"\| 0x{req.value:02X} \| {req.name} \|", text), req.name
    for event in Event:
        assert re.search(rf"\| 0x{event.value:02X} \| {event.name} \|", text), event.name


def _section(title: str) -> str:
    text = DOC.read_text(encoding="utf-8")
    return text.split(title, 1)[1].split("\n## ", 1)[0]


def test_the_ram_budget_rows_add_up_to_the_totals():
    budget = _section("## 7. What the arbitrator needs").split("**Measured", 1)[0]
    rows = [line.split("|") for line in budget.splitlines()
            if line.startswith("| ") and not line.startswith("| buffer")]
    sums = [0, 0]
    totals = None
    for cells in rows:
        values = []
        for cell in cells[2:4]:
            cell = cell.strip().strip("*").replace(",", "")
            if "=" in cell:
                cell = cell.split("=")[-1].strip()
            values.append(int(cell) if cell.isdigit() else 0)
        if "total" in cells[1]:
            totals = values
        else:
            sums = [a + b for a, b in zip(sums, values, strict=True)]
    assert totals == sums == [2744, 1580]


def test_the_recovery_reset_frame_in_the_text_is_the_implementations():
    from pdcp_studio.protocol.hostlink import Frame, Kind

    wire = " ".join(f"{b:02x}" for b in Frame(Kind.RESET, 0).encode())
    assert f"`{wire}`" in _section("## 3. The link layer")


def test_the_profiles_are_named_as_capabilities():
    from pdcp_studio.bus.hostlink.handlers import CAPABILITIES
    from pdcp_studio.protocol import hostlink_messages as hm

    assert CAPABILITIES == hm.CAP_FULL == 0x000F
    assert hm.CAP_LEAN == 0
    hello = _section("## 4. Greeting")
    assert "declares `0x000F`" in hello and "`0x0000`" in hello


def _numbers(text: str) -> list[int]:
    return [int(n.replace(",", "")) for n in re.findall(r"\d[\d,]*(?= B)", text)]


def test_the_measured_figures_are_the_firmware_readmes():
    """§7's measured row and totals are the reference firmware's map-file figures as
    firmware/README.md gives them (tests/firmware rebuilds and compares those)."""
    measured = _section("## 7. What the arbitrator needs").split("**Measured", 1)[1]
    measured = measured.split("**Baud rate", 1)[0]
    readme = (DOC.parents[1] / "firmware" / "README.md").read_text(encoding="utf-8")
    host_row = next(x for x in readme.splitlines() if x.startswith("| `hostlink.c`"))
    total_row = next(x for x in readme.splitlines() if x.startswith("| **total**"))
    arm_flash, arm_ram, avr_flash, avr_ram = [int(c.strip(" *").replace(",", ""))
                                              for c in host_row.split("|")[2:6]]
    totals = [int(c.strip(" *").replace(",", "")) for c in total_row.split("|")[2:6]]
    lines = measured.splitlines()
    flash = next(x for x in lines if x.startswith("| host link (") and "flash" in x)
    ram = next(x for x in lines if x.startswith("| host link: RAM"))
    whole = next(x for x in lines if x.startswith("| the whole arbitrator"))
    assert _numbers(flash) == [arm_flash, avr_flash]
    assert _numbers(ram) == [arm_ram, avr_ram]
    assert _numbers(whole) == [totals[0], totals[1], totals[2], totals[3]]
