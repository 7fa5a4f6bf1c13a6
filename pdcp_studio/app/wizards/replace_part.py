"""Replace a part: what is missing → plug the new part → the replacement plan explained with
its similarity → write → verify → report.

The missing parts are the absent devices that links on the bus or in the stored
configuration still reach. The page after waits for the bus to report a new part (on the
simulated prosthesis: the Simulator panel's Plug in). The plan is find replacements
(listing 4.6) as if the new part had just been plugged in — the arbitrator may already have
linked it on its own; the plan says why each link is made and how similar the new channel
is. The write is one transaction: the links, and the stored configuration naming the new
part, so the next start-up needs no replacement.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import QPushButton

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.wizards import logic, words
from pdcp_studio.app.wizards.change_pages import ChangePage, WritePage
from pdcp_studio.app.wizards.result_pages import ReportPage, VerifyPage
from pdcp_studio.app.wizards.runner import Look, alive
from pdcp_studio.app.wizards.task_wizard import Page, TaskWizard, bullets
from pdcp_studio.model.refs import DeviceKey

if TYPE_CHECKING:
    from pdcp_studio.app.docks.sim_panel import SimPanel
    from pdcp_studio.app.live.session_bridge import SessionBridge
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.model.system import Link, System


def _t(text: str) -> str:
    return translate("Wizards", text)


class _FollowsBus(Page):
    """A page that looks at the prosthesis again whenever a part joins or leaves."""

    #: Look again when the Simulator panel's list changes too (the page's words name it).
    follows_sim_list = False

    def __init__(self, title: str, subtitle: str) -> None:
        super().__init__(title, subtitle)
        self._again = QTimer(self)
        self._again.setSingleShot(True)
        self._again.setInterval(250)
        self._again.timeout.connect(self._look_if_shown)
        self._bridge: SessionBridge | None = None
        self.sim_button = QPushButton(_t("Show the Simulator panel"))
        self.sim_button.clicked.connect(self.show_simulator)
        self.box.addWidget(self.sim_button, 0, Qt.AlignmentFlag.AlignLeft)

    def follow(self) -> None:
        bridge = self.task.main.live.bridge
        if bridge is not None and bridge is not self._bridge:
            self._bridge = bridge
            bridge.deviceJoined.connect(alive(self, self._changed))
            bridge.deviceLeft.connect(alive(self, self._changed))
            if bridge.is_sim and self.follows_sim_list:
                bridge.simDevices.connect(alive(self, self._changed))
        self.sim_button.setVisible(bridge is not None and bridge.is_sim)

    def _changed(self, _key: object = None) -> None:
        if self.wizard() is not None and self.task.currentPage() is self:
            self._again.start()

    def _look_if_shown(self) -> None:
        # Not once the user went on: a late look would change what the next page plans.
        if self.wizard() is not None and self.task.currentPage() is self:
            self.look_again()

    def look_again(self) -> None:
        raise NotImplementedError

    def show_simulator(self) -> None:
        dock = self.task.main._leaf_docks.get("sim")
        if dock is not None:
            dock.show()
            dock.raise_()
            self.task.keep_clear_of_simulator()

    def sim_panel(self) -> SimPanel | None:
        """The window's Simulator panel (a simulated prosthesis), else None."""
        from pdcp_studio.app.docks.sim_panel import SimPanel

        dock = self.task.main._leaf_docks.get("sim")
        panel = dock.widget() if dock is not None else None
        return panel if isinstance(panel, SimPanel) else None

    def sim_offers(self) -> list[str]:
        """The names the Simulator panel gives the parts it can plug in (unplugged, and not
        the missing part itself); empty without the panel."""
        panel = self.sim_panel()
        if panel is None:
            return []
        missing = {m.key for m in self.task.missing}
        return [name for key, name in panel.unplugged() if key not in missing]


