"""A change beyond what the host link carries is refused before sending and before the
fitting history announces it (issue 28): a 90 KB configuration once crashed with
``struct.error`` and left a false "interrupted" entry; now it, a 40 KB one and one just over
the limit are refused in words naming the size and the limit, and nothing is recorded."""

from __future__ import annotations

import pytest

from pdcp_studio.bus.hostlink.change import MAX_CHANGE, ChangeTooLarge, encode_change, size_problem
from pdcp_studio.bus.transaction import Change, Status
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.storage import config_codec
from pdcp_studio.storage.history import History
from tests.road_rigs import served


def collection(links: int) -> ConfigCollection:
    return ConfigCollection([StoredConfiguration(1, [
        StoredLink(StoredChannel(1, 2, 2, 9, 0x5300, 0x1110),
                   StoredChannel(n % 255 + 1, 2, 2, 1000 + n // 255, 0x5000, 0x1100), n + 1)
        for n in range(links)])])


def _links_for(size: int) -> int:
    """The number of links whose configuration takes a little more than ``size`` bytes."""
    per = len(config_codec.dumps(collection(101))) - len(config_codec.dumps(collection(100)))
    return size // per + 1


def test_size_problem_names_the_size_and_the_limit_and_never_raises_struct_error():
    fits = Change("small", configuration=collection(100))
    assert size_problem(fits) is None
    huge = Change("huge", configuration=collection(_links_for(90_000)))
    with pytest.raises(ChangeTooLarge):
        encode_change(huge)
    why = size_problem(huge)
    assert why is not None
    size = len(config_codec.dumps(huge.configuration))
    assert f"its stored configuration {size:,} bytes" in why
    assert f"at most {MAX_CHANGE:,} bytes" in why and "nothing was sent" in why
    over = Change("over", configuration=collection(_links_for(MAX_CHANGE)))
    assert size_problem(over) is not None and "the change takes " in size_problem(over)


@pytest.mark.parametrize("size", [MAX_CHANGE, 40_000, 90_000])
def test_a_change_beyond_the_limit_is_refused_before_sending_and_recording(tmp_path, size):
    from pdcp_studio.bus.session.opening import open_session

    archive = History(tmp_path / "history.sqlite3")
    with served("thesis-test2", tmp_path / "m.mem") as (arbitrator, _host, url):
        generation = arbitrator.memory.generation
        session = open_session(url)
        try:
            change = Change("config write big", configuration=collection(_links_for(size)))
            result = session.transact(change, history=archive)
            assert (result.status, result.step) == (Status.FAILED, "preview")
            assert "the change takes " in result.reason
            assert f"at most {MAX_CHANGE:,} bytes" in result.reason
            assert archive.recover() == [] and archive.entries() == []  # no false entry
            assert session.carry_out(change).status is Status.FAILED  # unrecorded road too
            small = Change("config write small", configuration=collection(50))
            assert session.transact(small, history=archive).written  # the link still works
        finally:
            session.close()
        # only the small one arrived: its configuration, and the anchor before and after it
        assert arbitrator.memory.generation == generation + 3
    assert [e["action"] for e in archive.entries()] == ["config write small"]
    archive.close()


def test_config_write_of_a_huge_file_over_the_host_link_says_why(tmp_path, capsys):
    from pdcp_studio.cli.main import main

    big = tmp_path / "big.pdcfg"
    config_codec.save_path(collection(_links_for(90_000)), big)
    with served("thesis-test2", tmp_path / "m.mem") as (_arbitrator, _host, url):
        code = main(["config", "write", str(big), "--bus", url, "--yes"])
    out, err = capsys.readouterr()
    assert code == 1, (out, err)
    assert "Traceback" not in err and "struct" not in err
    assert f"the host link carries at most {MAX_CHANGE:,} bytes per change" in err
    assert "recorded as fitting history entry" not in out
    assert main(["history", "list"]) == 0
    assert capsys.readouterr().out.strip() == "the fitting history is empty"
