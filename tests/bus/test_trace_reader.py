"""One reader for every capture (bus/trace/files/reader.py): the format by content, damage read up
to the cut and said with its line or offset, bounded memory, FIFOs, gzip, MF4 named."""

from __future__ import annotations

import gzip
import os
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import can
import pytest

from pdcp_studio.bus.trace.files.capture import CaptureError
from pdcp_studio.bus.trace.files.reader import MAX_LINE, CaptureReader, sniff

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "captures"


def read(path, **kw):
    with CaptureReader(path, **kw) as reader:
        frames = list(reader)
    return reader, frames


@pytest.mark.parametrize("name, fmt, count", [
    ("canalyzer-car-cp1252.asc", "asc", 123),
    ("candump-car.log", "log", 123),
    ("vector-car.blf", "blf", 123),
    ("pcan-car-2.2.trc", "trc", 121),
    ("pcan-prosthesis-3.0.trc", "trc", 408),
    ("sim-transradial-midsession.asc", "asc", 408),
])
def test_captures_of_other_tools_read_by_content(name, fmt, count):
    reader, frames = read(DATA / name)
    assert reader.format == fmt and len(frames) == count == reader.frames
    assert not reader.truncated and reader.damage is None


def test_every_frame_kind_is_kept():
    """Error, remote, extended and CAN FD frames come as what they are, in every format
    that holds them."""
    for name in ("canalyzer-car-cp1252.asc", "candump-car.log", "vector-car.blf"):
        _, frames = read(DATA / name)
        assert any(m.is_error_frame for m in frames), name
        remote = [m for m in frames if m.is_remote_frame]
        assert remote and remote[0].arbitration_id == 0x3C2 and not remote[0].is_extended_id
        ext = [m for m in frames if m.is_extended_id and m.arbitration_id == 0x123]
        assert ext, name
        fd = [m for m in frames if m.is_fd]
        assert fd and len(fd[0].data) == 12, name
    _, frames = read(DATA / "pcan-car-2.2.trc")  # TRC 2.x keeps its error frames (ER)
    assert sum(m.is_error_frame for m in frames) == 1


def test_the_extension_does_not_matter(tmp_path):
    blf_as_asc = tmp_path / "capture.asc"
    shutil.copy(DATA / "vector-car.blf", blf_as_asc)
    asc_as_blf = tmp_path / "capture.blf"
    shutil.copy(DATA / "canalyzer-car-cp1252.asc", asc_as_blf)
    no_suffix = tmp_path / "capture"
    shutil.copy(DATA / "candump-car.log", no_suffix)
    assert read(blf_as_asc)[0].format == "blf"
    assert read(asc_as_blf)[0].format == "asc"
    assert read(no_suffix)[0].format == "log"


def test_a_cp1252_comment_does_not_make_an_asc_unreadable():
    raw = (DATA / "canalyzer-car-cp1252.asc").read_bytes()
    with pytest.raises(UnicodeDecodeError):
        raw.decode("utf-8")
    _, frames = read(DATA / "canalyzer-car-cp1252.asc")
    assert len(frames) == 123


@pytest.mark.parametrize("version", ["2.2", "3.0"])
def test_trc_2_2_and_3_0_headers(tmp_path, version):
    text = (DATA / "pcan-car-2.2.trc").read_text().replace(";$FILEVERSION=2.2",
                                                          f";$FILEVERSION={version}")
    path = tmp_path / "x.trc"
    path.write_text(text)
    reader, frames = read(path)
    assert len(frames) == 121 and not reader.truncated


def test_an_empty_asc_and_an_empty_blf_are_alike(tmp_path):
    for name in ("empty.asc", "empty.blf"):
        (tmp_path / name).write_bytes(b"")
        reader, frames = read(tmp_path / name)
        assert reader.format == "empty" and frames == []
    with can.BLFWriter(str(tmp_path / "header-only.blf")):
        pass
    reader, frames = read(tmp_path / "header-only.blf")
    assert frames == [] and not reader.truncated


