"""One name for one device in every panel (issue 11 item 6): the Simulator panel says what
the graph says (the catalogue's rule on what the bus reports), not the simulator's own
short name."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.gui


def test_the_simulator_panel_names_devices_as_the_graph_does(make_window, qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    panel = window._leaf_docks["sim"].widget()
    qtbot.waitUntil(lambda: panel.tree.topLevelItemCount() >= 4, timeout=10000)
    shown = {str(panel.tree.topLevelItem(i).data(0, 0x0100)): panel.tree.topLevelItem(i).text(0)
             for i in range(panel.tree.topLevelItemCount())}
    on_graph = {str(k): window.scene.device_label(d) for k, d in window.doc.system.devices.items()}
    assert on_graph and all(shown[k] == name for k, name in on_graph.items()), (shown, on_graph)
    # A spare part not on the bus gets the catalogue's product name, not a bare key.
    for key, name in shown.items():
        if key not in on_graph:
            assert not name.startswith("Device ") and name != key
    window.live.disconnect_bus()
