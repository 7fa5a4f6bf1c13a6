"""Text from outside is shown, never executed: control characters and bidi overrides escaped.

A device name or descriptor comes from the bus or a file, a patient reference and an
operator name from whoever typed them, a file name from the file system: any of them can hold
ESC (a terminal runs ``ESC[2J`` and clears the screen), BEL, other C0/C1 controls, or a
bidirectional override (U+202E shows "exe.txt" for "txt.exe"). Every place that shows such a
string — the command line's output and the app's labels and tables — passes it through
:func:`shown`, which replaces each such character by a visible escape: ``\\x1b``, ``\\x07``,
``\\u202e``. Tabs are kept; a newline only where it is the output's own (``newlines=True``
for a whole listing), never inside one value. A lone surrogate (a file name that was not
UTF-8) is escaped too, so printing it cannot fail. Pure: every layer may import it.
"""

from __future__ import annotations

import re

# C0 controls but tab (and newline, kept or not by the caller), DEL, C1 controls, the
# Arabic letter mark, the left-to-right and right-to-left marks, the bidi embeddings and
# overrides U+202A–U+202E, the isolates U+2066–U+2069, and lone surrogates.
_UNSAFE = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u061c\u200e\u200f\u202a-\u202e"
                     "\u2066-\u2069\ud800-\udfff]")
_UNSAFE_OR_NEWLINE = re.compile(f"{_UNSAFE.pattern[:-1]}\n]")


def _escape(match: re.Match[str]) -> str:
    code = ord(match.group())
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def shown(text: str, *, newlines: bool = False) -> str:
    """``text`` with every control character and bidi control as a visible escape.

    ``newlines`` keeps ``\\n`` (a listing's own line breaks); otherwise it is escaped as
    ``\\x0a`` too, so one value stays on one line.
    """
    pattern = _UNSAFE if newlines else _UNSAFE_OR_NEWLINE
    return pattern.sub(_escape, text)


def is_safe(text: str) -> bool:
    """True when :func:`shown` leaves ``text`` as it is (newlines allowed)."""
    return _UNSAFE.search(text) is None
