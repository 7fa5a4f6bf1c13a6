"""A fitting-history entry in the words of its change's effect (``engine.effect``).

An entry written since the effect is recorded keeps it (``effect`` and ``next_power_on``,
``storage.history.entry_from_result``) with the names it was computed with, so it reads as
the confirmation read when it was written. The History list shows its first line(s), the
detail pane all of it; older entries have none and say so.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.words.effect_words import effect_tr

if TYPE_CHECKING:
    from pdcp_studio.engine.effect import Effect

_CTX = "HistoryWords"


def _tr(text: str) -> str:
    return translate(_CTX, text)


def entry_effect(entry: dict[str, Any]) -> Effect | None:
    """The effect an entry recorded (None: an older entry, or one that wrote nothing)."""
    from pdcp_studio.engine.effect import Effect

    doc = entry.get("effect")
    if not isinstance(doc, dict):
        return None
    power_on = entry.get("next_power_on")
    try:
        return Effect.from_json(doc, power_on if isinstance(power_on, dict) else None)
    except (KeyError, ValueError, TypeError):
        return None


def headline(effect: Effect) -> list[str]:
    """What the change did, the most telling first: links and parameters, then the policy,
    then the stored configuration (no lists, no reasons)."""
    from pdcp_studio.engine import effect as E

    out = [effect_tr(E.T_LINK_ADDED).format(link=effect.name(lk)) for lk in effect.links_added]
    out += [effect_tr(E.T_LINK_REMOVED).format(link=effect.name(lk))
            for lk in effect.links_removed]
    out += [effect.parameter_text(p, effect_tr) for p in effect.parameters]
    out += effect.policy_lines(effect_tr)[:1]
    if not out:
        out = effect.stored_lines(effect_tr)[:1] or [effect_tr(E.T_NOTHING)]
    return out


def entry_summary(entry: dict[str, Any], first: int = 1) -> str:
    """The History list's text of an entry: its effect's first ``first`` line(s) and how
    many more; an older entry's recorded action."""
    effect = entry_effect(entry)
    if effect is None:
        return str(entry.get("action") or "")
    lines = headline(effect)
    text = "; ".join(lines[:first])
    more = len(lines) - first
    return text + (" " + _tr("(and {0} more)").format(more) if more > 0 else "")


def entry_words(entry: dict[str, Any]) -> list[str] | None:
    """The entry's effect in words, then what the next power-on does (None: older entry)."""
    effect = entry_effect(entry)
    if effect is None:
        return None
    return [*effect.lines(effect_tr), "", *effect.power_on_lines(effect_tr)]


def predates() -> str:
    """Said of an entry recorded before effects were kept."""
    return _tr("This entry was recorded before PDCP Studio kept what a change does in "
               "words: it is shown as it was recorded.")
