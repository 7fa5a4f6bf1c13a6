"""The change road with the clinic's archive (issue 25): on both engines a change is
recorded with its workstation; on PostgreSQL a reader's change and a change while the server
is down are refused before any frame reaches the prosthesis, and a server lost mid-change
leaves the prosthesis old or new with its outcome recorded once the server is back."""

from __future__ import annotations

import pytest

from pdcp_studio.bus.session.api import open_session
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.transaction import Change, Status
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import SetParameter
from pdcp_studio.storage.archive import open_archive
from tests.pg_cluster import FITTER_NAME, READER
from tests.road_rigs import FrameRecorder

JOY = Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2))


@pytest.fixture
def rig():
    channel = unique_virtual_channel("road-archive")
    recorder = FrameRecorder(channel)
    session = open_session("sim:thesis-test2", channel=channel)
    try:
        yield session, recorder
    finally:
        session.close()
        recorder.close()


def _writes(recorder) -> int:
    recorder.caught_up()
    return sum(isinstance(m, SetParameter) for m in recorder.messages())


def _clear(session) -> Change:
    return Change.from_plan(session.preview("clear"))


def test_a_change_is_recorded_with_its_workstation_on_either_engine(rig, archive_url):
    import socket

    session, _ = rig
    with open_archive(archive_url) as archive:
        result = session.transact(_clear(session), patient="P-9", history=archive)
        assert result.written and result.history_id == 1
        entry = archive.get(1)
    assert entry["workstation"] == socket.gethostname() and entry["patient"] == "P-9"


def test_a_readers_change_is_refused_before_any_frame_in_words(rig, pg_db):
    session, recorder = rig
    before = _writes(recorder)
    with open_archive(pg_db.reader) as archive:
        result = session.transact(_clear(session), history=archive)
        assert archive.entries() == []
    assert result.status is Status.FAILED and result.step == "record"
    assert (f"signed in as {READER}, who may read the fitting history but not record "
            "changes" in result.reason)
    assert "nothing was written to the prosthesis" in result.reason
    assert _writes(recorder) == before and JOY in session.system().links


def test_the_server_stopped_before_a_change_refuses_it_before_any_frame(rig, pg_db,
                                                                         monkeypatch):
    session, recorder = rig
    monkeypatch.setenv("PDCP_STUDIO_ARCHIVE", pg_db.fitter)
    before = _writes(recorder)
    pg_db.cluster.stop()
    try:
        result = session.transact(_clear(session))  # the archive in use: the stopped server
    finally:
        pg_db.cluster.start()
    assert result.status is Status.FAILED and result.step == "record"
    assert "cannot be reached" in result.reason
    assert "nothing was written to the prosthesis" in result.reason
    assert _writes(recorder) == before and JOY in session.system().links


def test_the_server_lost_mid_change_the_outcome_is_recorded_when_it_is_back(
        rig, pg_db, monkeypatch, tmp_path):
    """The cluster stops while the arbitrator writes: the prosthesis ends new (the
    transaction is whole), the outcome waits in this workstation's journal, and the next
    open of the archive records it — nothing is lost."""
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    session, _ = rig
    stopped = []

    def progress(done, total, what):
        if not stopped:
            stopped.append(what)
            pg_db.cluster.stop("immediate")

    archive = open_archive(pg_db.fitter)
    try:
        result = session.transact(_clear(session), progress=progress, history=archive)
    finally:
        archive.close()
        pg_db.cluster.start()
    assert stopped, "the change reported no progress: the server was never stopped"
    assert result.written and session.system().links == []  # the prosthesis ends new
    assert result.history_id is None
    note = " ".join(result.notes)
    assert "not recorded yet" in note and "recorded when the archive can be reached" in note
    with open_archive(pg_db.fitter) as back:
        assert back.recover() == [1]
        entry = back.get(1)
        assert entry["outcome"]["status"] == result.status.value and entry["links_after"] == []
        assert entry["recorded_late"] is True and entry["operator"] == FITTER_NAME
        assert back.recover() == [] and back.verify().ok  # recorded once, not twice
