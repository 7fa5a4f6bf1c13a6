"""Contracts §2 ``config decode`` / ``config encode`` and reference §3 (the byte format).

"A channel record omits owner_type / owner_profile when the file has no such record. A bad
file: exit 2 and a stderr line with ``offset N`` (the byte offset of the offending record)
and the reason." Numbers in the JSON are integers or ``"0x…"`` strings.
"""

from __future__ import annotations

import json
import struct

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.errors import ConfigFormatError
from pdcp_studio.storage import config_codec


def _records(*pairs: tuple[int, int]) -> bytes:
    return b"".join(struct.pack("<BH", code, value) for code, value in pairs)


def _channel(code: int, owner: bool = False, drop: int = 0) -> list[tuple[int, int]]:
    recs = [(code, 0), (7, 10), (8, 20), (9, 1), (10, 30), (11, 40), (12, 50)]
    if owner:
        recs += [(13, 60), (14, 70)]
    return [r for r in recs if r[0] != drop]


HEAD = [(1, 1), (2, 1), (3, 1), (4, 1)]  # offsets 0, 3, 6, 9
GOOD = HEAD + _channel(5) + _channel(6) + [(15, 0)]  # input at 12, output at 33, End at 54


def _decode(tmp_path, capsys, data: bytes) -> tuple[int, str, str]:
    path = tmp_path / "c.pdcfg"
    path.write_bytes(data)
    code = main(["config", "decode", str(path), "--json"])
    out, err = capsys.readouterr()
    return code, out, err


def test_decode_json_omits_owner_fields_the_file_does_not_have(tmp_path, capsys):
    data = _records(*HEAD, *_channel(5, owner=True), *_channel(6), (15, 0))
    code, out, err = _decode(tmp_path, capsys, data)
    assert (code, err) == (0, "")
    link = json.loads(out)["configurations"][0]["links"][0]
    assert list(link) == ["index", "input", "output"]
    assert link["input"] == {"type": "0x000A", "profile": "0x0014", "index": 1, "vid": 30,
                             "pid": 40, "serial": 50, "owner_type": 60, "owner_profile": 70}
    assert list(link["input"])[:6] == ["type", "profile", "index", "vid", "pid", "serial"]
    assert link["output"] == {"type": "0x000A", "profile": "0x0014", "index": 1, "vid": 30,
                              "pid": 40, "serial": 50}


BAD_FILES = [
    ("length not a multiple of 3", _records(*GOOD)[:-1], 54, "truncated record"),
    ("missing End", _records(*GOOD[:-1]), 54, "missing End"),
    ("# of configurations disagrees", _records((1, 2), *GOOD[1:]), 0, "# of configurations"),
    ("# of links disagrees", _records((1, 1), (2, 1), (3, 2), *GOOD[3:]), 6, "# of links"),
    ("value record outside a channel", _records((1, 1), (8, 5), *GOOD[1:]), 3,
     "outside a channel"),
    ("channel without index", _records(*HEAD, *_channel(5, drop=9), *_channel(6), (15, 0)),
     12, "Channel index"),
    ("channel without serial", _records(*HEAD, *_channel(5), *_channel(6, drop=12), (15, 0)),
     33, "Owner serial number"),
    ("link without an output", _records(*HEAD, *_channel(5), (15, 0)), 9, "no output channel"),
    ("checksum mismatch", _records(*GOOD[:-1], (16, 0x1234), (15, 0)), 54, "checksum"),
    ("channel index 0", _records(*HEAD, (5, 0), (9, 0)), 15, "out of range"),
]


@pytest.mark.parametrize(("what", "data", "offset", "reason"), BAD_FILES,
                         ids=[b[0] for b in BAD_FILES])
def test_bad_file_exit_2_with_offset_of_the_offending_record(tmp_path, capsys, what, data,
                                                             offset, reason):
    code, out, err = _decode(tmp_path, capsys, data)
    assert (code, out) == (2, "")
    assert len(err.splitlines()) == 1
    assert "c.pdcfg" in err and f"offset {offset}" in err and reason in err


def test_bytes_after_end_and_unknown_codes_are_skipped(tmp_path, capsys):
    data = _records(*HEAD, (99, 1), *_channel(5), (42, 7), *_channel(6), (15, 0))
    code, out, _ = _decode(tmp_path, capsys, data + b"\xff" * 7)
    assert code == 0 and len(json.loads(out)["configurations"][0]["links"]) == 1


def test_decode_of_a_directory_or_missing_file_is_bad_input(tmp_path, capsys):
    for path in (tmp_path, tmp_path / "absent.pdcfg"):
        assert main(["config", "decode", str(path), "--json"]) == 2
        out, err = capsys.readouterr()
        assert out == "" and str(path) in err


