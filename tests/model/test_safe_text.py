"""Text is shown, never executed (issue 28): control characters and bidi controls escaped."""

from __future__ import annotations

import pytest

from pdcp_studio.model.safe_text import is_safe, shown


@pytest.mark.parametrize(("raw", "escaped"), [
    ("Hand\x1b[2J", "Hand\\x1b[2J"),
    ("bell\x07", "bell\\x07"),
    ("txt.\u202eexe", "txt.\\u202eexe"),
    ("\u2066isolate\u2069", "\\u2066isolate\\u2069"),
    ("\u202a\u202b\u202c\u202d", "\\u202a\\u202b\\u202c\\u202d"),
    ("c1\x9b31m", "c1\\x9b31m"),
    ("del\x7f", "del\\x7f"),
    ("cr\roverwrite", "cr\\x0doverwrite"),
    ("nul\x00", "nul\\x00"),
    ("not utf-8 \udcff", "not utf-8 \\udcff"),
    ("tab\tkept", "tab\tkept"),
    ("Hand · Greifer “ä” 手", "Hand · Greifer “ä” 手"),
    ("C:\\Users\\x.pdcfg", "C:\\Users\\x.pdcfg"),
])
def test_controls_and_bidi_overrides_become_visible_escapes(raw, escaped):
    assert shown(raw) == escaped
    assert is_safe(shown(raw))


def test_a_newline_is_kept_only_where_it_is_the_outputs_own():
    assert shown("one\ntwo") == "one\\x0atwo"
    assert shown("one\ntwo\x1b", newlines=True) == "one\ntwo\\x1b"
