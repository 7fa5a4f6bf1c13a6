"""The main window offline: open, select, edit with undo, draw and delete links, save."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from PySide6.QtCore import QPointF, Qt
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QMessageBox

from pdcp_studio.app.window.main_window import MainWindow
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.storage import system_file

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"
CONTROL = DeviceKey(2641, 513, 201)
HAND = DeviceKey(2641, 769, 301)
FLEXOR = DeviceKey(2641, 257, 101)


@pytest.fixture
def window(make_window):
    return make_window(TRANSRADIAL, size=(1200, 800))


def test_open_shows_every_device_and_channel(window):
    doc = window.doc
    assert window.is_ready
    assert set(window.scene.cards) == set(doc.system.devices)
    assert len(doc.system.devices) == 4
    assert window.tree.topLevelItemCount() == 4
    rows = sum(window.tree.topLevelItem(i).childCount() for i in range(4))
    assert rows == sum(len(d.channels) for d in doc.system.devices.values())
    assert window.windowTitle().startswith("transradial.json")
    assert not window.isWindowModified()
    # Layers: sensors left of the control unit, the hand (terminal) right of it.
    x = {k: c.pos().x() for k, c in window.scene.cards.items()}
    assert x[FLEXOR] < x[CONTROL] < x[HAND]


def test_open_configuration_file(window):
    # A .pdcfg opens as its own document (app/configuration/window.py, issue 12); this window stays
    # on its prosthesis and plans against the opened configurations.
    links = set(window.doc.system.links)
    assert window.open_path(ROOT / "resources" / "configs" / "fig410.pdcfg")
    (cfg_window,) = window.config_windows
    assert cfg_window.config_list.count() == 2 and len(cfg_window.scene.link_items) == 1
    assert window.doc.config is not None and len(window.doc.config.configurations) == 2
    assert window.doc.kind == "system" and set(window.doc.system.links) == links
    cfg_window.close()


def test_open_bad_file_is_refused(window, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "nope"}')
    assert not window.open_path(bad)
    assert "Cannot open" in window.statusBar().currentMessage()
    assert len(window.doc.system.devices) == 4  # the old system stays


def test_selection_follows_tree_and_graph(window, qtbot):
    ref = ChannelRef(*HAND, 2)
    row = window.tree.row_for(ref)
    window.tree.setCurrentItem(row)
    assert window.doc.selection == ref
    card = window.scene.cards[HAND]
    assert card.isSelected() and card.selected_ref == ref
    assert window.inspector.subject == ref
    # Click a card on the graph: the tree follows.
    flex = window.scene.cards[FLEXOR]
    window.view.fit_all()
    pos = window.view.mapFromScene(flex.mapToScene(QPointF(60, 12)))
    QTest.mouseClick(window.view.viewport(), Qt.MouseButton.LeftButton, pos=pos)
    assert window.doc.selection == FLEXOR
    assert window.tree.selectedItems()[0] is window.tree.row_for(FLEXOR)


def test_edit_descriptor_undo_redo(window):
    ref = ChannelRef(*HAND, 1)
    window.doc.select(ref)
    edit = window.inspector.editors["descriptor"]
    edit.setText("Power grip motor")
    edit.editingFinished.emit()
    assert window.doc.channel(ref).descriptor == "Power grip motor"
    assert window.isWindowModified()
    assert window.doc.undo_stack.count() == 1
    window.act_undo.trigger()
    assert window.doc.channel(ref).descriptor == "Power grip"
    assert not window.isWindowModified()
    window.act_redo.trigger()
    assert window.doc.channel(ref).descriptor == "Power grip motor"
    # The inspector shows the model after undo/redo (it was rebuilt).
    assert window.inspector.editors["descriptor"].text() == "Power grip motor"


def test_invalid_profile_is_refused_inline(window):
    ref = ChannelRef(*HAND, 1)
    window.doc.select(ref)
    combo = window.inspector.editors["profile"]
    combo.setCurrentText("0x2020")
    combo.lineEdit().editingFinished.emit()
    err = window.inspector.errors["profile"]
    assert not err.isHidden()
    assert "follows a zero" in err.text()
    assert window.doc.channel(ref).profile == 0x2220
    assert window.doc.undo_stack.count() == 0
    combo.setCurrentText("0x2240")
    combo.lineEdit().editingFinished.emit()
    assert window.doc.channel(ref).profile == 0x2240
    assert window.doc.undo_stack.count() == 1


def test_profile_chosen_by_name_from_tree(window):
    ref = ChannelRef(*HAND, 3)
    window.doc.select(ref)
    combo = window.inspector.editors["profile"]
    i = next(i for i in range(combo.count()) if combo.itemData(i) == 0x2220)
    combo.setCurrentIndex(i)
    combo.activated.emit(i)
    assert window.doc.channel(ref).profile == 0x2220


def test_type_flags_and_required_inputs(window):
    ref = ChannelRef(*CONTROL, 1)
    window.doc.select(ref)
    before = window.doc.channel(ref).type
    window.inspector.editors["type.sole_access"].toggle()
    assert window.doc.channel(ref).type == before ^ 0x0200
    window.doc.select(ChannelRef(*CONTROL, 3))
    lst = window.inspector.editors["required_inputs"]
    items = {lst.item(i).data(Qt.ItemDataRole.UserRole): lst.item(i) for i in range(lst.count())}
    assert set(items) == {1, 2}  # the control unit's inputs, nothing else
    old = window.doc.channel(ChannelRef(*CONTROL, 3)).required_inputs
    target = items[2]
    target.setCheckState(Qt.CheckState.Unchecked if 2 in old else Qt.CheckState.Checked)
    new = window.doc.channel(ChannelRef(*CONTROL, 3)).required_inputs
    assert (2 in new) != (2 in old)
    assert window.doc.undo_stack.count() == 2
    window.doc.undo_stack.undo()
    assert window.doc.channel(ChannelRef(*CONTROL, 3)).required_inputs == old


def test_device_parameter_spinbox(window):
    window.doc.select(CONTROL)
    spin = window.inspector.editors["beacon_interval"]
    spin.setValue(250)
    spin.editingFinished.emit()
    assert window.doc.device(CONTROL).beacon_interval == 250
    # Read-only catalog parameters are shown as text, every one of them.
    from pdcp_studio.model.parameters import parameters_for

    shown = set(window.inspector.editors)
    for spec in parameters_for("device"):
        assert f"p{spec.id}" in shown or spec.id in (7, 8, 10, 11, 12)


def _drag(window, a: ChannelRef, b: ChannelRef) -> None:
    """Press on port a, move, release on port b — real mouse events on the viewport."""
    view = window.view
    view.fit_all()
    pa = view.mapFromScene(window.scene.port(a).scenePos())
    pb = view.mapFromScene(window.scene.port(b).scenePos())
    vp = view.viewport()
    QTest.mousePress(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, pa)
    mid = (pa + pb) / 2
    QTest.mouseMove(vp, mid)
    QTest.mouseMove(vp, pb)
    QTest.mouseRelease(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, pb)


def test_drag_a_link_then_undo(window):
    out, inp = ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1)
    _drag(window, out, inp)
    link = Link(out, inp)
    assert window.scene.last_link_result == (link, "")
    assert window.doc.system.has_link(link)
    assert link in window.scene.link_items
    window.act_undo.trigger()
    assert not window.doc.system.has_link(link)
    assert link not in window.scene.link_items


def test_drag_refused_with_reason(window):
    # The shipped system has no links: link one, then try to give that input a second source.
    _drag(window, ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))
    count = window.doc.undo_stack.count()
    _drag(window, ChannelRef(*CONTROL, 4), ChannelRef(*HAND, 1))
    link, reason = window.scene.last_link_result
    assert link is None and "already has a source" in reason
    assert "Cannot link" in window.statusBar().currentMessage()
    assert window.doc.undo_stack.count() == count
    # Output to output is refused too.
    _drag(window, ChannelRef(*FLEXOR, 1), ChannelRef(*CONTROL, 3))
    assert window.scene.last_link_result[0] is None


def test_delete_link_is_one_undo_step(window):
    link = Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))
    _drag(window, link.output, link.input)
    window.doc.select(link)
    assert window.scene.link_items[link].isSelected()
    window.act_delete.trigger()
    assert not window.doc.system.has_link(link)
    window.act_undo.trigger()
    assert window.doc.system.has_link(link)


def test_card_drag_is_remembered_and_undoable(window):
    card = window.scene.cards[HAND]
    start = card.pos()
    view = window.view
    view.fit_all()
    p0 = view.mapFromScene(card.mapToScene(QPointF(100, 10)))
    p1 = p0 + type(p0)(0, 60)
    vp = view.viewport()
    QTest.mousePress(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, p0)
    QTest.mouseMove(vp, p1)
    QTest.mouseRelease(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, p1)
    assert card.pos().y() > start.y()
    assert window.doc.positions[HAND] == (card.pos().x(), card.pos().y())
    window.act_undo.trigger()
    assert card.pos() == start


def test_save_and_reopen(window, tmp_path):
    link = Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))
    _drag(window, link.output, link.input)
    window.doc.select(ChannelRef(*HAND, 2))
    window.inspector.editors["descriptor"].setText("Pinch motor")
    window.inspector.editors["descriptor"].editingFinished.emit()
    window.doc.set_position(HAND, (900.0, 333.0))
    assert window.isWindowModified()
    path = tmp_path / "fitting.json"
    assert window.save_to(path)
    assert not window.isWindowModified()
    assert window.windowTitle().startswith("fitting.json")
    again = system_file.load_path(path)  # a valid pdcp-system/1 file
    assert again.has_link(link)
    assert json.loads(path.read_text())["x-pdcp-studio"]["positions"]
    assert window.open_path(path)
    assert window.doc.system.has_link(link)
    assert window.doc.channel(ChannelRef(*HAND, 2)).descriptor == "Pinch motor"
    assert window.scene.cards[HAND].pos().y() == 333.0
    cfg = tmp_path / "fitting.pdcfg"
    assert window.save_to(cfg)
    assert window.open_path(cfg)
    assert window.doc.kind == "config"
    assert set(window.doc.system.links) == {link}


def test_close_asks_when_dirty(window, monkeypatch):
    window.doc.select(ChannelRef(*HAND, 1))
    window.inspector.editors["descriptor"].setText("x")
    window.inspector.editors["descriptor"].editingFinished.emit()
    asked = []

    def answer(result):
        def ask():
            asked.append(result)
            return result
        return ask

    monkeypatch.setattr(window, "ask_save_changes", answer(QMessageBox.StandardButton.Cancel))
    assert not window.close()
    assert window.isVisible() and asked
    monkeypatch.setattr(window, "ask_save_changes", answer(QMessageBox.StandardButton.Discard))
    assert window.close()
    assert len(asked) == 2


def test_export_png_and_svg(window, tmp_path):
    window.export_graph(tmp_path / "g.png")
    window.export_graph(tmp_path / "g.svg")
    assert (tmp_path / "g.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    svg = (tmp_path / "g.svg").read_bytes()
    assert b"<svg" in svg and b"</svg>" in svg
    assert b"<image" not in svg  # cards drawn as vectors, not as their screen cache
    assert svg.count(b"<path") + svg.count(b"<text") > 20


def _content_box(image):
    """The bounding box (x0, y0, x1, y1) of pixels that differ from the corner pixel."""
    from PySide6.QtGui import QImage as _Q

    img = image.convertToFormat(_Q.Format.Format_RGB32)
    w, h = img.width(), img.height()
    bg = img.pixel(0, 0)
    xs, ys = [], []
    for y in range(0, h, 1):
        for x in range(0, w, 1):
            if img.pixel(x, y) != bg:
                xs.append(x)
                ys.append(y)
    return min(xs), min(ys), max(xs), max(ys)


def test_svg_and_png_exports_match_the_scene(window, tmp_path):
    """The SVG rendered back (QSvgRenderer) has the scene's size and its content sits where
    the PNG's does: nothing shifted, nothing clipped at the right or bottom."""
    from PySide6.QtGui import QImage, QPainter
    from PySide6.QtSvg import QSvgRenderer

    window.export_graph(tmp_path / "g.svg")
    window.export_graph(tmp_path / "g.png")
    rect = window.scene.itemsBoundingRect()
    renderer = QSvgRenderer(str(tmp_path / "g.svg"))
    assert renderer.isValid()
    box = renderer.viewBoxF()
    assert box.x() == 0 and box.y() == 0
    assert abs(box.width() - (rect.width() + 40)) <= 1
    assert abs(box.height() - (rect.height() + 40)) <= 1
    png = QImage(str(tmp_path / "g.png"))
    assert abs(png.width() - 2 * box.width()) <= 2 and abs(png.height() - 2 * box.height()) <= 2
    back = QImage(png.size(), QImage.Format.Format_ARGB32)
    back.fill(window.scene.backgroundBrush().color())
    painter = QPainter(back)
    renderer.render(painter)
    painter.end()
    svg_box, png_box = _content_box(back), _content_box(png)
    # The margin is on every side, in both files: nothing touches an edge (clipped).
    for got in (svg_box, png_box):
        assert got[0] >= 20 and got[1] >= 20, got
        assert png.width() - 1 - got[2] >= 20 and png.height() - 1 - got[3] >= 20, got
    assert all(abs(a - b) <= 3 for a, b in zip(svg_box, png_box, strict=True)), (svg_box, png_box)


