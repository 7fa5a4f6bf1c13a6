"""``parameter_words``: a staged edit or an undo step said as the change's effect says it —
the same words as the confirmation, one value at a time, no codes."""

from __future__ import annotations

import re

from pdcp_studio.engine.effect import effect_of, parameter_words
from pdcp_studio.model import param_names
from pdcp_studio.model.refs import DeviceKey
from tests.engine.test_effect import Write, linked

HAND = DeviceKey(2641, 769, 301)
CODES = re.compile(r"0x[0-9A-Fa-f]+|\b\d+/\d+/\d+\b|[0-9a-f]{8,}")


def _write(system, index, **values):
    ch = system.devices[HAND].channels[index]
    [(param, data)] = param_names.writes_for(ch, values)
    return Write(HAND, param, index, data)


def test_the_words_of_a_write_are_the_effects_own():
    system = linked()
    write = _write(system, 1, type="0x9700")
    words = parameter_words(system, [write])
    assert words == [line for line in effect_of(system, links_after=system.links,
                                                parameters=[write]).lines()
                     if "control mode" in line]
    assert words[0].endswith("control mode position → velocity")
    assert not CODES.search(words[0])


def test_only_one_named_value_and_a_translation():
    system = linked()
    both = _write(system, 2, type="0x9700", profile="0x0000")
    said = parameter_words(system, [both])
    assert len(said) == 2  # the type and the profile share one parameter
    only = parameter_words(system, [both], only="type")
    assert len(only) == 1 and "control mode" in only[0]
    german = {"control mode": "Regelungsart", "position": "Position"}
    said = parameter_words(system, [both], tr=lambda t: german.get(t, t), only="type")
    assert "Regelungsart Position → " in said[0]
    assert parameter_words(system, [_write(system, 1, type="0x9300")]) == []  # no change
