"""The bus graph on its own: layered layout, stability, states, zoom, big systems."""

from __future__ import annotations

import time
from pathlib import Path

from PySide6.QtCore import QRectF
from PySide6.QtGui import QImage, QPainter

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph import layout
from pdcp_studio.app.graph.analysis import compute_states, link_refusal
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.graph.view import GraphView
from pdcp_studio.engine import plan_autoconfigure
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link, System
from pdcp_studio.storage import system_file

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"


def linked_transradial() -> System:
    s = system_file.load_path(TRANSRADIAL)
    plan_autoconfigure(s).apply(s)
    return s


def big_system(n: int = 254) -> System:
    """n devices: sensors → control units → terminal devices, each control fed by 2 sensors."""
    s = System()
    groups = n // 4
    for g in range(groups):
        sensors = []
        for k in range(2):
            d = Device(10, 1, g * 2 + k + 1, name=f"Sensor {g}.{k}")
            d.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4222 + 2 * k))
            s.add_device(d)
            sensors.append(d)
        c = Device(10, 2, g + 1, name=f"Control {g}")
        c.add_channel(Channel(1, Direction.INPUT, type=0x9200, profile=0x4222))
        c.add_channel(Channel(2, Direction.INPUT, type=0x9200, profile=0x4224))
        c.add_channel(Channel(3, Direction.OUTPUT, type=0x9000, profile=0x2220))
        s.add_device(c)
        t = Device(10, 3, g + 1, name=f"Hand {g}")
        t.add_channel(Channel(1, Direction.INPUT, type=0x9300, profile=0x2220))
        s.add_device(t)
        s.add_link(Link(sensors[0].ref(1), c.ref(1)))
        s.add_link(Link(sensors[1].ref(1), c.ref(2)))
        s.add_link(Link(c.ref(3), t.ref(1)))
    for extra in range(n - 4 * groups):
        d = Device(10, 9, extra + 1, name=f"Spare {extra}")
        d.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4600))
        s.add_device(d)
    return s


def test_layers_sensors_control_terminal():
    s = linked_transradial()
    layers = layout.assign_layers(s)
    by_pid = {k.pid: v for k, v in layers.items()}
    assert by_pid[257] < by_pid[513] < by_pid[769]


def test_layout_stable_when_a_device_leaves_and_returns():
    s = linked_transradial()
    first = layout.place(s, {})
    hand = next(k for k in s.devices if k.pid == 769)
    removed = s.copy()
    removed.remove_device(hand)
    without = layout.place(removed, first)
    assert all(without[k] == first[k] for k in without)
    back = layout.place(s, without)
    assert all(back[k] == first[k] for k in without)
    # A newcomer never lands on another card.
    newcomer = Device(1, 1, 1, name="New sensor")
    newcomer.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4600))
    s.add_device(newcomer)
    placed = layout.place(s, first)
    nx, ny = placed[newcomer.key]
    for k, (x, y) in first.items():
        overlap_x = abs(nx - x) < layout.style.CARD_WIDTH
        overlap_y = ny < y + layout.card_height(s.devices[k]) and y < ny + 60
        assert not (overlap_x and overlap_y), k


def test_scene_keeps_card_position_when_device_removed(qtbot):
    doc = Document(linked_transradial())
    scene = BusScene(doc)
    keys = list(doc.system.devices)
    before = {k: (scene.cards[k].pos().x(), scene.cards[k].pos().y()) for k in keys}
    doc.remove_device(keys[0])
    for k in keys[1:]:
        assert (scene.cards[k].pos().x(), scene.cards[k].pos().y()) == before[k]


def test_states_and_refusals():
    s = linked_transradial()
    out = ChannelRef(2641, 257, 101, 1)
    ctrl_in2 = ChannelRef(2641, 513, 201, 2)
    assert "already has a source" in link_refusal(s, out, ctrl_in2)
    assert "starts at an output" in link_refusal(s, ctrl_in2, out)
    s.remove_link(Link(ChannelRef(2641, 257, 102, 1), ctrl_in2))
    assert "sole access" in link_refusal(s, out, ctrl_in2)
    st = compute_states(s)
    assert ctrl_in2 in st.unmet_required
    s.devices[DeviceKey(2641, 769, 301)].present = False
    st = compute_states(s)
    assert {lk.input.device for lk in st.missing_links} == {DeviceKey(2641, 769, 301)}