def test_export_to_a_folder_that_does_not_exist_is_an_error(window, tmp_path):
    for name in ("g.svg", "g.png"):
        with pytest.raises(OSError):
            window.export_graph(tmp_path / "no-such-folder" / name)


def test_autosave_and_restore(qtbot, tmp_path, monkeypatch):
    from pdcp_studio.app.documents.recovery import Recovery

    rec = Recovery(tmp_path / "recovery")
    w = MainWindow(recovery=rec)
    w.quiet = True
    w.show()
    assert w.open_path(TRANSRADIAL)
    ref = ChannelRef(*HAND, 1)
    w.doc.select(ref)
    w.inspector.editors["descriptor"].setText("Autosaved name")
    w.inspector.editors["descriptor"].editingFinished.emit()
    worker = w.autosaver.save_now()
    assert worker is not None and worker.wait(5)
    qtbot.waitUntil(lambda: bool(rec.entries()), timeout=3000)
    entry = rec.entries()[0]
    other = MainWindow()
    other.quiet = True
    assert other.restore(entry)
    assert other.doc.channel(ref).descriptor == "Autosaved name"
    assert other.doc.is_dirty and other.doc.path == TRANSRADIAL
    other.doc.mark_saved()
    other.close()
    # Closing on purpose (Discard) removes the autosave: nothing is offered next time.
    monkeypatch.setattr(w, "ask_save_changes", lambda: QMessageBox.StandardButton.Discard)
    assert w.close()
    assert rec.entries() == []


