"""One time base per run of ``monitor``: seconds since the first frame, live and replayed.

The trial saw lines of one run jump between small relative times and the epoch: the pump
read the decoder's first-frame time once, before any frame, and its fast paths (frames of
an identifier decoded before) printed ``timestamp - 0``. A live bus and every capture with
absolute timestamps (a candump ``.log``) did it; an ASC capture, whose clock starts at 0,
hid it.
"""

from __future__ import annotations

import re

from pdcp_studio.cli.main import main
from pdcp_studio.cli.monitor import time_base_line

LINE_TIME = re.compile(r"^\s*(\d+\.\d{6})  ")


def _times(out: str) -> list[float]:
    times = []
    for line in out.splitlines():
        match = LINE_TIME.match(line)
        if match:
            times.append(float(match.group(1)))
    return times


def _one_time_base(out: str, err: str) -> list[float]:
    times = _times(out)
    assert len(times) > 50, out[:500]
    assert times[0] == 0.0
    assert max(times) < 60.0, [t for t in times if t >= 60.0][:5]  # no epoch among them
    assert "Times are seconds since the first frame (the first at 20" in err
    return times


def test_live_and_replayed_times_share_one_base(tmp_path, capsys):
    capture = tmp_path / "live.log"  # candump format: absolute (epoch) timestamps
    assert main(["monitor", "--bus", "sim:transradial", "--seconds", "1.5",
                 "--log", str(capture)]) == 0
    out, err = capsys.readouterr()
    live = _one_time_base(out, err)
    assert capture.read_text().startswith("(17") or capture.read_text().startswith("(18")
    assert main(["monitor", "--replay", str(capture)]) == 0
    out, err = capsys.readouterr()
    replayed = _one_time_base(out, err)
    assert len(replayed) == len(live)


def test_the_closing_line_says_the_time_base():
    assert time_base_line(None) is None
    assert time_base_line(0.0) == ("Times are seconds since the first frame "
                                   "(the first at 0.000000 s on the capture's clock)")
    assert time_base_line(1_795_904_681.392086) == (
        "Times are seconds since the first frame "
        "(the first at 2026-11-28 22:24:41.392086 UTC)")
