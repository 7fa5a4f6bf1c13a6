"""The last loose ends of issue 26's words (points 8 and 9): no bracketed plural left in the
German file or in an English source, every channel by its one name in the guided tasks and
the stored-configuration window, an undo text that names the part moved, and the outcome
of a change to the prosthesis in the user's words in the status bar."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from PySide6.QtWidgets import QApplication

from pdcp_studio.app import i18n
from pdcp_studio.app.configuration.window import configuration_names
from pdcp_studio.app.configuration.words import ConfigWords
from pdcp_studio.app.documents import commands
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.words import plan_words
from pdcp_studio.app.words.outcome_words import outcome_words
from pdcp_studio.app.words.part_names import part_name
from pdcp_studio.bus.sim.rigs import HAND, SPARE_HAND, load_prosthesis
from pdcp_studio.bus.transaction import Status, TransactionResult
from pdcp_studio.engine import plan_autoconfigure
from pdcp_studio.model.configuration import StoredChannel
from pdcp_studio.model.profile_tree import ProfileNames
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link

ROOT = Path(__file__).resolve().parents[2]
TS = ROOT / "resources" / "i18n" / "pdcp_studio_de.ts"
#: "(s)" as the unit seconds, not a plural.
SECONDS = {"time before now (s)", "time before the hold (s)"}
CONTROL = DeviceKey(2641, 513, 201)


@pytest.fixture
def german(qapp):
    i18n.install(qapp, "de")
    yield
    i18n.uninstall(qapp)


def _bus():
    """sim:transradial's parts as the bus reports them: no names, only descriptors."""
    system = load_prosthesis("transradial")
    for device in system.devices.values():
        device.name = ""
    return system


def _messages():
    for context in ET.parse(TS).getroot().iter("context"):
        for message in context.iter("message"):
            yield context.findtext("name"), message


# -- plurals -----------------------------------------------------------------------------
def test_no_german_translation_leaves_a_plural_in_brackets():
    left = []
    for context, message in _messages():
        for text in message.find("translation").itertext():
            if re.search(r"\((e|en|n|s)\)", text) and message.findtext("source") not in SECONDS:
                left.append(f"{context}: {text.strip()!r}")
    assert not left, "\n".join(left)


def test_every_english_source_with_a_plural_in_brackets_is_a_plural_message():
    """A source with "(s)" is a numerus message (``count``: "1 link", "2 links"); a source
    filled in with .format() would show the "(s)" to the user."""
    left = [f"{context}: {message.findtext('source')!r}" for context, message in _messages()
            if re.search(r"\((s|es)\)", message.findtext("source") or "")
            and message.findtext("source") not in SECONDS
            and message.get("numerus") != "yes"]
    assert not left, "\n".join(left)
    numerus = [m for _c, m in _messages() if m.get("numerus") == "yes"]
    assert len(numerus) > 50
    assert all("%n" in m.findtext("source") for m in numerus)


def _scene(qtbot):
    from pdcp_studio.app.graph.scene import BusScene

    system = _bus()
    plan_autoconfigure(system).apply(system)
    doc = Document(system)
    scene = BusScene(doc)
    said: list[str] = []
    scene.statusMessage.connect(said.append)
    return doc, scene, said


@pytest.mark.parametrize(("lang", "one", "two"), [
    ("en", "Removed 1 link", "Removed 2 links"),
    ("de", "1 Verbindung entfernt", "2 Verbindungen entfernt"),
])
def test_removing_links_counts_them_in_the_status_bar(qtbot, lang, one, two):
    app = QApplication.instance()
    if lang == "de":
        i18n.install(app, "de")
    try:
        doc, scene, said = _scene(qtbot)
        links = sorted(doc.system.links, key=str)[:3]
        doc.select(links[0])
        assert scene.delete_selected() == 1
        for link in links[1:]:
            scene.link_items[link].setSelected(True)
        assert scene.delete_selected() == 2
    finally:
        if lang == "de":
            i18n.uninstall(app)
    assert said == [one, two]


# -- undo texts --------------------------------------------------------------------------
def test_moving_a_part_names_it_in_the_undo_text(qtbot):
    system = _bus()
    doc = Document(system)
    move = commands.MoveDeviceCommand(doc, HAND, (0.0, 0.0), (10.0, 0.0))
    assert move.text() == f"Move {part_name(system, HAND)}"
    assert move.text() == "Move Multi-grip hand with wrist rotator (serial 301)"
    assert "2641" not in move.text()
    one = commands.MoveDevicesCommand(doc, {HAND: ((0.0, 0.0), (1.0, 0.0))})
    two = commands.MoveDevicesCommand(doc, {HAND: ((0.0, 0.0), (1.0, 0.0)),
                                            CONTROL: ((0.0, 0.0), (1.0, 0.0))})
    assert (one.text(), two.text()) == ("Move 1 part", "Move 2 parts")


