"""The graph's words: card names, tooltips and the advice behind its warning marks.

The same findings the Checks list reports, said for one card, port or link, the
prosthetist's words first and the engineer's codes after them in grey.
"""

from __future__ import annotations

from collections.abc import Callable
from html import escape

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph.analysis import SystemStates
from pdcp_studio.app.i18n import translate
from pdcp_studio.model import profile as prof
from pdcp_studio.model.catalog import default_catalog
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.safe_text import shown
from pdcp_studio.model.system import Channel, Device, Link


def _tr(text: str) -> str:
    return translate("BusScene", text)


def _grey(text: str) -> str:
    return f"<span style='color:#6b7280'>{escape(text)}</span>"


class SceneWords:
    """Names and advice for ``doc``'s system as the scene shows it (``states``: the
    scene's current findings)."""

    def __init__(self, doc: Document, states: Callable[[], SystemStates]) -> None:
        self._doc = doc
        self._states = states
        self._names: dict[DeviceKey, str] | None = None
        self._channels: dict[tuple[ChannelRef, str, int], str] = {}

    def forget(self) -> None:
        """Name the parts again at the next label (a new system, a changed catalogue)."""
        self._names = None
        self._channels.clear()

    def channel_label(self, ref: ChannelRef) -> str:
        """A card row's text: the channel's one name without its part (``model/names.py``:
        descriptor, else profile name, else "channel N"); remembered per descriptor and
        profile, as a card repaints often."""
        from pdcp_studio.app.words.part_names import names

        ch = self._doc.system.channel(ref)
        key = (ref, ch.descriptor if ch else "", ch.profile if ch else 0)
        text = self._channels.get(key)
        if text is None:
            if len(self._channels) > 20000:
                self._channels.clear()
            profile = self._doc.profile_name(ch.profile) if ch is not None else ""
            text = self._channels[key] = names(self._doc.system).channel_only(ref, profile)
        return text

    def device_label(self, device: Device) -> str:
        """The device's own name, else its product from the device catalogue (looked up
        once per rebuild: finding the catalogue reads the user's folder)."""
        from pdcp_studio.app.words.part_names import part_name, part_names

        if self._names is None:
            self._names = part_names(self._doc.system)
        name = self._names.get(device.key)
        if name is None:  # a device just added: name the system again
            name = part_name(self._doc.system, device.key)
        return name

    def renamed_others(self, device: Device) -> list[DeviceKey]:
        """After ``device`` changed: the other parts whose names changed with it (two parts
        that now read alike, or no longer); the names are looked up afresh."""
        before, self._names = self._names, None
        if before is None or before.get(device.key) == self.device_label(device):
            return []
        names: dict[DeviceKey, str] = self._names or {}
        return [other for other, name in before.items()
                if other != device.key and names.get(other) != name]

    def profile_name(self, profile: int) -> str:
        return self._doc.profile_name(profile)

    def describe(self, ref: ChannelRef) -> str:
        """``Multi-grip hand, channel 1 (Power grip)``: a channel in words."""
        from pdcp_studio.app.words.plan_words import channel_words

        ch = self._doc.system.channel(ref)
        name = self.profile_name(ch.profile) if ch else ""
        return channel_words(self._doc.system, ref, "" if name.startswith("0x") else name)

    def tooltip_for(self, device: Device, row: Channel | None) -> str:
        """A card's (``row`` None) or a channel row's tooltip."""
        return self._card_tip(device) if row is None else self._row_tip(device, row)

    def _card_tip(self, d: Device) -> str:
        from pdcp_studio.app.words.part_names import numbers

        lines = [f"<b>{escape(self.device_label(d))}</b>"]
        entry = default_catalog().lookup(d.vid, d.pid)
        if entry is not None:
            lines.append(escape(" · ".join(x for x in (entry.product, entry.vendor) if x)))
        if not d.present:
            lines.append(f"<i>{escape(_tr('Missing from the bus'))}</i>")
        lines += [f"<span style='color:#b45309'>⚠ {p}</span>"
                  for p in self.problem_advice(d.key)]
        detail = numbers(d.key)
        if d.node_id is not None:
            detail += " · " + _tr("node ID {0}").format(d.node_id)
        lines.append(_grey(detail))
        return "<br>".join(lines)

    def _row_tip(self, d: Device, row: Channel) -> str:
        system = self._doc.system
        ref = d.ref(row.index)
        what = self._doc.tree.name_of(row.profile)
        head = (_tr("Input {n}") if row.is_input else _tr("Output {n}")).format(n=row.index)
        lines = [f"<b>{escape(head)}</b> — {escape(what)}"]
        if row.descriptor:
            lines.append(f"“{escape(shown(row.descriptor))}”")
        if row.is_input:
            src = system.source_of(ref)
            lines.append(escape(_tr("Fed by {0}").format(self.describe(src)) if src
                                else _tr("Nothing feeds it")))
        else:
            fed = system.inputs_fed_by(ref)
            lines.append(escape(_tr("Feeds {0}").format(
                "; ".join(self.describe(r) for r in fed)) if fed
                else _tr("Feeds nothing")))
        detail = _tr("profile {profile} · signal type {type}: {description}").format(
            profile=prof.fmt(row.profile), type=prof.fmt(row.type),
            description=row.ctype.describe())
        if row.is_input and row.terminal:
            detail += " · " + _tr("drives the part with profile {0}").format(
                prof.fmt(row.terminal_profile))
        lines.append(_grey(detail))
        advice = self.port_advice(ref)
        if advice:
            lines.append(f"<span style='color:#b91c1c'>⚠ {advice}</span>")
        return "<br>".join(lines)

    # -- findings in plain words (the same ones the Checks list reports) -----------
    def port_advice(self, ref: ChannelRef) -> str:
        """What is wrong with one input and what to do (empty: nothing)."""
        st = self._states()
        if ref in st.unmet_required:
            return _tr("Input {n} must be connected: a channel of this device that is "
                       "in use needs it. Connect a source to it, or let Autoconfigure "
                       "do it.").format(n=ref.index)
        if ref in st.unconnected_terminals:
            return _tr("Input {n} drives a part of the prosthesis but nothing feeds it, "
                       "so that part will not move. Connect a matching output, or let "
                       "Autoconfigure do it.").format(n=ref.index)
        return ""

    def problem_advice(self, key: DeviceKey) -> list[str]:
        """Every finding behind a card's warning badge, with what to do."""
        st = self._states()
        refs = sorted(r for r in st.unmet_required | st.unconnected_terminals
                      if r.device == key)
        out = [self.port_advice(r) for r in refs]
        if any(key in (lk.output.device, lk.input.device) for lk in st.conflict_links):
            out.append(_tr("One output feeds several inputs that each need it for "
                           "themselves. Keep one of these links and remove the others."))
        return out

    def link_advice(self, link: Link) -> str:
        """What a marked link means and what to do (empty: nothing marked)."""
        st = self._states()
        if link in st.conflict_links:
            return _tr("Conflict: this output also feeds another input that needs it "
                       "for itself. Keep one of these links and remove the others.")
        if link in st.missing_links:
            return _tr("This link carries no data: a device at one of its ends is not "
                       "on the bus. Plug the device in, or remove the link.")
        return ""
