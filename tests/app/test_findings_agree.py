"""The graph marks exactly what the Checks list (and ``pdcp-studio check``) reports."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdcp_studio import paths
from pdcp_studio.app.graph.analysis import compute_states
from pdcp_studio.bus.sim import rigs as simulator
from pdcp_studio.engine import plan_autoconfigure
from pdcp_studio.engine.checks import check_system
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import System
from pdcp_studio.storage import system_file


def _systems() -> list[tuple[str, System]]:
    out = []
    for path in sorted(paths.systems_dir().glob("*.json")):
        for variant in ("as shipped", "autoconfigured", "last device unplugged"):
            s = system_file.load_path(path)
            if variant != "as shipped":
                plan_autoconfigure(s).apply(s)
            if variant == "last device unplugged":
                list(s.devices.values())[-1].present = False
            out.append((f"{path.stem} {variant}", s))
    large = simulator.large_system()
    plan_autoconfigure(large).apply(large)
    out.append(("large autoconfigured", large))
    return out


def _refs(findings, code: str, pick) -> set[ChannelRef]:
    return {pick(f.refs) for f in findings if f.code == code}


@pytest.mark.parametrize("name, system", _systems(), ids=lambda v: v if isinstance(v, str)
                         else "")
def test_graph_marks_equal_check_findings(name, system):
    findings = check_system(system)
    states = compute_states(system)
    assert states.unmet_required == _refs(findings, "required-unmet", lambda r: r[1]), name
    assert states.unconnected_terminals == _refs(findings, "terminal-unconnected",
                                                 lambda r: r[0]), name
    conflicted = {lk.output for lk in states.conflict_links}
    assert conflicted == _refs(findings, "sole-access", lambda r: r[0]), name


def test_appendix_d_has_no_badge_when_checks_find_nothing():
    """Appendix D: an unlinked output's required input has no source. Nothing uses that
    output, so Checks report nothing, and the graph shows no badge and no red ring."""
    s = system_file.load_path(paths.systems_dir() / "appendix-d.json")
    assert [f for f in check_system(s) if f.code == "required-unmet"] == []
    states = compute_states(s)
    assert states.unmet_required == set()
    assert all(states.device_problems(k) == [] for k in s.devices)


def test_every_badge_ring_and_marked_link_explains_itself(qtbot):
    """On the graph: appendix D shows no badge; an unconnected terminal input, a required
    input a linked channel needs, and a link to an unplugged device each carry a tooltip
    with the finding and what to do, in plain words."""
    from pdcp_studio.app.documents.document import Document
    from pdcp_studio.app.graph.scene import BusScene

    appendix = BusScene(Document(system_file.load_path(paths.systems_dir() / "appendix-d.json")))
    assert all(not card.problems for card in appendix.cards.values())
    assert all(not port.toolTip() for c in appendix.cards.values() for port in c.ports.values())

    s = system_file.load_path(paths.systems_dir() / "transradial.json")
    plan_autoconfigure(s).apply(s)
    control = next(d for d in s.devices.values() if any(c.required_inputs
                                                        for c in d.channels.values()))
    needed = ChannelRef(*control.key, next(i for c in control.channels.values()
                                          for i in c.required_inputs))
    for link in [lk for lk in s.links if lk.input == needed]:
        s.remove_link(link)
    terminal = next(ref for ref, ch in s.channels() if ch.terminal and s.source_of(ref))
    feeding = next(lk for lk in s.links if lk.input == terminal)
    s.remove_link(feeding)
    unplugged = next(s.devices[lk.output.device] for lk in s.links
                     if not s.devices[lk.output.device].inputs())
    unplugged.present = False
    scene = BusScene(Document(s))
    findings = {f.code for f in check_system(s)}
    assert {"required-unmet", "terminal-unconnected", "missing-end"} <= findings
    ring = scene.cards[needed.device].ports[needed.index]
    assert ring.unmet and "must be connected" in ring.toolTip()
    assert "Autoconfigure" in ring.toolTip()
    card = scene.cards[terminal.device]
    assert card.problems and "nothing feeds it" in scene.tooltip_for(card, None)
    missing = next(item for lk, item in scene.link_items.items() if lk in
                   scene.states.missing_links)
    assert "Plug the device in, or remove the link" in missing.toolTip()
    for text in (ring.toolTip(), scene.tooltip_for(card, None), missing.toolTip()):
        assert "no_candidate" not in text and "input_taken" not in text
        assert "plan " not in text and "`" not in text


def test_checks_list_speaks_plainly_and_keeps_the_detail(qtbot):
    """Every finding the shipped systems produce reads without rule keys, CLI names or
    channel triples; the engineer's message and key stay in the tooltip."""
    import re
    from html import escape

    from pdcp_studio.app.words.finding_text import (
        _TEXTS,
        channel_words,
        finding_detail,
        plain_finding,
    )
    from pdcp_studio.engine import checks

    source = Path(checks.__file__)
    codes = set(re.findall(r'Finding\(Severity\.\w+, "([a-z-]+)"', source.read_text()))
    codes |= {"required-not-input", "desired-not-input", "required-unmet", "desired-unmet"}
    assert codes <= set(_TEXTS), codes - set(_TEXTS)
    seen = set()
    for name, system in _systems():
        for finding in checks.check_system(system):
            seen.add(finding.code)
            text = plain_finding(finding, system)
            assert "`" not in text and "plan " not in text, (name, text)
            assert finding.code not in text and not re.search(r"\d+/\d+/\d+#", text), text
            # each channel by its one name (its descriptor, else "channel N")
            assert all(channel_words(system, r) in text for r in finding.refs[:2]), text
            detail = finding_detail(finding)
            assert escape(finding.message) in detail and finding.code in detail
    assert {"terminal-unconnected", "missing-end"} <= seen
