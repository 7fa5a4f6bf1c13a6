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