def test_moving_and_applying_a_plan_read_german(german):
    system = _bus()
    doc = Document(system)
    assert commands.MoveDeviceCommand(doc, HAND, None, (1.0, 1.0)).text() == \
        f"{part_name(system, HAND)} verschieben"
    moved = commands.MoveDevicesCommand(doc, {HAND: ((0.0, 0.0), (1.0, 0.0)),
                                              CONTROL: ((0.0, 0.0), (1.0, 0.0))})
    assert moved.text() == "2 Teile verschieben"
    plan = plan_autoconfigure(_bus())
    assert commands.push_plan(doc, plan)
    n = len(plan.actions)
    assert doc.undo_stack.text(doc.undo_stack.index() - 1) == \
        f"Plan ausführen ({n} {'Schritt' if n == 1 else 'Schritte'})"


def test_applying_a_plan_counts_its_steps_in_english():
    doc = Document(_bus())
    plan = plan_autoconfigure(_bus())
    assert commands.push_plan(doc, plan)
    n = len(plan.actions)
    assert n > 1
    assert doc.undo_stack.text(0) == f"Apply the plan ({n} steps)"


# -- one name per channel ----------------------------------------------------------------
def test_the_guided_tasks_name_a_channel_as_every_panel_does():
    from pdcp_studio.app.wizards import words

    system = _bus()
    for ref in (ChannelRef(*HAND, 1), ChannelRef(*HAND, 3), ChannelRef(*CONTROL, 3)):
        assert words.channel_phrase(system, ref) == plan_words.channel_words(system, ref)
        assert ", channel " not in words.channel_phrase(system, ref)
    assert words.channel_phrase(system, ChannelRef(*HAND, 1)) == \
        "Multi-grip hand with wrist rotator (serial 301), Power grip"
    link = Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))
    assert words.link_words(system, link) == plan_words.link_words(
        system, link.output, link.input)


def test_a_replacement_names_a_channel_no_longer_on_the_bus_by_its_one_name():
    """The hand taken out and no longer seen (a fresh scan): the plan's reason names its
    channel as the graph did, by what the plan remembers of it."""
    from pdcp_studio.app.wizards import logic, words

    system = _bus()
    plan_autoconfigure(system).apply(system)
    swapped = system.copy()
    swapped.devices[HAND].present = False
    swapped.devices[SPARE_HAND].present = True
    plan = logic.replacement_plan(swapped, None, [SPARE_HAND])
    seen = swapped.copy()
    del seen.devices[HAND]
    words.shown_system = lambda: swapped  # the graph still shows the hand
    try:
        lines = "\n".join(words.plan_lines(seen, plan))
    finally:
        words.shown_system = None
    assert "It takes the place of Multi-grip hand with wrist rotator (serial 301), " \
           "Power grip, which is gone" in lines, lines
    assert "→ Multi-grip hand with wrist rotator (serial 301), Power grip\n" in lines
    assert ", channel 1" not in lines


def test_a_channel_of_a_german_guided_task_reads_german(german):
    from pdcp_studio.app.wizards import words

    system = _bus()
    device = system.devices[HAND]
    device.channels[2].descriptor = ""
    assert words.channel_phrase(system, ChannelRef(*HAND, 2)).endswith(", Kanal 2")


def _stored(ref: ChannelRef) -> StoredChannel:
    return StoredChannel(ref.index, ref.vid, ref.pid, ref.serial)


def test_the_configuration_window_names_stored_channels_by_the_one_naming():
    """On the prosthesis: the channel's one name (its descriptor); not on it: the part by
    its catalogue product (serial numbers only for twins), the channel by its number."""
    system = _bus()
    hand = ChannelRef(*HAND, 1)
    away = ChannelRef(2641, 769, 399, 1)  # a hand of the same product, not on the bus
    names = configuration_names(system, [])
    config_words = ConfigWords(lambda: names, ProfileNames)
    assert config_words.channel_text(_stored(hand)) == plan_words.channel_words(system, hand)
    assert config_words.channel_text(_stored(hand)).endswith(", Power grip")
    text = config_words.channel_text(_stored(away))
    assert text.endswith(", channel 1") and "2641" not in text and "unknown" not in text
    # Two parts of one product known only by their numbers: told apart by serial number.
    from pdcp_studio.model.configuration import StoredConfiguration, StoredLink

    a, b = ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 1)
    cfg = StoredConfiguration(1, [StoredLink(_stored(b), _stored(a), 1)])
    names = configuration_names(None, [cfg])
    config_words = ConfigWords(lambda: names, ProfileNames)
    first, second = config_words.channel_text(_stored(a)), config_words.channel_text(_stored(b))
    assert first != second and "(serial 4)" in first and "(serial 5)" in second


