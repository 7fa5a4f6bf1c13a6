"""Plans, previewed: run a profile-layer operation, see it, then Apply or Discard.

The engine computes a :class:`~pdcp_studio.engine.plan.Plan` from a copy-free read of the
document's system; the panel lists its actions in order in plain words (add or remove,
which link by device and channel names, why, how similar — rows wrap, so an ordinary plan
reads without scrolling sideways) and what was tried and refused, while the graph draws the
links to add and to remove. The engineer's detail of the selected row (the engine's reason,
profile codes, the similarity score's breakdown) is in the detail pane beside the list.
Nothing changes until Apply, which makes the plan one undo step — on a live bus a staged
change, written to the prosthesis by Write to prosthesis as one transaction. On a live bus
plans take the arbitrator's stored configuration as last read (re-read after every write),
and a shown preview is computed again whenever the bus changes, so it never describes a bus
that is gone.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from PySide6.QtCore import QEvent, QObject, Qt, Signal
from PySide6.QtGui import QBrush, QColor, QResizeEvent
from PySide6.QtWidgets import (
    QAbstractItemView,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QPushButton,
    QSplitter,
    QTableWidget,
    QTableWidgetItem,
    QTextBrowser,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.documents import commands
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph import style
from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.words import plan_words as W
from pdcp_studio.errors import PdcpError
from pdcp_studio.model import profile as prof
from pdcp_studio.model.refs import ChannelRef

if TYPE_CHECKING:
    from pdcp_studio.engine.plan import Plan
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.model.system import Link

#: The operations offered, in menu order: (engine mode, menu text).
OPERATIONS = (
    ("autoconfigure", QT_TRANSLATE_NOOP("PlanPanel", "Autoconfigure")),
    ("replacements", QT_TRANSLATE_NOOP("PlanPanel", "Find replacements")),
    ("startup", QT_TRANSLATE_NOOP("PlanPanel", "Start-up")),
    ("enforce", QT_TRANSLATE_NOOP("PlanPanel", "Enforce sole access")),
)
LINK_ROLE = Qt.ItemDataRole.UserRole
DETAIL_ROLE = Qt.ItemDataRole.UserRole + 1
COL_N, COL_CHANGE, COL_LINK, COL_WHY, COL_SIMILAR = range(5)


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
        self.actions_view = QTableWidget(0, 5)
        self.actions_view.setHorizontalHeaderLabels(
            ["", self.tr("Change"), self.tr("Link"), self.tr("Why"), self.tr("How similar")])
        view = self.actions_view
        view.verticalHeader().hide()
        view.setWordWrap(True)  # long names wrap onto more lines: never cut, no sideways scroll
        view.setTextElideMode(Qt.TextElideMode.ElideNone)
        view.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        view.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        view.setSelectionMode(QAbstractItemView.SelectionMode.SingleSelection)
        view.setAlternatingRowColors(True)
        view.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        view.verticalHeader().setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
        header = view.horizontalHeader()
        for col in (COL_N, COL_CHANGE):
            header.setSectionResizeMode(col, QHeaderView.ResizeMode.ResizeToContents)
        header.setSectionResizeMode(COL_LINK, QHeaderView.ResizeMode.Stretch)
        for col in (COL_WHY, COL_SIMILAR):  # sized with the table: see _share_width
            header.setSectionResizeMode(col, QHeaderView.ResizeMode.Interactive)
        view.viewport().installEventFilter(self)
        view.itemSelectionChanged.connect(self._on_row_selected)
        self.detail = QTextBrowser()
        self.detail.setMinimumWidth(160)
        self._detail_hint()
        split = QSplitter(Qt.Orientation.Horizontal)
        split.addWidget(view)
        split.addWidget(self.detail)
        split.setStretchFactor(0, 5)
        split.setStretchFactor(1, 1)
        split.setSizes([800, 200])
        split.setChildrenCollapsible(False)
        box.addWidget(split, 1)
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

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:
        if isinstance(event, QResizeEvent) and watched is self.actions_view.viewport():
            self._share_width(event.size().width())
        return super().eventFilter(watched, event)

    def _share_width(self, width: int) -> None:
        """Why and How similar get a fifth of the width each; the link (the longest text)
        the rest, so an ordinary plan's rows wrap onto two lines at most."""
        for col in (COL_WHY, COL_SIMILAR):
            self.actions_view.setColumnWidth(col, max(110, width // 5))

    # -- computing ------------------------------------------------------------------
    def configuration(self) -> ConfigCollection | None:
        """The stored configuration plans use: the opened/read one, else None."""
        config: ConfigCollection | None = self.doc.config
        return config

    def preview(self, mode: str) -> Plan | None:
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
    def plan(self) -> Plan | None:
        """The previewed plan (the document's; a new system clears it)."""
        plan: Plan | None = self.doc.preview_plan
        return plan

    def _on_preview_changed(self, plan: Plan | None) -> None:
        self._fill(plan)
        self._update_buttons()

    def _update_buttons(self) -> None:
        plan = self.plan
        self.discard_button.setEnabled(plan is not None)
        self.apply_button.setEnabled(plan is not None and bool(plan.actions))
        live = self.doc.session is not None
        self.apply_button.setText(self.tr("Stage for the prosthesis") if live else
                                  self.tr("Apply"))
        self.apply_button.setToolTip(self.tr(
            "Add the plan to the pending changes; Write to prosthesis writes them in one "
            "transaction") if live else self.tr("Apply the plan (one undo step)"))

    # -- showing --------------------------------------------------------------------
    def _ref_text(self, plan: Plan, ref: ChannelRef) -> str:
        """The engineer's form of a channel: device, index, profile name and code."""
        facts = plan.channels.get(ref)
        who = f"{W.device_words(self.doc.system, ref.device)} ({ref.device})"
        if facts is None:
            return f"{who} #{ref.index}"
        missing = "" if facts.present else " [missing]"
        return (f"{who} #{ref.index} {self.doc.profile_name(facts.profile)} "
                f"{prof.fmt(facts.profile)}{missing}")

    def _words(self, plan: Plan, ref: ChannelRef) -> str:
        """A channel in plain words: device, channel, what it carries; (missing) if gone."""
        facts = plan.channels.get(ref)
        name = self.doc.profile_name(facts.profile) if facts is not None else ""
        if name.startswith("0x"):
            name = ""
        text = W.channel_words(self.doc.system, ref, name)
        if facts is not None and not facts.present:
            text += self.tr(" (missing)")
        return text

    def _add_row(self, cells: list[str], link: Link | None, detail: str,
                 colour: QColor | None = None) -> None:
        view = self.actions_view
        row = view.rowCount()
        view.insertRow(row)
        for col, text in enumerate(cells):
            item = QTableWidgetItem(text)
            item.setTextAlignment(Qt.AlignmentFlag.AlignTop | Qt.AlignmentFlag.AlignLeft)
            item.setData(LINK_ROLE, link)
            item.setData(DETAIL_ROLE, detail)
            item.setToolTip(detail)
            if colour is not None and col == COL_CHANGE:
                item.setForeground(QBrush(colour))
            view.setItem(row, col, item)

    def _detail_hint(self) -> None:
        """What the detail pane is for, wrapped to its width (a placeholder is one line,
        cut off in a narrow pane), grey until a row is chosen."""
        from html import escape

        self.detail.setHtml("<p style='color:#6b7280'>" + escape(self.tr(
            "Select a row for the engineer's detail: the engine's reason, profile codes and "
            "the similarity score")) + "</p>")

    def _fill(self, plan: Plan | None) -> None:
        from pdcp_studio.app.words.part_names import one_naming

        with one_naming(self.doc.system):  # every row names parts: one lookup for all
            self._fill_rows(plan)

    def _fill_rows(self, plan: Plan | None) -> None:
        view = self.actions_view
        view.setRowCount(0)
        self._detail_hint()
        if plan is None:
            self.summary.setText(self.tr("No plan previewed. Choose an operation to see what it "
                                 "would change before anything changes."))
            return
        title = translate("PlanPanel", dict(OPERATIONS).get(plan.mode, plan.mode))
        text = self.tr("<b>{0}</b>: add {1}, remove {2} ({3} links before, {4} after)").format(
            title, len(plan.added), len(plan.removed), len(plan.links_before),
            len(plan.final_links))
        if plan.configuration_reason:
            text += "<br>" + self.tr("Stored set-up used: {reason}").format(
                reason=plan.configuration_reason)
        if not plan.actions:
            text += "<br>" + self.tr("Nothing to change.")
        self.summary.setText(text)
        for n, a in enumerate(plan.actions, 1):
            add = a.op.value == "add"
            link_words = (f"{self._words(plan, a.link.output)} → "
                          f"{self._words(plan, a.link.input)}")
            why = W.rule_words(a.rule)
            if a.rule.value == "replacement" and isinstance(a.cause, ChannelRef):
                why += self.tr(" ({channel} is missing)").format(
                    channel=W.channel_words(self.doc.system, a.cause))
            detail = (f"<b>{n}. {'add' if add else 'remove'}</b> "
                      f"{self._ref_text(plan, a.link.output)} → "
                      f"{self._ref_text(plan, a.link.input)}<br>"
                      f"<i>{a.rule.value}</i>: {a.reason}")
            if a.similarity is not None:
                detail += f"<br>similarity {a.similarity.describe()}"
            self._add_row([f"{n}.", self.tr("Add") if add else self.tr("Remove"), link_words,
                           why, W.similarity_words(a, plan)], a.link, detail,
                          style.PREVIEW_ADD if add else style.PREVIEW_REMOVE)
        for r in plan.rejections:
            at = r.attempt
            if at.link is not None:
                what = (f"{self._words(plan, at.link.output)} → "
                        f"{self._words(plan, at.link.input)}")
                eng = (f"{self._ref_text(plan, at.link.output)} → "
                       f"{self._ref_text(plan, at.link.input)}")
            elif at.channel is not None:
                what = self._words(plan, at.channel)
                eng = self._ref_text(plan, at.channel)
            else:
                what = eng = ""
            detail = f"<b>{r.kind.value}</b> {eng}<br><i>{at.rule.value}</i>: {r.reason}"
            self._add_row(["", self.tr("Not done"), what, W.refusal_words(r.kind), ""],
                          at.link, detail)
        for note in plan.notes:
            self._add_row(["", self.tr("Note"), note, "", ""], None, note)

    def _on_row_selected(self) -> None:
        items = self.actions_view.selectedItems()
        if not items:
            return
        self.detail.setHtml(str(items[0].data(DETAIL_ROLE) or ""))
        link = items[0].data(LINK_ROLE)
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
        title = translate("PlanPanel", dict(OPERATIONS).get(plan.mode, plan.mode))
        if self.doc.session is not None:
            self.statusMessage.emit(self.tr(
                "Staged {0}: {1} to add, {2} to remove — Write to prosthesis writes them "
                "(Undo unstages)").format(title, len(plan.added), len(plan.removed)))
        else:
            self.statusMessage.emit(
                self.tr(
                    "Applied {mode}: {n_added} added, {n_removed} removed (Undo reverts it)"
                ).format(mode=title, n_added=len(plan.added), n_removed=len(plan.removed))
            )
        self.applied.emit(plan)
        return True
