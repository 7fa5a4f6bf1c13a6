"""Writing the stored configuration: the diff first, then write, read back and verify — on the
real simulated prosthesis; and the compare dialog reading the arbitrator."""

from __future__ import annotations

import pytest

from pdcp_studio.app.dialogs import write_config_dialog as wcd
from pdcp_studio.app.dialogs.compare_dialog import CompareDialog
from pdcp_studio.app.dialogs.write_config_dialog import WriteConfigDialog, diff_rows
from pdcp_studio.app.live.session_bridge import SessionBridge
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.engine import configuration_from_system
from pdcp_studio.model.configuration import ConfigCollection, StoredConfiguration

pytestmark = pytest.mark.gui


@pytest.fixture
def bridge(qtbot):
    session = open_session("sim:thesis-test2")  # autoconfigured: 3 links, empty memory
    bridge = SessionBridge(session, interval_ms=20)
    yield bridge
    bridge.close(wait_ms=5000)
    assert session.closed


def _collection(system) -> ConfigCollection:
    return ConfigCollection([configuration_from_system(system)])


def _table(dialog: WriteConfigDialog) -> list[tuple[str, str]]:
    return [(dialog.table.item(r, 1).text(), dialog.table.item(r, 3).text())
            for r in range(dialog.table.rowCount())]


def test_diff_then_write_then_verify(qtbot, bridge):
    system = bridge.system()
    l1, l2, l3 = system.links
    partial = system.copy()
    partial.remove_link(l3)

    dialog = WriteConfigDialog.for_system(bridge, partial)
    qtbot.addWidget(dialog)
    assert dialog.state == wcd.READING and not dialog.write_button.isEnabled()
    qtbot.waitUntil(lambda: dialog.state == wcd.READY, timeout=5000)
    assert dialog.stored is not None and dialog.stored.configurations == []
    assert "stores no configuration" in dialog.message.text()
    assert "adds 2 links, removes 0" in dialog.message.text()
    assert [kind for kind, _ in _table(dialog)] == ["+ add", "+ add"]
    assert not dialog.write_button.isDefault() and not dialog.write_button.autoDefault()

    with qtbot.waitSignal(dialog.verified, timeout=10_000) as result:
        dialog.write_button.click()
    assert result.args[0] is True, result.args[1]
    assert dialog.state == wcd.VERIFIED and "Verified" in dialog.result.text()
    assert dialog.close_button.text() == "Close"
    stored = bridge.session.read_configuration()
    assert {(sl.output.ref, sl.input.ref) for sl in stored.configurations[0].links} == \
        {(l1.output, l1.input), (l2.output, l2.input)}

    # Writing the whole system now adds one link and keeps two.
    again = WriteConfigDialog.for_system(bridge, system)
    qtbot.addWidget(again)
    qtbot.waitUntil(lambda: again.state == wcd.READY, timeout=5000)
    assert sorted(kind for kind, _ in _table(again)) == ["+ add", "keep", "keep"]
    assert dict(_table(again))["+ add"].endswith("#2 (2/2/6)")  # named by the device
    with qtbot.waitSignal(again.verified, timeout=10_000) as result:
        again.write()
    assert result.args[0] is True
    assert len(bridge.session.read_configuration().configurations[0].links) == 3


def test_write_is_refused_before_the_diff_and_fails_cleanly_when_the_bus_is_gone(qtbot, bridge):
    dialog = WriteConfigDialog.for_system(bridge, bridge.system())
    qtbot.addWidget(dialog)
    assert dialog.write() is None  # still reading: nothing written
    qtbot.waitUntil(lambda: dialog.state == wcd.READY, timeout=5000)
    bridge.close(wait_ms=3000)
    with qtbot.waitSignal(dialog.verified, timeout=5000) as result:
        dialog.write_button.click()
    assert result.args == [False, "the bus connection is closed"]
    assert dialog.state == wcd.FAILED and "Failed" in dialog.result.text()


