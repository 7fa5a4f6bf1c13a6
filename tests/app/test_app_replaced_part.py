"""In the window, a replaced hand is no longer missing (issue 26 item 6): once the
replacement's transaction is written and verified the document drops the hand, nothing
counts it missing, and Bus events says what replaced it."""

from __future__ import annotations

import pytest

from pdcp_studio.app.wizards import logic
from pdcp_studio.bus.sim.rigs import HAND, SPARE_HAND

pytestmark = pytest.mark.gui


def _missing(window):
    return [k for k, d in window.doc.system.devices.items() if not d.present]


def test_after_the_replacement_is_written_the_old_hand_is_not_missing(make_window, qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    panel = window._leaf_docks["events"].widget()
    session = window.live.bridge.session
    qtbot.waitUntil(lambda: len(session.system().links) == 5, timeout=15000)  # started up
    session.save_configuration()
    session.unplug(HAND)
    qtbot.waitUntil(lambda: _missing(window) == [HAND], timeout=10000)
    session.plug(SPARE_HAND)
    qtbot.waitUntil(lambda: sum(lk.input.device == SPARE_HAND
                                for lk in window.doc.system.links) == 3, timeout=15000)
    assert _missing(window) == [HAND]  # linked by the duty cycle, not yet a fitting

    window.flow.confirm = lambda _title, _preview: True
    # The Replace a part wizard's own change: the replacement plan's links and the stored
    # configuration naming the new part.
    system = session.system()
    change = logic.replacement_change(system, logic.replacement_plan(
        system, session.read_configuration(), [SPARE_HAND]))
    with qtbot.waitSignal(window.flow.finished, timeout=20000) as got:
        window.flow.run(change, "Replace a part")
    assert got.args[0].written, got.args[0].summary()
    assert "replaced 2641/769/301 by 2641/769/302" in got.args[0].notes
    qtbot.waitUntil(lambda: HAND not in window.doc.system.devices, timeout=10000)
    assert _missing(window) == []
    qtbot.waitUntil(lambda: any("is replaced by" in w for w, _y, _s in panel.rows()),
                    timeout=10000)
    (what,) = [w for w, _y, _s in panel.rows() if "is replaced by" in w]
    assert "hand" in what.lower() and not any("missing" in w for w, _y, _s in panel.rows()
                                              if "replaced" in w)
    window.live.disconnect_bus()
