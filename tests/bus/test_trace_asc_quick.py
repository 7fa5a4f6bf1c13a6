"""The quick ASC reader yields exactly what python-can's ``ASCReader`` yields.

On every ASC capture in the test data (other tools' captures among them) and on generated
lines — well-formed data frames and near misses that must fall back to python-can's own
parsing (decimal captures, odd DLCs, glued bytes, trailing fields, short data).
"""

from __future__ import annotations

import gzip
import io
from pathlib import Path
from typing import Any

import can
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.bus.trace.files.asc import QuickASCReader

CAPTURES = Path(__file__).resolve().parents[1] / "data" / "captures"
ASC_FILES = sorted(p for p in CAPTURES.rglob("*") if p.name.endswith((".asc", ".asc.gz")))

FIELDS = ("timestamp", "channel", "is_rx", "is_extended_id", "arbitration_id", "dlc",
          "is_remote_frame", "is_error_frame", "is_fd", "bitrate_switch",
          "error_state_indicator")


def _record(msg: can.Message) -> tuple[Any, ...]:
    return (*(getattr(msg, name) for name in FIELDS), bytes(msg.data))


def _read(reader_type: type[can.ASCReader], text: str) -> tuple[list[tuple[Any, ...]], str]:
    """The frames a reader yields from ``text``, and the error it stopped on ("" for none)."""
    out: list[tuple[Any, ...]] = []
    try:
        for msg in reader_type(io.StringIO(text), relative_timestamp=False):
            out.append(_record(msg))
    except Exception as err:  # python-can raises anything on bad input: so must we
        return out, type(err).__name__
    return out, ""


def _text(path: Path) -> str:
    raw = path.read_bytes()
    if path.name.endswith(".gz"):
        raw = gzip.decompress(raw)
    return raw.decode("utf-8", errors="replace")


def test_there_are_captures_to_compare() -> None:
    assert len(ASC_FILES) >= 6
    assert any("public" in p.parts for p in ASC_FILES)


@pytest.mark.parametrize("path", ASC_FILES, ids=lambda p: p.name)
def test_every_capture_reads_as_python_can_reads_it(path: Path) -> None:
    text = _text(path)
    quick, theirs = _read(QuickASCReader, text), _read(can.ASCReader, text)
    assert quick == theirs
    assert quick[0], "a capture with frames"


HEADER = "date Mon Nov 30 10:00:00.000 am 2026\nbase {base}  timestamps absolute\n" \
         "internal events logged\nBegin Triggerblock Mon Nov 30 10:00:00.000 am 2026\n"

hex_byte = st.integers(0, 255).map(lambda b: f"{b:02X}")
#: A data frame line as Vector writes it, and ways other tools (or damage) bend it.
data_frame = st.builds(
    lambda t, ch, ident, ext, rx, dlc, data, tail: (
        f"{t:.6f} {ch}  {ident:X}{'x' if ext else ''}  {'Rx' if rx else 'Tx'}  d {dlc} "
        f"{' '.join(data)}{tail}"),
    st.floats(0, 1e5, allow_nan=False), st.integers(1, 16), st.integers(0, 0x1FFFFFFF),
    st.booleans(), st.booleans(),
    st.sampled_from(["0", "1", "4", "8", "08", "9", "F", "10", "x"]),
    st.lists(hex_byte, max_size=10),
    st.sampled_from(["", "  Length = 228000 BitCount = 118 ID = 419x", " 1", " 0102",
                     "zz", "  ", " Length"]))
other_line = st.sampled_from([
    "0.000100 1  123  Rx  r", "0.000200 1  123x Tx  r 4", "0.000300 1  ErrorFrame",
    "0.000400 CANFD   1 Rx        123                                   1 0 8  8 "
    "01 02 03 04 05 06 07 08   0   0   3000 0 0 0 0 0",
    "0.000500 Start of measurement", "// a comment", "0.000600 1  Statistic: D 0 R 0",
    "End TriggerBlock", "0.000700 2  1A3  Rx  d 2 1 2",
    "Begin Triggerblock Tue Dec 01 11:00:00.000 am 2026", "0.000800 1  12X  Rx  d 1 05",
])


@settings(max_examples=300, deadline=None)
@given(st.lists(st.one_of(data_frame, other_line), min_size=1, max_size=12),
       st.sampled_from(["hex", "dec"]))
def test_generated_lines_read_as_python_can_reads_them(lines: list[str], base: str) -> None:
    text = HEADER.format(base=base) + "\n".join(lines) + "\nEnd TriggerBlock\n"
    assert _read(QuickASCReader, text) == _read(can.ASCReader, text)


def test_a_plain_data_frame_takes_the_quick_road() -> None:
    """The fast path is really taken (else this module would only test python-can)."""
    reader = QuickASCReader(io.StringIO(HEADER.format(base="hex") +
                                        "1.5 1  1A3x Rx  d 3 01 02 03\n"),
                            relative_timestamp=False)
    slow_calls: list[str] = []
    original = reader._python_can_line

    def spy(line: str) -> Any:
        slow_calls.append(line)
        return original(line)

    reader._python_can_line = spy  # type: ignore[method-assign]
    [msg] = list(reader)
    assert (msg.arbitration_id, msg.is_extended_id, bytes(msg.data), msg.channel) == \
        (0x1A3, True, b"\x01\x02\x03", 0)
    assert [x for x in slow_calls if "1A3x" in x] == []  # (the trigger line goes slow)
    assert len(slow_calls) == 1