def test_compare_dialog_reads_the_arbitrator(qtbot, bridge):
    system = bridge.system()
    stored_system = system.copy()
    stored_system.remove_link(system.links[0])
    bridge.session.write_configuration(_collection(stored_system))
    dialog = CompareDialog(system, bridge=bridge)
    qtbot.addWidget(dialog)
    assert dialog.read_button.isEnabled()
    with qtbot.waitSignal(dialog.compared, timeout=5000):
        dialog.read_arbitrator()
    names = [dialog.table.horizontalHeaderItem(c).text()
             for c in range(dialog.table.columnCount())]
    assert names == ["Output", "Input", "On screen", "Arbitrator", "Status"]
    status = [dialog.table.item(r, 4).text() for r in range(dialog.table.rowCount())]
    assert sorted(status) == ["in all", "in all", "only in On screen"]
    qtbot.waitUntil(dialog.read_button.isEnabled, timeout=2000)


# -- the pure parts ------------------------------------------------------------------------
def test_the_dialog_lists_the_one_configuration_diff(systems_dir):
    from pdcp_studio.model.config_diff import diff_configurations
    from pdcp_studio.storage import system_file

    system = system_file.load_path(systems_dir / "appendix-d.json")
    full = configuration_from_system(system)
    two = StoredConfiguration(1, full.links[:2])
    stored = ConfigCollection([two, StoredConfiguration(2, full.links[2:])])
    new = ConfigCollection([full])
    rows = diff_rows(diff_configurations(stored, new), new)
    by_index = {i: sorted(kind for j, kind, _l in rows if j == i) for i in (1, 2)}
    assert by_index[1] == ["add", "keep", "keep"]  # configuration 1 gains one link
    assert by_index[2] == ["remove"]  # configuration 2 is not written again
    assert not diff_configurations(new, ConfigCollection([two])).equal


def test_a_refused_write_and_a_mismatching_read_back_are_shown(qtbot, bridge):
    from pdcp_studio.model.configuration import StoredChannel, StoredLink

    bad = ConfigCollection([StoredConfiguration(1, [StoredLink(
        StoredChannel(0, 2, 2, 6), StoredChannel(1, 2, 2, 4))])])  # channel index 0
    dialog = WriteConfigDialog(bridge, bad)
    qtbot.addWidget(dialog)
    qtbot.waitUntil(lambda: dialog.state == wcd.READY, timeout=5000)
    with qtbot.waitSignal(dialog.verified, timeout=5000) as result:
        dialog.write()
    ok, message = result.args
    assert not ok and message.startswith("writing failed:") and "index" in message
    assert dialog.state == wcd.FAILED
    assert bridge.session.read_configuration().configurations == []  # nothing was stored

    good = WriteConfigDialog.for_system(bridge, bridge.system())
    qtbot.addWidget(good)
    qtbot.waitUntil(lambda: good.state == wcd.READY, timeout=5000)
    good._on_read_back(ConfigCollection())  # as if the arbitrator had kept nothing
    assert good.state == wcd.MISMATCH and "Verification failed" in good.result.text()


def test_a_cancelled_read_back_fails_instead_of_staying_unclosable(qtbot, bridge, monkeypatch):
    from pdcp_studio.app.workers import Cancelled, Worker

    dialog = WriteConfigDialog.for_system(bridge, bridge.system())
    qtbot.addWidget(dialog)
    qtbot.waitUntil(lambda: dialog.state == wcd.READY, timeout=5000)

    def cancelled(_p, _c):
        raise Cancelled

    monkeypatch.setattr(bridge, "read_configuration", lambda: Worker(cancelled, "read").start())
    with qtbot.waitSignal(dialog.verified, timeout=5000) as result:
        dialog._read_back()  # as if the bus closed while verifying
    assert result.args == [False, "cancelled while verifying"]
    assert dialog.state == wcd.FAILED and dialog.close_button.text() == "Close"