def test_output_node_id_and_link_inspector(window):
    ref = ChannelRef(*CONTROL, 3)
    window.doc.select(ref)
    spin = window.inspector.editors["node_id"]
    assert spin.value() == -1 and spin.text() == "not assigned"
    spin.setValue(42)
    spin.editingFinished.emit()
    assert window.doc.channel(ref).node_id == 42
    # Every parameter of the output-channel catalog has a row (ID 1 is type + profile).
    from pdcp_studio.model.parameters import parameters_for

    rows = {1: "type", 2: "descriptor", 3: "transfer_type", 4: "data_enabled", 5: "node_id",
            9: "required_inputs", 10: "desired_inputs"}
    assert {s.id for s in parameters_for("output")} == set(rows)
    assert set(rows.values()) | {"profile"} <= set(window.inspector.editors)
    link = Link(ref, ChannelRef(*HAND, 1))
    _drag(window, link.output, link.input)
    window.doc.select(link)
    window.inspector.editors["delete"].click()
    assert not window.doc.system.has_link(link)
    assert window.doc.undo_stack.count() == 3  # node ID, link, delete


def test_system_overview_lists_checks(window):
    window.doc.select(None)
    lst = window.inspector.editors["findings"]
    texts = [lst.item(i).text() for i in range(lst.count())]
    # Plain words with what to do; the engine's message and rule key in the tooltip.
    assert any("nothing feeds it" in t and "Autoconfigure" in t for t in texts), texts
    tips = [lst.item(i).toolTip() for i in range(lst.count())]
    assert any("terminal-unconnected" in t and "not connected" in t for t in tips)
    lst.itemClicked.emit(lst.item(0))
    assert isinstance(window.doc.selection, ChannelRef)


