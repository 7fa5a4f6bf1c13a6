"""What one fitting-history entry says in the report: its action, its link counts, its
effect, the next power-on it predicted, the parts it replaced, and its codes.

The entry is a dict as ``History.entries`` returns it. The effect (``"effect"``) and the
prediction (``"next_power_on"``) are the change road's own words (contracts §2); an entry
recorded before they existed says so plainly instead of guessing. Link counts come from the
links the entry recorded before and after the change, so they are what the prosthesis did;
a swap also counts the links to the new part that the prosthesis had made on its own when
it was plugged in (they were not on the bus before the swap, and the write keeps them).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.words.part_names import part_name, twin_format
from pdcp_studio.app.words.plural import count
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Link, System

_CTX = "FittingReport"

#: Fitting-history actions and their words, by the action's first words.
_ACTIONS = (
    ("config write", QT_TRANSLATE_NOOP("FittingReport", "Stored set-up written")),
    ("config save", QT_TRANSLATE_NOOP("FittingReport", "Current links stored as the set-up")),
    ("policy autoconfigure on", QT_TRANSLATE_NOOP("FittingReport", "Autoconfigure turned on")),
    ("policy autoconfigure off", QT_TRANSLATE_NOOP("FittingReport", "Autoconfigure turned off")),
    ("add link", QT_TRANSLATE_NOOP("FittingReport", "Link added")),
    ("remove link", QT_TRANSLATE_NOOP("FittingReport", "Link removed")),
    ("set parameter", QT_TRANSLATE_NOOP("FittingReport", "Setting changed")),
    ("write to prosthesis",
     QT_TRANSLATE_NOOP("FittingReport", "Changes written to the prosthesis")),
    # The guided tasks' (app/wizards/logic.py ACTION_*).
    ("new fitting: connect", QT_TRANSLATE_NOOP("FittingReport", "New fitting: links written")),
    ("new fitting: store configuration",
     QT_TRANSLATE_NOOP("FittingReport", "New fitting: configuration stored")),
    ("replace a part", QT_TRANSLATE_NOOP("FittingReport", "Part replaced")),
    ("restore configuration from file",
     QT_TRANSLATE_NOOP("FittingReport", "Configuration restored from a file")),
)
_OUTCOMES = {
    "applied": QT_TRANSLATE_NOOP("FittingReport", "applied"),
    "rolled_back": QT_TRANSLATE_NOOP("FittingReport", "rolled back"),
    "failed": QT_TRANSLATE_NOOP("FittingReport", "failed"),
}


def _t(text: str) -> str:
    return translate(_CTX, text)


def action_words(action: str) -> str:
    """A fitting-history action (``config write``, ``apply autoconfigure``, ``policy
    autoconfigure off``…) in words for the report; unknown ones as they are."""
    from pdcp_studio.app.docks.plan_panel import OPERATIONS

    words = action.strip()
    low = words.lower()
    if low.startswith("undo "):
        return _t("Undone: {0}").format(action_words(words[5:]))
    if low.startswith("redo "):
        return _t("Done again: {0}").format(action_words(words[5:]))
    if low.startswith("history restore "):
        return _t("Fitting history entry {0} restored").format(words[16:].strip())
    if low.startswith("apply "):
        mode = low.split()[1] if len(low.split()) > 1 else ""
        known = dict(OPERATIONS).get(mode)
        title = translate("PlanPanel", known) if known else mode.replace("-", " ")
        return _t("{0} carried out").format(title)
    for prefix, text in _ACTIONS:
        if low.startswith(prefix):
            return _t(text)
    return words


def outcome_words(entry: dict[str, Any]) -> str:
    """How the change ended: applied (and verified), rolled back, failed…"""
    status = str((entry.get("outcome") or {}).get("status", ""))
    if status == "applied" and entry.get("verified"):
        return _t("applied, verified")
    return _t(_OUTCOMES[status]) if status in _OUTCOMES else status


def _key(doc: Any) -> DeviceKey | None:
    try:
        return DeviceKey(int(doc["vid"]), int(doc["pid"]), int(doc["serial"]))
    except (KeyError, TypeError, ValueError):
        return None


def _links(docs: Any) -> set[Link] | None:
    from pdcp_studio.bus.transaction import link_from_json

    if not isinstance(docs, list):
        return None
    out = set()
    for doc in docs:
        try:
            out.add(link_from_json(doc))
        except (KeyError, TypeError, ValueError):
            continue
    return out


def _ends(link: Link) -> tuple[DeviceKey, DeviceKey]:
    return link.output.device, link.input.device


def stored_links(entry: dict[str, Any]) -> set[Link] | None:
    """The links of the stored configuration the entry left (None: it did not record it)."""
    from pdcp_studio.storage import config_codec

    doc = entry.get("configuration_after")
    if not isinstance(doc, dict):
        return None
    try:
        collection = config_codec.from_json(doc)
    except (KeyError, TypeError, ValueError):
        return None
    return {Link(sl.output.ref, sl.input.ref) for c in collection.configurations
            for sl in c.links}


def _stored_before(earlier: Sequence[dict[str, Any]]) -> set[Link]:
    """The stored configuration before an entry: the last earlier entry's, if one says."""
    for e in reversed(earlier):
        links = stored_links(e)
        if links is not None:
            return links
    return set()