class MissingPage(_FollowsBus):
    """Which parts the prosthesis expects and does not find."""

    follows_sim_list = True

    def __init__(self) -> None:
        super().__init__(_t("What is missing"),
                         _t("PDCP Studio compares the parts on the bus with the parts the "
                            "prosthesis is linked and configured for."))

    def initializePage(self) -> None:
        self.follow()
        self.look_again()

    def look_again(self) -> None:
        self.read_bus(self._show)

    def _show(self, got: Look) -> None:
        task = self.task
        system = got.system
        missing = logic.missing_parts(system, got.stored)
        task.missing = missing
        task.known = set(system.devices)
        if missing:
            lines = [_t("{0} is not on the bus; {1}").format(
                words.part_words(system, m.key),
                words.count("%n link(s) led to it.", m.links)) for m in missing]
            self.view.setHtml(bullets(lines, _t("Missing:")))
            self.idle(_t("Next: plug the new part in."))
        else:
            lines = [_t("Every part the prosthesis expects is on the bus.")]
            if self.sim_button.isVisible():
                lines.append(_t("To try a swap on this simulated prosthesis: in the Simulator "
                                "panel choose {0} and press Unplug. This page follows the "
                                "bus and shows the missing part.").format(
                                    self._swappable(system)))
            self.view.setHtml(bullets(lines, _t("Nothing is missing.")))
        self.set_ready(bool(missing))


    def _swappable(self, system: System) -> str:
        """The part on the bus with a spare of its product waiting in the Simulator panel
        (on sim:transradial, the hand), by its name; else "a part"."""
        panel = self.sim_panel()
        spares = {(k.vid, k.pid) for k, _n in panel.unplugged()} if panel is not None \
            else set()
        for key, dev in sorted(system.devices.items()):
            if dev.present and (key.vid, key.pid) in spares:
                return words.part_words(system, key)
        return _t("a part")


class PlugPage(_FollowsBus):
    """Wait for the new part to appear on the bus and say what was seen."""

    def __init__(self) -> None:
        super().__init__(_t("Plug the new part in"),
                         _t("Plug the new part in now. This page waits for it to appear on "
                            "the bus."))
        self.known: set[DeviceKey] = set()  # the parts that are not new

    def initializePage(self) -> None:
        task = self.task
        stored = {k for lk in logic.stored_links(task.stored)
                  for k in (lk.output.device, lk.input.device)}
        # A part the stored configuration does not name is new; without one, a part not
        # seen on the page before.
        self.known = stored if stored else set(task.known)
        task.new_parts = []
        self.follow()
        self.look_again()

    def look_again(self) -> None:
        self.read_bus(self._show, _t("Waiting for the new part…"))

    def _show(self, got: Look) -> None:
        task = self.task
        system = got.system
        new = logic.new_parts(system, self.known)
        task.new_parts = new
        back = [m for m in task.missing if m.key in system.devices
                and system.devices[m.key].present]
        lines = [_t("New on the bus: {0}.").format(words.part_words(system, k))
                 for k in new]
        lines += [_t("{0} is back on the bus: it needs no replacement.").format(
            words.part_words(system, m.key)) for m in back]
        if self.sim_button.isVisible() and not new:
            offers = self.sim_offers()
            spare = (_t("{0} or {1}").format(", ".join(offers[:-1]), offers[-1])
                     if len(offers) > 1 else offers[0] if offers else _t("the new part"))
            lines.append(_t("On this simulated prosthesis: in the Simulator panel choose "
                            "{0} and press Plug in.").format(spare))
        self.view.setHtml(bullets(lines))
        if new:
            self.idle(_t("The new part is on the bus. Next shows how it will be linked."))
        else:
            self.working(_t("Waiting for the new part…"))
        self.set_ready(bool(new))


def replace_step(task: TaskWizard, system: System,
                 stored: ConfigCollection | None) -> tuple[list[str], Change, list[Link]]:
    """Find replacements for the missing part's channels among the new part's."""
    new = list(task.new_parts)
    plan = logic.replacement_plan(system, stored, new)
    change = logic.replacement_change(system, plan)
    lines = [_t("The new part: {0}.").format(", ".join(words.part_words(system, k)
                                                        for k in new))]
    lines += words.plan_lines(system, plan)
    already = [a for a in plan.added if a.link in set(system.links)]
    if already:
        lines.append(words.count("The prosthesis made %n link(s) of these on its own when the "
                                 "part was plugged in; the write makes them part of the "
                                 "fitting.", len(already)))
    lines.append(_t("The stored configuration will name the new part, so the next start-up "
                    "links it directly."))
    return lines, change, plan.final_links


class ReplacePartWizard(TaskWizard):
    """A part swapped, step by step."""

    def __init__(self, window: Any) -> None:
        super().__init__(window, _t("Replace a part"))
        self.missing_page = MissingPage()
        self.plug_page = PlugPage()
        self.plan_page = ChangePage(
            _t("Replacement plan"),
            _t("How the new part takes the missing part's place: each link with why it is "
               "made and how alike the new channel is. Nothing is written yet."),
            replace_step)
        self.write_page = WritePage(_t("Write"),
                                    _t("The replacement is written to the prosthesis."),
                                    _t("Write to prosthesis"))
        self.verify_page = VerifyPage()
        self.report_page = ReportPage()
        for page in (self.missing_page, self.plug_page, self.plan_page, self.write_page,
                     self.verify_page, self.report_page):
            self.addPage(page)
