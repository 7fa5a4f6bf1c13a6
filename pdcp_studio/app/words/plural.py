"""Counts in words: ``1 link``, ``2 links`` — Qt's plural forms (``%n`` with a count), and
English read right without an English translation file.

Qt picks a translation's plural form by the count (``translate(ctx, "%n link(s)", None,
n)``; the German file has both forms); with no translation (English, the source language)
Qt only puts the number in, so the ``(s)`` of the source is resolved here: dropped for
one, an ``s`` for any other count.
"""

from __future__ import annotations

import re

from pdcp_studio.app.i18n import translate

_ENGLISH_PLURAL = re.compile(r"\((s|es)\)")


def english(text: str, n: int) -> str:
    """``%n link(s)`` → ``1 link`` / ``2 links`` (the ``(s)`` markers resolved)."""
    text = text.replace("%n", str(n))
    return _ENGLISH_PLURAL.sub("" if n == 1 else r"\1", text)


def count(context: str, text: str, n: int) -> str:
    """``text`` (with ``%n`` and ``(s)``) for ``n`` things, in the user's language."""
    shown = translate(context, text, None, n)
    return english(shown, n) if "(s)" in shown or "(es)" in shown else shown