def replaced_pairs(entry: dict[str, Any], earlier: Sequence[dict[str, Any]] = (),
                   ) -> list[tuple[DeviceKey, DeviceKey]]:
    """(old part, new part) of a swap: the entry's ``replaced`` list when it has one; for a
    "replace a part" entry recorded before that field, each part linked before it (on the
    bus or in the stored configuration of an ``earlier`` entry) and by no link after it,
    with the part of the same product linked after it."""
    pairs = []
    for item in entry.get("replaced") or []:
        old, new = _key((item or {}).get("old")), _key((item or {}).get("new"))
        if old is not None and new is not None:
            pairs.append((old, new))
    if pairs or not str(entry.get("action", "")).lower().startswith("replace"):
        return pairs
    before, after = _links(entry.get("links_before")), _links(entry.get("links_after"))
    if before is None or after is None:
        return []
    linked_after = {k for lk in after for k in _ends(lk)}
    was = {k for lk in before | _stored_before(earlier) for k in _ends(lk)}
    for old in sorted(was - linked_after):
        same = sorted(k for k in linked_after
                      if (k.vid, k.pid) == (old.vid, old.pid) and k != old)
        if same:
            pairs.append((old, same[0]))
    return pairs


def link_changes(entry: dict[str, Any], earlier: Sequence[dict[str, Any]] = (),
                 ) -> tuple[set[Link], set[Link]] | None:
    """The links the change made and removed, from the links recorded before and after it;
    None when the entry has no ``links_after`` (it stopped before writing).

    A swap counts the links to the new part as made and the old part's links as removed,
    even when the prosthesis had already made or dropped them on its own between the
    plug-in and the write (then the old part's links are those it had on the bus, else in
    the stored configuration of an ``earlier`` entry)."""
    before, after = _links(entry.get("links_before")), _links(entry.get("links_after"))
    if before is None or after is None or entry.get("links_after") is None:
        return None
    added, removed = after - before, before - after
    pairs = replaced_pairs(entry, earlier)
    if pairs:
        new_parts = {new for _old, new in pairs}
        old_parts = {old for old, _new in pairs}
        added |= {lk for lk in after if set(_ends(lk)) & new_parts}
        old_links = {lk for lk in before if set(_ends(lk)) & old_parts}
        if not old_links:
            old_links = {lk for lk in _stored_before(earlier)
                         if set(_ends(lk)) & old_parts}
        removed |= old_links - after
    return added, removed