def test_an_asc_line_cut_mid_data_is_an_error_at_that_line(tmp_path):
    lines = (DATA / "sim-transradial-midsession.asc").read_text().splitlines()
    k = next(i for i, x in enumerate(lines) if " d 2 " in x and i > 20)
    lines[k] = lines[k].rsplit(" ", 1)[0]  # "d 2 B8" : one of its two bytes
    path = tmp_path / "cut.asc"
    path.write_text("\n".join(lines) + "\n")
    reader, frames = read(path)
    assert reader.truncated and f"cut.asc: line {k + 1}: a frame cut short: DLC 2 with 1" \
        in reader.damage
    assert all(len(m.data) == m.dlc for m in frames)


def test_an_asc_cut_at_the_end_reads_up_to_the_cut(tmp_path):
    raw = (DATA / "sim-transradial-midsession.asc").read_bytes()
    path = tmp_path / "cut.asc"
    path.write_bytes(raw[:len(raw) // 2])
    reader, frames = read(path)
    assert reader.truncated and frames and "cut.asc: line " in reader.damage
    assert "cut short" in reader.damage


def test_a_blf_cut_in_half_is_read_up_to_the_cut(tmp_path):
    msgs = list(CaptureReader(DATA / "sim-transradial-midsession.asc")) * 30
    whole = tmp_path / "whole.blf"
    with can.BLFWriter(str(whole)) as writer:
        for m in msgs:
            writer.on_message_received(m)
    raw = whole.read_bytes()
    half = tmp_path / "half.blf"
    half.write_bytes(raw[:len(raw) // 2])
    reader, frames = read(half, plain_frames=True)
    assert 0 < len(frames) < len(msgs)
    assert reader.truncated and "half.blf: offset " in reader.damage and "cut short" in reader.damage


def test_damage_before_any_frame_is_unreadable(tmp_path):
    path = tmp_path / "x.asc"
    path.write_text("date Sat Nov 28 22:33:50.470 2026\nbase hex  timestamps absolute\n"
                    "Begin Triggerblock\n 0.1 1 123 Rx d 8 FE 3\n 0.2 1 124 Rx d 1 01\n")
    with pytest.raises(CaptureError, match=r"x\.asc: line 4: a frame cut short"):
        read(path)


def test_text_that_is_no_capture_is_refused_by_content(tmp_path):
    path = tmp_path / "notes.asc"
    path.write_text("Dear diary,\nthe bus was quiet today.\n")
    with pytest.raises(CaptureError, match="not a readable capture"):
        read(path)
    assert sniff(b"\x00" * 100) is None and sniff(b"") == "empty"


def test_a_line_longer_than_any_valid_one_is_an_error(tmp_path):
    path = tmp_path / "long.asc"
    path.write_bytes(b"date x\nbase hex\n 0.1 1 123 Rx d 1 01\n" + b"A" * (MAX_LINE * 3))
    reader, frames = read(path)
    assert len(frames) == 1 and reader.truncated and "line 4: a line longer than" in reader.damage


HUGE = ("import sys, resource\n"
        "from pdcp_studio.bus.trace.files.reader import CaptureReader\n"
        "from pdcp_studio.bus.trace.files.capture import CaptureError\n"
        "try:\n"
        "    with CaptureReader(sys.argv[1]) as r:\n"
        "        n = sum(1 for _ in r)\n"
        "    print('read', n, r.damage)\n"
        "except CaptureError as e:\n"
        "    print('refused', e)\n"
        # VmHWM is this program's own peak: ru_maxrss keeps the peak of the process it was
        # forked from (Linux records it at exec), a pytest grown large by a whole run.
        "try:\n"
        "    hwm = [l for l in open('/proc/self/status') if l.startswith('VmHWM')][0]\n"
        "    print(int(hwm.split()[1]) // 1024)\n"
        "except OSError:\n"
        "    print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024)\n")


@pytest.mark.parametrize("head", [b"", b"date Sat Nov 28 2026\nbase hex\n" + b"A" * 70_000])
def test_a_2_gb_file_without_newlines_takes_no_memory(tmp_path, head):
    """A sparse 2 GB file (NUL bytes, or an ASC header then no newline): refused or cut
    at once, in a few MB."""
    path = tmp_path / "huge.asc"
    with open(path, "wb") as f:
        f.write(head)
        f.truncate(2 << 30)
    out = subprocess.run([sys.executable, "-c", HUGE, str(path)], capture_output=True,
                         text=True, timeout=60, env=dict(os.environ, PYTHONPATH=str(ROOT)),
                         check=True).stdout.split("\n")
    assert out[0].startswith(("refused", "read 0")) or "line 3" in out[0], out
    assert int(out[1]) < 150, f"peak RSS {out[1]} MB"


def test_a_blf_object_larger_than_any_valid_one_is_an_error(tmp_path):
    import struct

    whole = tmp_path / "w.blf"
    with can.BLFWriter(str(whole)) as writer:
        for m in list(CaptureReader(DATA / "vector-car.blf"))[:10]:
            writer.on_message_received(m)
    raw = bytearray(whole.read_bytes())
    at = raw.index(b"LOBJ")
    struct.pack_into("<L", raw, at + 8, 1 << 30)  # the container says 1 GiB
    path = tmp_path / "big.blf"
    path.write_bytes(bytes(raw) + bytes(100))
    with pytest.raises(CaptureError, match=r"big\.blf: offset \d+: an object of 1,073,741,"):
        read(path)


def test_a_fifo_is_read_as_a_stream(tmp_path):
    fifo = tmp_path / "live.log"
    os.mkfifo(fifo)
    content = (DATA / "candump-car.log").read_bytes()

    def feed():
        with open(fifo, "wb") as f:
            for k in range(0, len(content), 1000):
                f.write(content[k:k + 1000])

    writer = threading.Thread(target=feed)
    writer.start()
    reader, frames = read(fifo)
    writer.join()
    assert reader.format == "log" and len(frames) == 123


def test_a_gzipped_capture_and_a_cut_gzip(tmp_path):
    raw = (DATA / "canalyzer-car-cp1252.asc").read_bytes()
    path = tmp_path / "car.asc.gz"
    path.write_bytes(gzip.compress(raw))
    reader, frames = read(path)
    assert reader.gzipped and len(frames) == 123
    cut = tmp_path / "cut.gz"
    big = b"".join([raw.split(b"Begin Triggerblock")[0]] + [raw.split(b"Start of measurement\r\n")[1]] * 50)
    cut.write_bytes(gzip.compress(big)[:-2000])
    reader, frames = read(cut)
    assert reader.truncated and frames


def test_mf4_is_named_as_missing_when_its_extra_is_not_installed(tmp_path):
    path = tmp_path / "x.mf4"
    path.write_bytes(b"MDF     4.10    " + bytes(100))
    import importlib.util

    if importlib.util.find_spec("asammdf") is not None:  # pragma: no cover
        pytest.skip("asammdf is installed here")
    with pytest.raises(CaptureError, match=r"mf4 extra, which is not installed"):
        read(path)


def test_a_missing_file_and_a_folder(tmp_path):
    with pytest.raises(CaptureError, match="no such file"):
        CaptureReader(tmp_path / "nothing.asc")
    with pytest.raises(CaptureError, match="is a folder"):
        CaptureReader(tmp_path)


def test_a_blf_container_that_inflates_beyond_reason_is_refused(tmp_path):
    """python-can would inflate it whole (a zip bomb's gigabytes); the reader stops."""
    import struct
    import zlib

    from pdcp_studio.bus.trace.files.blf import MAX_CONTAINER

    small = tmp_path / "small.blf"
    with can.BLFWriter(str(small)) as writer:
        writer.on_message_received(can.Message(arbitration_id=1, data=b"\x0a",
                                               is_extended_id=False))
    raw = small.read_bytes()
    header = raw[:struct.unpack_from("<L", raw, 4)[0]]
    payload = zlib.compress(bytes(MAX_CONTAINER + 1000), 9)
    body = struct.pack("<4sHHLL", b"LOBJ", 16, 1, 16 + 16 + len(payload), 10)
    body += struct.pack("<H6xL4x", 2, MAX_CONTAINER + 1000) + payload
    path = tmp_path / "bomb.blf"
    path.write_bytes(header + body + bytes(-len(body) % 4))
    with pytest.raises(CaptureError, match="inflating to more than"):
        read(path, plain_frames=True)
