"""``check_system``: what a prosthetist must know before trusting a system."""

from __future__ import annotations

from pdcp_studio.engine import Severity, check_system
from pdcp_studio.model import SourceInfo
from tests.engine.engine_builders import L, dev, inp, load, out, ref, system


def codes(s) -> list[tuple[str, str]]:
    return [(f.severity.value, f.code) for f in check_system(s)]


def test_the_appendix_d_rig_is_clean():
    assert check_system(load("appendix-d")) == []


def test_links_that_break_sole_access():
    s = system(dev(4, out(1, 0x1000)), dev(6, inp(1, 0x1000, sole=True), inp(2, 0x1000, sole=True)),
               links=[L(4, 1, 6, 1), L(4, 1, 6, 2)])
    (f,) = check_system(s)
    assert (f.severity, f.code) == (Severity.ERROR, "sole-access")
    assert f.refs == (ref(4, 1), ref(6, 1), ref(6, 2))
    assert "plan enforce" in f.message


def test_two_sources_on_one_input():
    s = system(dev(3, out(1, 0x1000)), dev(4, out(1, 0x1000)), dev(6, inp(1, 0x1000)),
               links=[L(3, 1, 6, 1), L(4, 1, 6, 1)])
    (f,) = check_system(s)
    assert (f.severity, f.code) == (Severity.ERROR, "two-sources")
    assert "2/2/3#1" in f.message and "2/2/4#1" in f.message


def test_required_inputs_left_unmet_and_desired_ones_noted():
    s = system(dev(5, inp(1, 0x2000), inp(2, 0x2100), out(3, 0x1000, req=[1], des=[2])),
               dev(6, inp(1, 0x1000)), links=[L(5, 3, 6, 1)])
    assert codes(s) == [("error", "required-unmet"), ("info", "desired-unmet")]
    f = check_system(s)[0]
    assert f.refs == (ref(5, 3), ref(5, 1))


def test_terminal_channels_left_unconnected_and_why():
    s = system(dev(4, out(1, 0x2000), out(2, 0x1100)),
               dev(6, inp(1, 0x1000, terminal=True), inp(2, 0x3000, terminal=True),
                   inp(3, 0x1100, terminal=True)))
    found = {f.refs[0]: f.message for f in check_system(s) if f.code == "terminal-unconnected"}
    assert "`plan autoconfigure` would link it to 2/2/4#2 (similarity 15)" in found[ref(6, 1)]
    assert "no present output shares its root component 0x3" in found[ref(6, 2)]
    assert "(similarity 23)" in found[ref(6, 3)]


def test_a_terminal_channel_whose_only_outputs_are_on_its_own_device():
    s = system(dev(6, out(1, 0x1000), inp(2, 0x1000, terminal=True)))
    (f,) = check_system(s)
    assert f.code == "terminal-unconnected"
    assert "only outputs sharing its root component are on its own device" in f.message


def test_a_terminal_channel_starved_by_sole_access():
    s = system(dev(4, out(1, 0x1000)),
               dev(6, inp(1, 0x1000, sole=True), inp(2, 0x1000, sole=True, terminal=True)),
               links=[L(4, 1, 6, 1)])
    (f,) = check_system(s)
    assert "already feeds a sole-access input (2/2/6#1)" in f.message


def test_links_with_missing_ends():
    s = system(dev(4, out(1, 0x1000), present=False), dev(6, inp(1, 0x1000)),
               links=[L(4, 1, 6, 1)])
    (f,) = check_system(s)
    assert (f.severity, f.code) == (Severity.WARNING, "missing-end")
    assert "2/2/4#1 is missing" in f.message


def test_required_and_desired_bits_naming_channels_that_are_not_inputs():
    # The loader refuses these; a system built in memory (or read from a bus) may have them.
    s = system(dev(5, inp(1, 0x2000), out(2, 0x1000, req=[3], des=[2])))
    assert codes(s) == [("error", "desired-not-input"), ("error", "required-not-input")]


def test_the_null_profile():
    s = system(dev(5, out(1, 0x0000)), dev(6, inp(1, 0x1000)))
    (f,) = check_system(s)
    assert (f.severity, f.code, f.refs) == (Severity.ERROR, "null-profile", (ref(5, 1),))


def test_self_links_and_malformed_profiles_are_warned_about():
    s = system(dev(5, out(1, 0x1010), inp(2, 0x1000)), links=[L(5, 1, 5, 2)])
    assert codes(s) == [("warning", "malformed-profile"), ("warning", "self-link")]


def test_findings_are_sorted_errors_first_and_serialise():
    s = system(dev(4, out(1, 0x0000)), dev(6, inp(1, 0x3000, terminal=True)))
    findings = check_system(s)
    assert [f.severity for f in findings] == [Severity.ERROR, Severity.WARNING]
    doc = findings[0].to_json()
    assert doc == {"severity": "error", "code": "null-profile",
                   "message": findings[0].message,
                   "refs": [{"vid": 2, "pid": 2, "serial": 4, "index": 1}]}


def test_an_input_whose_stored_source_disagrees_with_its_link_is_noted():
    s = system(dev(3, out(1, 0x1000)), dev(4, out(1, 0x1000)), dev(6, inp(1, 0x1000)),
               links=[L(3, 1, 6, 1)])
    s.channel(ref(6, 1)).source = SourceInfo(2, 2, 4, 1, 0x5000, 0x1000)
    (f,) = check_system(s)
    assert (f.severity, f.code) == (Severity.INFO, "source-field-stale")
    assert "stores source 2/2/4#1" in f.message