def test_click_on_a_link_selects_it(window):
    link = Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))
    _drag(window, link.output, link.input)
    window.doc.select(None)
    item = window.scene.link_items[link]
    mid = item.path().pointAtPercent(0.5)
    pos = window.view.mapFromScene(mid)
    QTest.mouseClick(window.view.viewport(), Qt.MouseButton.LeftButton,
                     Qt.KeyboardModifier.NoModifier, pos)
    assert window.doc.selection == link
    assert window.inspector.editors.get("delete") is not None


def test_a_snapshot_where_every_device_left_updates_cards_and_overview_once(window, qtbot):
    """A live snapshot can change every device at once; the scene and the inspector follow
    once the event loop is free, not once per device."""
    window.doc.select(None)
    gone = window.doc.system.copy()
    for device in gone.devices.values():
        device.present = False
    rebuilds = []
    before = window.scene.states
    window.inspector.editors.clear()
    original = window.inspector.show_object
    window.inspector.show_object = lambda obj: (rebuilds.append(obj), original(obj))
    window.inspector._refresh_timer.timeout.disconnect()
    window.inspector._refresh_timer.timeout.connect(
        lambda: window.inspector.show_object(window.inspector._pending))
    window.doc.sync_live(gone)
    qtbot.waitUntil(lambda: "findings" in window.inspector.editors)
    assert len(rebuilds) == 1
    assert all(not card.device.present for card in window.scene.cards.values())
    assert window.scene.states is not before and not window.scene._states_timer.isActive()
