"""Readers bounded by what they read (issue 15, contracts §1): size counted in bytes read
(standard input too), a nesting-depth limit, no key twice, no null profile; a named pipe
is no file (issue 28)."""

from __future__ import annotations

import copy
import io
import json
import os
import threading

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.errors import SystemFileError
from pdcp_studio.storage import system_file
from pdcp_studio.storage.bounded_input import InputError, loads_json, nesting_depth, read_capped

SMALL = {
    "format": "pdcp-system/1",
    "devices": [{"vid": 2, "pid": 2, "serial": 4, "channels": [
        {"index": 1, "direction": "output", "type": "0x5000", "profile": "0x2110"}]}],
    "links": [],
}


def _fifo_feeding(tmp_path, size: int):
    """A named pipe (``st_size`` 0) a thread writes ``size`` bytes into; returns the path and
    a list that ends up holding how many bytes the reader took before it stopped reading."""
    path = tmp_path / "pipe.json"
    os.mkfifo(path)
    written = []

    def feed() -> None:
        n = 0
        try:
            with open(path, "wb") as out:
                chunk = b" " * 65536
                while n < size:
                    out.write(chunk)
                    n += len(chunk)
        except BrokenPipeError:
            pass
        written.append(n)

    thread = threading.Thread(target=feed, daemon=True)
    thread.start()
    return path, written, thread


def test_a_system_file_from_a_named_pipe_is_refused_without_reading_it(tmp_path):
    """A FIFO is not a file (issue 28): refused by what it is, its writer never read from
    (standard input, ``-``, is the one pipe a reader takes, bounded as below)."""
    path, _, thread = _fifo_feeding(tmp_path, 64 * 1024 * 1024)
    with pytest.raises(SystemFileError, match=r"is a FIFO \(named pipe\), not a regular file"
                       ) as info:
        system_file.load_path(path)
    assert str(path) in str(info.value)
    with open(path, "rb") as drain:  # let the writer go: it got no reader until now
        drain.read(1)
    thread.join(5)
    assert not thread.is_alive()


def test_read_capped_counts_bytes_read_not_the_size_on_disk():
    assert read_capped(io.BytesIO(b"x" * 10), 10) == b"x" * 10
    with pytest.raises(InputError, match="larger than 10 bytes"):
        read_capped(io.BytesIO(b"x" * 11), 10)


@pytest.mark.parametrize("depth", [17, 1_000, 100_000])
def test_deep_nesting_is_refused_with_a_clear_error_not_a_recursion_error(tmp_path, depth):
    path = tmp_path / "deep.json"
    path.write_text('{"format": "pdcp-system/1", "devices": ' + "[" * depth + "]" * depth + "}")
    with pytest.raises(SystemFileError, match=r"nested .* deeper|levels deep"):
        system_file.load_path(path)


@pytest.mark.parametrize("command", [["info", "--system"], ["print", "--system"],
                                     ["plan", "autoconfigure", "--system"]])
