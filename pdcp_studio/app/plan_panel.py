"""Plans, previewed: run a profile-layer operation, see it, then Apply or Discard.

The engine computes a :class:`~pdcp_studio.engine.plan.Plan` from a copy-free read of the
document's system; the panel lists its actions in order (op, both channels with profile
names, rule, reason, similarity and its breakdown) and what was tried and refused, while
the graph draws the links to add and to remove. Nothing changes until Apply, which makes
the plan one undo step — on a live bus a staged change, written to the prosthesis by Write
to prosthesis as one transaction. On a live bus plans take the arbitrator's stored
configuration as last read (re-read after every write), and a shown preview is computed
again whenever the bus changes, so it never describes a bus that is gone.
"""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import QT_TRANSLATE_NOOP, Qt, Signal
from PySide6.QtGui import QBrush
from PySide6.QtWidgets import (
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QPushButton,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app import commands
from pdcp_studio.app.document import Document
from pdcp_studio.app.graph import style
from pdcp_studio.app.i18n import translate
from pdcp_studio.errors import PdcpError
from pdcp_studio.model import profile as prof
from pdcp_studio.model.refs import ChannelRef

#: The operations offered, in menu order: (engine mode, menu text).
OPERATIONS = (
    ("autoconfigure", QT_TRANSLATE_NOOP("PlanPanel", "Autoconfigure")),
    ("replacements", QT_TRANSLATE_NOOP("PlanPanel", "Find replacements")),
    ("startup", QT_TRANSLATE_NOOP("PlanPanel", "Start-up")),
    ("enforce", QT_TRANSLATE_NOOP("PlanPanel", "Enforce sole access")),
)
LINK_ROLE = Qt.ItemDataRole.UserRole


class PlanPanel(QWidget):
    """The previewed plan of the document, with Apply and Discard."""

    statusMessage = Signal(str)
    #: A plan was applied: one undo step (on a live bus a staged change).
    applied = Signal(object)

    def __init__(self, doc: Document, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        box = QVBoxLayout(self)
        box.setContentsMargins(6, 6, 6, 6)
        buttons = QHBoxLayout()
        self.mode_buttons: dict[str, QPushButton] = {}
        for mode, text in OPERATIONS:
            b = QPushButton(translate("PlanPanel", text))
            b.setToolTip(
                self.tr("Preview what {v0} would change").format(v0=translate("PlanPanel", text))
            )
            b.clicked.connect(lambda _c=False, m=mode: self.preview(m))
            buttons.addWidget(b)
            self.mode_buttons[mode] = b
        buttons.addStretch(1)
        box.addLayout(buttons)
        self.summary = QLabel(self.tr("No plan previewed. Choose an operation to see what it would "
                              "change before anything changes."))
        self.summary.setWordWrap(True)
        box.addWidget(self.summary)
        self.actions_view = QTreeWidget()
        self.actions_view.setColumnCount(4)
        self.actions_view.setHeaderLabels(
            [self.tr("Action"), self.tr("Output → input"), self.tr("Rule"), self.tr("Similarity")]
        )
        self.actions_view.setUniformRowHeights(False)
        header = self.actions_view.header()
        header.setStretchLastSection(False)
        header.setSectionResizeMode(1, QHeaderView.ResizeMode.Stretch)
        for col in (0, 2, 3):
            header.setSectionResizeMode(col, QHeaderView.ResizeMode.ResizeToContents)
        self.actions_view.setAlternatingRowColors(True)
        self.actions_view.itemSelectionChanged.connect(self._on_row_selected)
        box.addWidget(self.actions_view, 1)
        row = QHBoxLayout()
        row.addStretch(1)
        self.discard_button = QPushButton(self.tr("Discard"))
        self.apply_button = QPushButton(self.tr("Apply"))
        self.apply_button.setDefault(True)
        self.discard_button.clicked.connect(self.discard)
        self.apply_button.clicked.connect(self.apply)
        row.addWidget(self.discard_button)
        row.addWidget(self.apply_button)
        box.addLayout(row)
        doc.previewChanged.connect(self._on_preview_changed)
        doc.busChanged.connect(self._on_bus_changed)
        self._update_buttons()

    # -- computing ------------------------------------------------------------------
    def configuration(self) -> Any:
        """The stored configuration plans use: the opened/read one, else None."""
        return getattr(self.doc, "config", None)

    def preview(self, mode: str) -> Any:
        """Compute ``mode``'s plan and show it (graph and list); returns it or None."""
        from pdcp_studio.engine import plan_for, plan_on_bus

        config = self.configuration()
        try:
            if self.doc.session is not None and config is not None:
                plan = plan_on_bus(mode, self.doc.system, config)  # the arbitrator's memory
            else:
                plan = plan_for(mode, self.doc.system, config)
        except (PdcpError, ValueError) as err:
            self.statusMessage.emit(
                f"{translate('PlanPanel', dict(OPERATIONS).get(mode, mode))}: {err}")
            self.summary.setText(
                self.tr("<span style='color:#b91c1c'>Cannot plan: {err}</span>").format(err=err)
            )
            return None
        self.doc.set_preview(plan)
        return plan

    def _on_bus_changed(self) -> None:
        """The bus is not what the preview was computed on: compute it again."""
        plan = self.plan
        if plan is not None:
            self.preview(plan.mode)

    @property
    def plan(self) -> Any:
        """The previewed plan (the document's; a new system clears it)."""
        return self.doc.preview_plan

    def _on_preview_changed(self, plan: Any) -> None:
        self._fill(plan)
        self._update_buttons()

    def _update_buttons(self) -> None:
        has = self.plan is not None
        self.discard_button.setEnabled(has)
        self.apply_button.setEnabled(has and bool(self.plan.actions))
        live = self.doc.session is not None
        self.apply_button.setText(self.tr("Stage for the prosthesis") if live else
                                  self.tr("Apply"))
        self.apply_button.setToolTip(self.tr(
            "Add the plan to the pending changes; Write to prosthesis writes them in one "
            "transaction") if live else self.tr("Apply the plan (one undo step)"))

    # -- showing --------------------------------------------------------------------
    def _ref_text(self, plan: Any, ref: ChannelRef) -> str:
        facts = plan.channels.get(ref)
        dev = self.doc.system.device(ref.device)
        who = dev.label if dev else str(ref.device)
        if facts is None:
            return f"{who} #{ref.index}"
        missing = "" if facts.present else " [missing]"
        return (f"{who} #{ref.index} {self.doc.profile_name(facts.profile)} "
                f"{prof.fmt(facts.profile)}{missing}")

    def _fill(self, plan: Any) -> None:
        view = self.actions_view
        view.clear()
        if plan is None:
            self.summary.setText(self.tr("No plan previewed. Choose an operation to see what it "
                                 "would change before anything changes."))
            return
        title = translate("PlanPanel", dict(OPERATIONS).get(plan.mode, plan.mode))
        text = self.tr("<b>{0}</b>: add {1}, remove {2} ({3} links before, {4} after)").format(
            title, len(plan.added), len(plan.removed), len(plan.links_before),
            len(plan.final_links))
        if plan.configuration_reason:
            text += f"<br>Configuration ({plan.configuration_source}): " \
                    f"{plan.configuration_reason}"
        if not plan.actions:
            text += "<br>Nothing to change."
        self.summary.setText(text)
        for n, a in enumerate(plan.actions, 1):
            add = a.op.value == "add"
            sign = "+ add" if add else "− remove"
            sim = str(a.similarity.total) if a.similarity is not None else ""
            item = QTreeWidgetItem([f"{n}. {'  ' * a.depth}{sign}",
                                    f"{self._ref_text(plan, a.link.output)} → "
                                    f"{self._ref_text(plan, a.link.input)}",
                                    a.rule.label, sim])
            colour = style.PREVIEW_ADD if add else style.PREVIEW_REMOVE
            item.setForeground(0, QBrush(colour))
            item.setData(0, LINK_ROLE, a.link)
            details = [f"why: {a.reason}"]
            if a.similarity is not None:
                details.append(f"similarity {a.similarity.describe()}")
            view.addTopLevelItem(item)
            for text in details:
                child = QTreeWidgetItem([text])
                child.setData(0, LINK_ROLE, a.link)
                child.setToolTip(0, text)
                item.addChild(child)
                child.setFirstColumnSpanned(True)
        if plan.rejections:
            head = QTreeWidgetItem(["Refused", f"{len(plan.rejections)} attempt(s) refused",
                                    "", ""])
            for r in plan.rejections:
                at = r.attempt
                if at.link is not None:
                    what = (f"{self._ref_text(plan, at.link.output)} → "
                            f"{self._ref_text(plan, at.link.input)}")
                elif at.channel is not None:
                    what = self._ref_text(plan, at.channel)
                else:
                    what = ""
                child = QTreeWidgetItem([r.kind.value, what, at.rule.label, ""])
                head.addChild(child)
                why = QTreeWidgetItem([f"why: {r.reason}"])
                child.addChild(why)
                why.setFirstColumnSpanned(True)
            view.addTopLevelItem(head)
        for note in plan.notes:
            view.addTopLevelItem(QTreeWidgetItem(["Note", note, "", ""]))
        view.expandAll()

    def _on_row_selected(self) -> None:
        items = self.actions_view.selectedItems()
        link = items[0].data(0, LINK_ROLE) if items else None
        if link is not None and self.doc.system.has_link(link):
            self.doc.select(link)

    # -- Apply / Discard --------------------------------------------------------------
    def discard(self) -> None:
        if self.plan is not None:
            self.doc.set_preview(None)
            self.statusMessage.emit(self.tr("Plan discarded: nothing changed"))

    def apply(self) -> bool:
        """One undo step; on a live bus a staged change (Write to prosthesis writes it)."""
        plan = self.plan
        if plan is None or not plan.actions:
            return False
        self.doc.set_preview(None)
        commands.push_plan(self.doc, plan)
        if self.doc.session is not None:
            self.statusMessage.emit(self.tr(
                "Staged {0}: {1} to add, {2} to remove — Write to prosthesis writes them "
                "(Undo unstages)").format(plan.mode, len(plan.added), len(plan.removed)))
        else:
            self.statusMessage.emit(
                self.tr(
                    "Applied {mode}: {n_added} added, {n_removed} removed (Undo reverts it)"
                ).format(mode=plan.mode, n_added=len(plan.added), n_removed=len(plan.removed))
            )
        self.applied.emit(plan)
        return True
