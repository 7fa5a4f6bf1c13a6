"""The stored-configuration window's words: channels by their parts' names, channel types
and profiles in words, the configuration checks and the fit in plain words with what to do
(the engine's own words stay in the tooltips).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from PySide6.QtCore import QCoreApplication

from pdcp_studio.engine.config_checks import ConfigFinding
from pdcp_studio.model import profile as prof
from pdcp_studio.model.configuration import StoredChannel
from pdcp_studio.model.names import Names
from pdcp_studio.model.profile_tree import ProfileNames
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import System


def _tr(text: str) -> str:
    return QCoreApplication.translate("ConfigWindow", text)


class ConfigWords:
    """Words for one window: parts and channels named by ``names()`` (the one naming),
    profiles by ``tree()`` (both change with the prosthesis fitted to)."""

    def __init__(self, names: Callable[[], Names], tree: Callable[[], ProfileNames]) -> None:
        self._names = names
        self._tree = tree

    def channel_text(self, ch: StoredChannel) -> str:
        return self.ref_words(ch.ref)

    def ref_words(self, ref: ChannelRef) -> str:
        """``Multi-grip hand, Power grip``: the one name (``model/names.py``); "channel N"
        only where no descriptor is known (a stored configuration names VID, PID, serial
        and index, nothing more)."""
        return self._names().channel(ref)

    def profile_text(self, profile: int) -> str:
        """What a channel carries, by the profile tree's names (the code is the tooltip)."""
        if profile == prof.NULL_PROFILE:
            return _tr("not stored")
        tree = self._tree()
        if tree.node(profile) is None:
            return _tr("not named in the profile tree")
        return tree.name_of(profile)

    @staticmethod
    def type_text(value: int) -> str:
        """A channel type in words: its data type, size and control mode."""
        from pdcp_studio.model.channel_type import ChannelType

        try:
            t = ChannelType(value)
        except ValueError:
            return _tr("unknown form")
        kind = (_tr("signed number"), _tr("number"), _tr("decimal number"),
                _tr("on/off"))[int(t.data_type)]
        mode = (_tr("position"), _tr("speed"), _tr("acceleration"),
                _tr("other"))[int(t.control_mode)]
        return _tr("{kind} ({bits} bits), {mode}").format(kind=kind, bits=t.bits, mode=mode)

    def finding_words(self, f: ConfigFinding) -> str:
        """A configuration check in plain words with what to do (the engine's as tooltip)."""
        names = [self.ref_words(r) for r in f.refs]
        links = ", ".join(str(p + 1) for p in f.links)
        a = names[0] if names else ""
        b = names[1] if len(names) > 1 else ""
        text = {
            "same-device": _tr("Link {links} joins {a} to its own device. Remove it."),
            "duplicate-link": _tr("Links {links} store the same link {a} → {b}; it is made "
                                  "once. Remove the extra ones."),
            "two-sources": _tr("{a} is given more than one source (links {links}); only "
                               "the first would be made. Keep one of them."),
            "both-directions": _tr("{a} is stored as an output and as an input (links "
                                   "{links}); a channel is one or the other. Correct the "
                                   "wrong link."),
            "sole-access": _tr("{a} feeds several inputs that each need it for themselves "
                               "(links {links}). Keep one of these links."),
            "inconsistent-records": _tr("{a} is stored with different descriptions in "
                                        "links {links}. Edit the channel so they agree."),
            "profile-misfit": _tr("Link {links}: {a} and {b} carry different kinds of "
                                  "signal; {b} may not understand what it is sent."),
            "type-differs": _tr("Link {links}: {a} and {b} carry the same kind of signal in "
                                "different forms; the input adapts to the output."),
        }.get(f.code)
        if text is None:
            return f.message
        return text.format(links=links, a=a, b=b)

    @staticmethod
    def plan_step_words(a: Any, system: System) -> str:
        from pdcp_studio.app.words import plan_words as W

        verb = _tr("Add") if a.op.value == "add" else _tr("Remove")
        return (f"{verb} {W.link_words(system, a.link.output, a.link.input)}: "
                f"{W.rule_words(a.rule)}")

    @staticmethod
    def link_fit_words(lf: Any, system: System, plan: Any) -> str:
        """What happens to one stored link on this prosthesis, in words (``plan``: the
        fit's plan, None without a fit)."""
        from pdcp_studio.app.words import plan_words as W
        from pdcp_studio.engine.config_fit import MISSING, PRESENT

        if lf.whole:
            return _tr("both ends are on the prosthesis: made as stored")
        parts = []
        for end, state in ((_tr("the output"), lf.output), (_tr("the input"), lf.input)):
            if state == MISSING:
                parts.append(_tr("{end} is missing").format(end=end))
            elif state != PRESENT:
                parts.append(_tr("{end} has the other direction on the prosthesis").format(
                    end=end))
        adds = [a for a in lf.actions if a.op.value == "add"]
        if adds:
            made = "; ".join(_tr("replaced by {link} ({similar})").format(
                link=W.link_words(system, a.link.output, a.link.input),
                similar=W.similarity_words(a, plan) if plan is not None else "")
                for a in adds)
            return f"{', '.join(parts)}: {made}"
        return _tr("{parts}: no replacement found, the link is not made").format(
            parts=", ".join(parts))