def test_deep_nesting_is_bad_input_for_every_command_that_reads_a_system(tmp_path, capsys,
                                                                          command):
    path = tmp_path / "deep.json"
    path.write_text("[" * 5000 + "]" * 5000)
    assert main([*command, str(path)]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and "levels deep" in err and "Traceback" not in err


def test_depth_ignores_brackets_inside_strings():
    assert nesting_depth(b'{"a": "[[[[{{{{", "b": ["]]]", {"c": "\\"]"}]}') == 3
    assert nesting_depth(b'"unterminated [[[') == 0
    assert loads_json('{"a": "[[[[[[[[[["}', max_depth=1) == {"a": "[[[[[[[[[["}


@pytest.mark.parametrize(("text", "path"), [
    ('{"format": "pdcp-system/1", "format": "pdcp-system/1"}', "format"),
    ('{"format": "pdcp-system/1", "devices": [{"vid": 2, "pid": 2, "serial": 4, "vid": 3}]}',
     "devices[0].vid"),
    ('{"format": "pdcp-system/1", "devices": [{"vid": 2, "pid": 2, "serial": 4, "channels": ['
     '{"index": 1, "direction": "output", "profile": "0x2110", "profile": "0x0000"}]}]}',
     "devices[0].channels[0].profile"),
])
def test_a_key_given_twice_is_refused_naming_its_json_path(text, path):
    with pytest.raises(SystemFileError) as info:
        system_file.loads(text, "s.json")
    assert f"s.json: {path}: " in str(info.value) and "twice" in str(info.value)


def test_the_null_profile_is_refused_as_a_channel_profile_naming_its_path():
    doc = copy.deepcopy(SMALL)
    doc["devices"][0]["channels"][0]["profile"] = "0x0000"
    with pytest.raises(SystemFileError) as info:
        system_file.from_json(doc)
    assert info.value.path == "devices[0].channels[0].profile"
    assert "0x0000" in info.value.reason
    del doc["devices"][0]["channels"][0]["profile"]
    with pytest.raises(SystemFileError, match="missing 'profile'"):
        system_file.from_json(doc)


def test_nan_and_infinity_are_not_json():
    with pytest.raises(SystemFileError, match="NaN"):
        system_file.loads('{"format": "pdcp-system/1", "devices": [{"vid": NaN}]}')


def _devices(n: int, channels: int = 1) -> dict:
    return {"format": "pdcp-system/1", "links": [], "devices": [
        {"vid": 10, "pid": 1, "serial": i + 1, "channels": [
            {"index": c + 1, "direction": "output", "profile": "0x4222"}
            for c in range(channels)]} for i in range(n)]}


def test_the_largest_system_file_is_accepted_and_one_more_device_or_channel_is_refused():
    biggest = _devices(system_file.MAX_DEVICES, system_file.MAX_CHANNELS // 256)
    assert len(system_file.from_json(biggest).devices) == system_file.MAX_DEVICES
    with pytest.raises(SystemFileError, match="at most 254") as info:
        system_file.from_json(_devices(system_file.MAX_DEVICES + 1))
    assert info.value.path == "devices"
    with pytest.raises(SystemFileError, match="at most 2048") as info:
        system_file.from_json(_devices(9, 255))
    assert info.value.path == "devices[8].channels"


def test_config_encode_refuses_duplicate_keys_deep_nesting_and_an_oversized_pipe(
        tmp_path, capsys, monkeypatch):
    out = tmp_path / "out.pdcfg"
    dup = tmp_path / "dup.json"
    dup.write_text('{"configurations": [{"index": 1, "index": 2, "links": []}]}')
    assert main(["config", "encode", str(dup), "-o", str(out)]) == 2
    assert "configurations[0].index" in capsys.readouterr().err
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 3000 + "]" * 3000)
    assert main(["config", "encode", str(deep), "-o", str(out)]) == 2
    assert "levels deep" in capsys.readouterr().err
    from pdcp_studio.cli.config_cmd import MAX_JSON_BYTES

    class Endless(io.RawIOBase):
        given = 0

        def readable(self) -> bool:
            return True

        def readinto(self, buf) -> int:
            buf[:] = b" " * len(buf)
            Endless.given += len(buf)
            return len(buf)

    monkeypatch.setattr("sys.stdin", io.TextIOWrapper(io.BufferedReader(Endless())))
    assert main(["config", "encode", "-", "-o", str(out)]) == 2
    assert "larger than" in capsys.readouterr().err
    assert Endless.given < MAX_JSON_BYTES + 1024 * 1024
    assert not out.exists()


def test_a_profile_tree_and_a_plan_configuration_are_bounded_too(tmp_path, capsys):
    system = tmp_path / "s.json"
    system.write_text(json.dumps(SMALL))
    cfg = tmp_path / "c.json"
    cfg.write_text('{"configurations": [], "configurations": []}')
    assert main(["plan", "startup", "--system", str(system), "--config", str(cfg)]) == 2
    assert "configurations: this key is given twice" in capsys.readouterr().err
