"""New fitting: connect → scan → checks → autoconfigure preview → write → store the
configuration → report.

The plan is autoconfigure's on the prosthesis as it is (links a start-up already made stay);
the write and the store are two transactions of the change road, each recorded in the
fitting history, so the report lists both.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.wizards import logic, words
from pdcp_studio.app.wizards.change_pages import ChangePage, WritePage
from pdcp_studio.app.wizards.connect_page import ConnectPage
from pdcp_studio.app.wizards.result_pages import ReportPage
from pdcp_studio.app.wizards.scan_pages import ChecksPage, ScanPage
from pdcp_studio.app.wizards.task_wizard import TaskWizard

if TYPE_CHECKING:
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.model.system import Link, System

_CTX = "Wizards"


def _t(text: str) -> str:
    return translate(_CTX, text)


def plan_step(task: TaskWizard, system: System,
              _stored: ConfigCollection | None) -> tuple[list[str], Change, list[Link]]:
    """Autoconfigure on the prosthesis as it is, explained link by link."""
    plan = logic.autoconfigure_plan(system)
    change = logic.change_to(system.links, plan, logic.ACTION_FITTING)
    lines = [_t("The links to make, each with why:") if plan.actions else
             _t("Every part is already linked as autoconfigure would link it.")]
    lines += words.plan_lines(system, plan)
    kept = len(set(system.links) & set(plan.final_links))
    if kept:
        lines.append(words.count("Already on the prosthesis and kept as they are: %n link(s).",
                                 kept))
    return lines, change, plan.final_links


def store_step(task: TaskWizard, system: System,
               _stored: ConfigCollection | None) -> tuple[list[str], Change, list[Link]]:
    """The links on the prosthesis now, stored as its configuration."""
    change = logic.store_change(system)
    lines = [_t("The prosthesis keeps its links in its stored configuration: after a "
                "restart, or when a part is replaced, it links the parts as stored.")]
    lines += [_t("The links were written and verified (fitting history entry {0}).").format(
        r.history_id) for r in task.results if r.history_id]
    return lines, change, list(system.links)


class NewFittingWizard(TaskWizard):
    """A first fitting of a prosthesis, step by step."""

    def __init__(self, window: Any) -> None:
        super().__init__(window, _t("New fitting"))
        self.connect_page = ConnectPage()
        self.scan_page = ScanPage()
        self.checks_page = ChecksPage()
        self.plan_page = ChangePage(
            _t("Autoconfigure"),
            _t("PDCP Studio proposes the links between the parts: each one below with why "
               "it is made. Nothing is written yet."), plan_step)
        self.write_page = WritePage(
            _t("Write"), _t("The proposed links are written to the prosthesis."),
            _t("Write to prosthesis"))
        self.store_page = WritePage(
            _t("Store the configuration"),
            _t("The links are stored in the prosthesis, so that it keeps them."),
            _t("Store configuration"), build=store_step)
        self.report_page = ReportPage()
        for page in (self.connect_page, self.scan_page, self.checks_page, self.plan_page,
                     self.write_page, self.store_page, self.report_page):
            self.addPage(page)