def test_zoom_and_fit(qtbot):
    doc = Document(linked_transradial())
    scene = BusScene(doc)  # kept: a view does not own its scene (GC would delete it)
    view = GraphView(scene)
    qtbot.addWidget(view)
    view.resize(800, 500)
    view.show()
    view.fit_all()
    rect = view.mapToScene(view.viewport().rect()).boundingRect()
    assert rect.contains(view.scene().itemsBoundingRect())
    z = view.zoom
    view.zoom_by(2.0)
    assert abs(view.zoom - 2 * z) < 1e-6
    view.set_zoom(100)
    assert view.zoom == 4.0


def test_254_devices_open_layout_render_under_a_second(qtbot):
    system = big_system(254)
    t0 = time.perf_counter()
    doc = Document(system)
    scene = BusScene(doc)
    rect = scene.itemsBoundingRect()
    image = QImage(1600, 1200, QImage.Format.Format_ARGB32)
    image.fill(0xFFFFFFFF)
    p = QPainter(image)
    scene.render(p, source=rect)
    p.end()
    elapsed = time.perf_counter() - t0
    assert len(scene.cards) == 254 and len(scene.link_items) == len(system.links)
    assert elapsed < 2.0, elapsed  # benchmarks/gui.py quotes it; 2 s leaves CI headroom
    # Roughly square, not one endless column.
    assert 0.3 < rect.width() / rect.height() < 5


def test_sensor_order_follows_the_input_ports():
    s = linked_transradial()
    # Put the extensor first in file order: the layout must still avoid the crossing.
    ext = DeviceKey(2641, 257, 102)
    devices = [s.devices[ext]] + [d for k, d in s.devices.items() if k != ext]
    s2 = System(devices, s.links)
    pos = layout.layered_layout(s2)
    assert pos[DeviceKey(2641, 257, 101)][1] < pos[ext][1]  # flexor → input 1, above


def test_unnamed_devices_take_catalogue_names_and_hex_moves_to_tooltips(qtbot):
    """A device without a name of its own is shown by its product from the device
    catalogue on its card and in the device tree; the card rows show profile names, and
    the hex profile code is in the row's tooltip."""
    from pdcp_studio.app.docks.tree_panel import DeviceTree

    system = linked_transradial()
    hand_key = next(k for k in system.devices if (k.vid, k.pid) == (2641, 769))
    system.devices[hand_key].name = ""
    system.devices[hand_key].descriptor = ""
    stranger = Device(4242, 7, 3)
    stranger.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4222))
    system.add_device(stranger)
    doc = Document(system)
    scene = BusScene(doc)
    hand = scene.cards[hand_key]
    assert scene.device_label(hand.device) == "Multi-grip hand"  # no other part reads so
    assert scene.device_label(stranger) == "unknown device (4242/7/3)"
    card_tip = scene.tooltip_for(hand, None)
    assert "Multi-grip hand" in card_tip and "PDCP Studio simulator" in card_tip
    row = next(iter(hand.device.channels.values()))
    row_tip = scene.tooltip_for(hand, row)
    assert f"0x{row.profile:04X}" in row_tip
    tree = DeviceTree(doc)
    qtbot.addWidget(tree)
    names = {tree.topLevelItem(i).text(0) for i in range(tree.topLevelItemCount())}
    assert "Multi-grip hand" in names
    assert "unknown device (4242/7/3)" in names
    # The card still paints (no hex column left to size the row text against), its rows
    # named from the profile tree.
    scene.render_pending()
    image = QImage(int(hand.width), int(hand.height), QImage.Format.Format_ARGB32)
    image.fill(0)
    painter = QPainter(image)
    scene.render(painter, QRectF(image.rect()), hand.sceneBoundingRect())
    painter.end()
    assert image.pixelColor(int(hand.width / 2), 10).alpha() > 0
    texts = hand.texts()
    assert scene.device_label(hand.device) in texts
    assert all(not t.startswith("0x") for t in texts)