def _link_json(**input_fields) -> dict:
    inp = {"type": "0x5300", "profile": "0x1110", "index": 1, "vid": 2, "pid": 2, "serial": 6}
    inp.update(input_fields)
    return {"configurations": [{"index": 1, "links": [{"index": 1, "input": inp, "output": {
        "type": 20480, "profile": 4352, "index": "0x3", "vid": "0x2", "pid": 2, "serial": 5}}]}]}


def test_encode_accepts_integers_and_0x_strings(tmp_path, capsys):
    src, dst = tmp_path / "c.json", tmp_path / "c.pdcfg"
    src.write_text(json.dumps(_link_json(serial="0x06", owner_type="0x3C")))
    assert main(["config", "encode", str(src), "-o", str(dst)]) == 0
    link = config_codec.load_path(dst).configurations[0].links[0]
    assert (link.output.type, link.output.profile, link.output.index) == (0x5000, 0x1100, 3)
    assert (link.input.serial, link.input.owner_type, link.input.owner_profile) == (6, 60, None)


@pytest.mark.parametrize("text", ["6", "0b110", "1_0", "six", ""])
def test_encode_refuses_a_string_that_is_not_0x_hex(tmp_path, capsys, text):
    src, dst = tmp_path / "c.json", tmp_path / "c.pdcfg"
    src.write_text(json.dumps(_link_json(serial=text)))
    assert main(["config", "encode", str(src), "-o", str(dst)]) == 2
    _, err = capsys.readouterr()
    assert "configurations[0].links[0].input.serial" in err
    assert not dst.exists()
    with pytest.raises(ConfigFormatError):
        config_codec.from_json(_link_json(serial=text))


def test_encode_onto_a_directory_fails_with_1_naming_it_and_leaves_no_temporary(tmp_path,
                                                                                 capsys):
    src, target = tmp_path / "c.json", tmp_path / "out"
    src.write_text(json.dumps(_link_json()))
    target.mkdir()
    assert main(["config", "encode", str(src), "-o", str(target)]) == 1
    out, err = capsys.readouterr()
    assert out == "" and str(target) in err and ".tmp" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.json", "out"]


def test_unknown_records_appear_on_their_object_and_encode_writes_them_back(tmp_path, capsys):
    """Contracts §2: ``"unknown_records": [{"code": 32, "value": 4660}, …]`` on the object
    they belong to, in file order; ``config encode`` writes them back in the same place."""
    body = _records((1, 1), (0x21, 1), (2, 1), (3, 1), (0x22, 2), (4, 1), (0x23, 3),
                    *_channel(5), (0x20, 4660), (0x20, 4661), *_channel(6), (0x24, 5),
                    (15, 0))
    code, out, _ = _decode(tmp_path, capsys, body)
    assert code == 0
    doc = json.loads(out)
    cfg = doc["configurations"][0]
    link = cfg["links"][0]
    assert doc["unknown_records"] == [{"code": 0x21, "value": 1}]
    assert cfg["unknown_records"] == [{"code": 0x22, "value": 2}]
    assert link["unknown_records"] == [{"code": 0x23, "value": 3}]
    assert link["input"]["unknown_records"] == [{"code": 32, "value": 4660},
                                                {"code": 32, "value": 4661}]
    assert link["output"]["unknown_records"] == [{"code": 0x24, "value": 5}]
    src, dst = tmp_path / "c.json", tmp_path / "again.pdcfg"
    src.write_text(out)
    assert main(["config", "encode", str(src), "-o", str(dst)]) == 0
    head = body[:-3]
    expected = head + _records((16, config_codec.crc16_ccitt_false(head)), (15, 0))
    assert dst.read_bytes() == expected  # the same records, only the checksum added
    capsys.readouterr()
    assert main(["config", "decode", str(dst)]) == 0
    listing = capsys.readouterr().out
    assert "6 record(s) with unknown codes kept" in listing
    assert "code 32 = 0x1234, code 32 = 0x1235" in listing


def test_encode_refuses_a_known_code_as_an_unknown_record(tmp_path, capsys):
    doc = {"configurations": [], "unknown_records": [{"code": 15, "value": 0}]}
    src = tmp_path / "c.json"
    src.write_text(json.dumps(doc))
    assert main(["config", "encode", str(src), "-o", str(tmp_path / "x.pdcfg")]) == 2
    err = capsys.readouterr().err
    assert "unknown_records[0].code: 15 is a known code (End)" in err
    assert not (tmp_path / "x.pdcfg").exists()
