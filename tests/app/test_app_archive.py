"""The app and the clinic's archive (issue 25): it signs in once per session — libpq's own
password sources first, else a dialog — and says who is signed in in the status bar; the
operator it records is then the signed-in one; the History panel filters by patient and
says where each change was made."""

from __future__ import annotations

import pytest

from tests.pg_cluster import FITTER, FITTER_NAME, PASSWORD, PASSWORD_ROLE, READER

pytestmark = pytest.mark.gui
T = 20000


@pytest.fixture(autouse=True)
def new_session():
    from pdcp_studio.app.documents import sign_in
    from pdcp_studio.storage.archive.postgres import forget_passwords

    sign_in.forget()
    forget_passwords()
    yield
    sign_in.forget()
    forget_passwords()


def test_the_status_bar_says_who_is_signed_in_and_the_operator_follows(
        make_window, qtbot, pg_db, monkeypatch):
    from pdcp_studio.app.documents import fitting

    monkeypatch.setenv("PDCP_STUDIO_ARCHIVE", pg_db.fitter)
    window = make_window()
    label = window.archive_status.label
    qtbot.waitUntil(lambda: "signed in" in label.text(), timeout=T)
    assert label.text() == f"Fitting history: signed in as {FITTER_NAME} ({FITTER})"
    assert pg_db.cluster.url(FITTER).split("@")[1].split("/")[0] in label.toolTip()
    assert fitting.stored_operator() == FITTER_NAME  # not $PDCP_STUDIO_OPERATOR
    assert window.pending_panel.operator.text() == f"Operator: {FITTER_NAME}"


def test_a_reader_is_said_to_be_read_only(make_window, qtbot, pg_db, monkeypatch):
    monkeypatch.setenv("PDCP_STUDIO_ARCHIVE", pg_db.reader)
    window = make_window()
    label = window.archive_status.label
    qtbot.waitUntil(lambda: "signed in" in label.text(), timeout=T)
    assert label.text() == f"Fitting history: signed in as {READER}, read only"


def test_a_password_is_asked_once_and_never_written_down(pg_db, tmp_path):
    from pdcp_studio.app.documents import sign_in

    url = pg_db.cluster.url(PASSWORD_ROLE, pg_db.name)
    asked = []

    def ask(_parent, location, why):
        asked.append(why)
        return "wrong" if len(asked) == 1 else PASSWORD

    state = sign_in.sign_in(url=url, ask=ask)
    assert len(asked) == 2 and state.role == PASSWORD_ROLE and not state.error
    # Signed in once: the archive opens again without asking (kept in memory only).
    from pdcp_studio.storage.archive import open_archive

    with open_archive(url) as archive:
        assert archive.signed_in() == PASSWORD_ROLE
    written = [p for p in tmp_path.rglob("*") if p.is_file()
               and PASSWORD.encode() in p.read_bytes()]
    assert written == []


def test_libpqs_own_password_source_needs_no_dialog(pg_db, monkeypatch):
    from pdcp_studio.app.documents import sign_in

    monkeypatch.setenv("PGPASSWORD", PASSWORD)
    state = sign_in.sign_in(url=pg_db.cluster.url(PASSWORD_ROLE, pg_db.name),
                            ask=lambda *_a: pytest.fail("asked for a password"))
    assert state.role == PASSWORD_ROLE


def test_a_declined_password_dialog_leaves_nobody_signed_in(pg_db):
    from pdcp_studio.app.documents import sign_in

    state = sign_in.sign_in(url=pg_db.cluster.url(PASSWORD_ROLE, pg_db.name),
                            ask=lambda *_a: None)
    assert state.role is None and "password" in state.error
    assert state.status_text() == "Fitting history: not signed in"


def test_on_this_computers_archive_nobody_signs_in(make_window):
    window = make_window()
    assert window.archive_status.label.text() == "Fitting history: this computer"


def test_the_history_panel_filters_by_patient_and_names_the_workstation(make_window, qtbot):
    import socket

    from pdcp_studio.bus.transaction import Change

    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=T):
        window.connect_bus("sim:transradial")
    session = window.live.bridge.session
    links = sorted(session.system().links)
    assert session.transact(Change.links_to(links, links[1:], "one less"),
                            patient="P-100").written
    assert session.transact(Change.links_to(links[1:], links, "again"),
                            patient="Q-200").written
    panel = window.history_panel
    with qtbot.waitSignal(panel.loaded, timeout=5000):
        panel.refresh()
    panel.scope.setCurrentIndex(1)  # all prostheses
    assert len(panel.shown) == 2
    panel.patient_filter.setText("p-1")
    assert [e["patient"] for e in panel.shown] == ["P-100"]
    panel.select_ids(panel.shown[0]["id"])
    assert f"Workstation: {socket.gethostname()}" in panel.details.toPlainText()
    panel.patient_filter.clear()
    assert len(panel.shown) == 2


def test_a_full_name_from_the_server_is_shown_not_run(pg_db):
    from pdcp_studio.app.documents import sign_in

    pg_db.cluster.sql(f"UPDATE pdcp.operators SET full_name = E'Anna\\x1b[2J' "
                      f"WHERE role = '{FITTER}'", pg_db.name)
    state = sign_in.sign_in(url=pg_db.fitter)
    assert state.operator == "Anna\x1b[2J"  # recorded as the clinic wrote it
    assert "\x1b" not in state.status_text() and "Anna\\x1b[2J" in state.status_text()