def test_a_finding_names_its_channel_by_the_one_naming():
    from pdcp_studio.app.words.finding_text import channel_words, plain_finding
    from pdcp_studio.engine.checks import Finding, Severity

    system = _bus()
    ref = ChannelRef(*HAND, 2)
    assert channel_words(system, ref) == plan_words.channel_words(system, ref)
    assert channel_words(system, ref, {HAND: "Hand"}) == "Hand, Pinch grip"
    finding = Finding(Severity.WARNING, "terminal-unconnected", "input 2641/769/301#2", (ref,))
    text = plain_finding(finding, system)
    assert text.startswith("Multi-grip hand with wrist rotator (serial 301), Pinch grip drives")
    system.devices[HAND].channels[2].descriptor = ""
    assert channel_words(system, ref).endswith(", channel 2")


def test_the_report_names_a_link_end_by_the_one_naming():
    from pdcp_studio.app.report import _end
    from pdcp_studio.storage.profile_trees import load_profile_tree

    system = _bus()
    text = _end(system, load_profile_tree(user_dir=False), ChannelRef(*HAND, 1))
    assert text.startswith("<b>Multi-grip hand with wrist rotator (serial 301)</b>, Power grip<br>")
    assert "channel 1" not in text


# -- the outcome of a change -------------------------------------------------------------
def _result(status: Status, **kw) -> TransactionResult:
    return TransactionResult(status, "config write", **kw)


LINKS = [Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1)),
         Link(ChannelRef(*CONTROL, 4), ChannelRef(*HAND, 2))]


@pytest.mark.parametrize(("result", "text"), [
    (_result(Status.APPLIED, links_after=LINKS[:1]),
     "Write to prosthesis: written and verified — 1 link on the prosthesis"),
    (_result(Status.APPLIED, links_after=LINKS, held=[HAND, CONTROL]),
     "Write to prosthesis: written and verified — 2 links on the prosthesis; "
     "2 parts held still while writing"),
    (_result(Status.NOTHING), "Write to prosthesis: nothing to change on the prosthesis"),
    (_result(Status.DECLINED), "Write to prosthesis: not confirmed, nothing written"),
    (_result(Status.ROLLED_BACK, step="verify", reason="channel 2 reads 0x00"),
     "Write to prosthesis: stopped while reading back; what was written is undone: "
     "channel 2 reads 0x00"),
    (_result(Status.FAILED, step="interlock", reason="the hand is moving"),
     "Write to prosthesis: failed while holding the parts still: the hand is moving"),
])
def test_the_outcome_of_a_change_in_words(result, text):
    said = outcome_words(result, "Write to prosthesis")
    assert said == text
    assert "(s)" not in said and "config write" not in said and "step " not in said


def test_the_outcome_of_a_change_reads_german(german):
    title = "Auf die Prothese schreiben"
    assert outcome_words(_result(Status.APPLIED, links_after=LINKS), title) == \
        f"{title}: geschrieben und geprüft — 2 Verbindungen an der Prothese"
    assert outcome_words(_result(Status.APPLIED, links_after=LINKS[:1], held=[HAND]),
                         title) == (f"{title}: geschrieben und geprüft — 1 Verbindung an der "
                                    "Prothese; 1 Teil während des Schreibens stillgehalten")
    assert outcome_words(_result(Status.NOTHING), title) == \
        f"{title}: an der Prothese ist nichts zu ändern"
    assert outcome_words(_result(Status.FAILED, step="write", reason="timeout"), title) == \
        f"{title}: beim Schreiben fehlgeschlagen: timeout"


@pytest.mark.gui
def test_a_written_change_says_its_outcome_in_the_status_bar(make_window, qtbot):
    """On sim:transradial: a link removed and written; the status bar says so in words."""
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    try:
        assert window.live.is_live
        qtbot.waitUntil(lambda: window.doc.config is not None, timeout=5000)
        window.flow.confirm = lambda title, preview: True
        said: list[str] = []
        say = window.flow.status.say
        window.flow.status.say = lambda text, *a, **k: (said.append(text), say(text, *a, **k))
        link = Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))
        window.doc.select(link)
        window.act_delete.trigger()
        with qtbot.waitSignal(window.flow.finished, timeout=20000) as got:
            window.write_pending()
        result = got.args[0]
        assert result.written, result.summary()
        n = len(result.links_after)
        assert (f"Write to prosthesis: written and verified — {n} links on the prosthesis"
                in said[-1]), said
        assert not any(result.summary() in text for text in said)
    finally:
        window.live.disconnect_bus()