def change_words(entry: dict[str, Any], earlier: Sequence[dict[str, Any]] = (),
                 ) -> str:
    """``3 links added, 3 removed`` (and the parameters it set); ``earlier``: the entries
    before it, oldest first (a swap looks up the old part's stored links there)."""
    changes = link_changes(entry, earlier)
    plan = entry.get("plan") or {}
    if changes is not None:
        adds, removes = len(changes[0]), len(changes[1])
    else:  # not written: what it was to do
        actions = plan.get("actions") or []
        adds = sum(1 for a in actions if a.get("op") == "add")
        removes = sum(1 for a in actions if a.get("op") == "remove")
    what = _t("{added}, {removed}").format(added=count(_CTX, "%n link(s) added", adds),
                                           removed=count(_CTX, "%n removed", removes))
    params = len(plan.get("parameters") or [])
    if params:
        what += ", " + count(_CTX, "%n parameter(s)", params)
    return what


def _lines(doc: Any, key: str) -> list[str]:
    if not isinstance(doc, dict):
        return []
    lines = doc.get(key)
    if isinstance(lines, str):
        return [lines]
    return [str(x) for x in lines] if isinstance(lines, list) else []


def replaced_lines(system: System, entry: dict[str, Any],
                   earlier: Sequence[dict[str, Any]] = (),
                   ) -> list[str]:
    """``Multi-grip hand (serial 301) replaced by Multi-grip hand (serial 302)``."""
    out = []
    for old, new in replaced_pairs(entry, earlier):
        a, b = part_name(system, old), part_name(system, new)
        if a == b:
            a = twin_format().format(name=a, serial=old.serial)
            b = twin_format().format(name=b, serial=new.serial)
        out.append(_t("{old} replaced by {new}").format(old=a, new=b))
    return out


def _effect(entry: dict[str, Any]) -> Any:
    """The entry's recorded effect, read back (None when it has none or it does not read)."""
    from pdcp_studio.engine.effect import Effect

    doc, power_on = entry.get("effect"), entry.get("next_power_on")
    if not isinstance(doc, dict) or "links_before" not in doc:  # only words were kept
        return None
    try:
        return Effect.from_json(doc, power_on if isinstance(power_on, dict) else None)
    except (KeyError, TypeError, ValueError):
        return None


def effect_lines(entry: dict[str, Any]) -> list[str]:
    """What the change did, in words in the user's language (the change road's effect, read
    back from the entry); empty when not recorded."""
    from pdcp_studio.app.words.effect_words import effect_tr

    effect = _effect(entry)
    if effect is None:
        return _lines(entry.get("effect"), "text")
    return [ln.strip() for ln in effect.lines(effect_tr)]


def technical_lines(entry: dict[str, Any]) -> list[str]:
    """The effect's lines with codes, for the Technical detail section."""
    return _lines(entry.get("effect"), "technical")


def has_prediction(entry: dict[str, Any]) -> bool:
    return isinstance(entry.get("next_power_on"), dict)


def power_on_lines(entry: dict[str, Any]) -> list[str]:
    """What the next power-on does after this change, in words; when the entry predates the
    prediction, one line that says so."""
    if not has_prediction(entry):
        return [_t("This entry was recorded before PDCP Studio predicted the next "
                   "power-on, so the report cannot say what the prosthesis does at its next "
                   "start-up.")]
    doc = entry["next_power_on"]
    effect = _effect(entry)
    if effect is not None:
        from pdcp_studio.app.words.effect_words import effect_tr

        return [ln.strip() for ln in effect.power_on_lines(effect_tr)]
    lines = _lines(doc, "text")
    if lines:
        return lines
    added, removed = len(doc.get("links_added") or []), len(doc.get("links_removed") or [])
    if not added and not removed:
        return [_t("the prosthesis starts up with the links as they are now.")]
    return [_t("{added}, {removed}").format(added=count(_CTX, "%n link(s) added", added),
                                            removed=count(_CTX, "%n removed", removed))]
