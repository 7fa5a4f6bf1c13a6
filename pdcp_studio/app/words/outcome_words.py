"""The outcome of a change to the prosthesis in the user's words, for the status bar.

``TransactionResult.summary()`` (``bus/transaction.py``) is the CLI's English line with the
action's code ("config write: applied and verified (3 link(s); interlock: held 2
devices)"); the app says the same in the user's language, named by what the user asked for
(the title of the change), counts with plural forms and the step in words. The reason a
transaction stopped comes from the prosthesis's side and is quoted as it is.
"""

from __future__ import annotations

from typing import Any

from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.words.plural import count

_CTX = "TransactionOutcome"

#: A step of the change road (``bus.transaction.STEPS``) in words ("failed while …").
STEP_WORDS = {
    "preview": QT_TRANSLATE_NOOP("TransactionOutcome", "previewing"),
    "confirm": QT_TRANSLATE_NOOP("TransactionOutcome", "asking for confirmation"),
    "interlock": QT_TRANSLATE_NOOP("TransactionOutcome", "holding the parts still"),
    "write": QT_TRANSLATE_NOOP("TransactionOutcome", "writing"),
    "verify": QT_TRANSLATE_NOOP("TransactionOutcome", "reading back"),
    "restore": QT_TRANSLATE_NOOP("TransactionOutcome", "putting back"),
    "release": QT_TRANSLATE_NOOP("TransactionOutcome", "releasing the parts"),
    "record": QT_TRANSLATE_NOOP("TransactionOutcome", "recording in the fitting history"),
}


def _t(text: str) -> str:
    return translate(_CTX, text)


def step_words(step: str) -> str:
    """A step of the change road in words (an unknown one as it is)."""
    text = STEP_WORDS.get(step)
    return _t(text) if text else step


def outcome_words(result: Any, what: str) -> str:
    """One line for the status bar: how the change ``what`` (its title, in the user's
    language) ended — written and verified, nothing to change, not confirmed, undone or
    failed at a step with the reason."""
    status = str(getattr(result.status, "value", result.status))
    if status == "applied":
        text = _t("{what}: written and verified — {links}").format(
            what=what, links=count(_CTX, "%n link(s) on the prosthesis",
                                   len(result.links_after)))
        held = len(getattr(result, "held", ()) or ())
        if held:
            text += "; " + count(_CTX, "%n part(s) held still while writing", held)
        return text
    if status == "nothing":
        return _t("{what}: nothing to change on the prosthesis").format(what=what)
    if status == "declined":
        return _t("{what}: not confirmed, nothing written").format(what=what)
    step = step_words(str(result.step or ""))
    reason = str(result.reason or "")
    if status == "rolled_back":
        text = _t("{what}: stopped while {step}; what was written is undone")
    else:
        text = _t("{what}: failed while {step}")
    text = text.format(what=what, step=step)
    return f"{text}: {reason}" if reason else text
