"""The History view: every change recorded for the connected prosthesis (or all of them).

Reads the fitting history in use (:mod:`pdcp_studio.storage.archive`: the clinic's shared
archive, or this computer's SQLite file) on a worker; one row per entry — time, operator,
patient, bus, action, outcome — filtered by prosthesis and by patient reference (a clinic's
view: every workstation's changes). One selected entry shows its details (the plan with its
reasons, the interlock, the stored configuration's CRC before and after); two selected show the
difference between their links. Restore writes the selected entry's links (and stored
configuration, when it was recorded) back as a new, previewed transaction; Report makes the
fitting report for the entry's session. The chain is verified each time it is read.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QCoreApplication, QEvent, QPoint, Qt, Signal
from PySide6.QtGui import (
    QBrush,
    QColor,
    QHelpEvent,
    QResizeEvent,
    QTextCharFormat,
    QTextCursor,
)
from PySide6.QtWidgets import (
    QComboBox,
    QFileDialog,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QLineEdit,
    QMessageBox,
    QPlainTextEdit,
    QPushButton,
    QSplitter,
    QTableWidget,
    QTableWidgetItem,
    QToolButton,
    QToolTip,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.words.history_words import (
    entry_effect,
    entry_summary,
    entry_words,
    headline,
    predates,
)
from pdcp_studio.app.workers import ProgressFn, Worker
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.safe_text import shown
from pdcp_studio.model.system import Link

if TYPE_CHECKING:
    from pdcp_studio.storage.history import VerifyReport

COLUMNS = (
    "#",
    QT_TRANSLATE_NOOP("HistoryPanel", "Time (UTC)"),
    QT_TRANSLATE_NOOP("HistoryPanel", "Action"),
    QT_TRANSLATE_NOOP("HistoryPanel", "Outcome"),
    QT_TRANSLATE_NOOP("HistoryPanel", "Operator"),
    QT_TRANSLATE_NOOP("HistoryPanel", "Patient"),
    QT_TRANSLATE_NOOP("HistoryPanel", "Links"),
    QT_TRANSLATE_NOOP("HistoryPanel", "Bus"),
)
#: The Action column: what the change did, the first line of its effect.
ACTION_COLUMN = 2
THIS, ALL = "this", "all"
FAILED_COLOUR = QColor(250, 215, 215)
#: The details pane's share of the panel's width (what an entry changed needs room).
DETAILS_SHARE = 0.42

#: How a link is said in the details: ``str`` gives the engineer's ``2641/513/201#3 →
#: 2641/769/301#1``; the panel passes part and channel names (:meth:`HistoryPanel.link_words`).
LinkWords = Callable[[Link], str]
#: One fitting-history entry, as ``History.entries`` returns it (its JSON body, with ``id``).
Entry = dict[str, Any]


def _tr(text: str) -> str:
    return QCoreApplication.translate("HistoryPanel", text)


def entry_links(entry: Entry, key: str = "links_after") -> list[Link]:
    from pdcp_studio.bus.transaction import link_from_json

    return [link_from_json(d) for d in entry.get(key) or ()]


def entry_devices(entry: Entry) -> set[DeviceKey]:
    return {DeviceKey(int(d["vid"]), int(d["pid"]), int(d["serial"]))
            for d in entry.get("devices") or ()}


def for_prosthesis(entries: list[Entry], devices: set[DeviceKey]) -> list[Entry]:
    """The entries of a prosthesis: those that share a device with it."""
    return [e for e in entries if entry_devices(e) & devices]


def summary_tip(entry: Entry) -> str:
    """The Action cell's tooltip: every headline of the effect, and the recorded action."""
    effect = entry_effect(entry)
    action = str(entry.get("action") or "")
    if effect is None:
        return action + "\n" + predates()
    return "\n".join([*headline(effect), f"({action})"])


def outcome_text(entry: Entry) -> str:
    outcome = entry.get("outcome") or {}
    status = outcome.get("status", "")
    if status == "applied":
        return (
            translate("HistoryPanel", "applied, verified")
            if entry.get("verified")
            else translate("HistoryPanel", "applied")
        )
    if status in ("failed", "rolled_back"):
        word = (
            translate("HistoryPanel", "rolled back")
            if status == "rolled_back"
            else translate("HistoryPanel", "failed")
        )
        return f"{word} ({outcome.get('step', '')})"
    return str(status)


def entries_difference(a: Entry, b: Entry, say: LinkWords = str) -> list[str]:
    """How the links after entry ``a`` and after entry ``b`` differ, in plain words."""
    la, lb = set(entry_links(a)), set(entry_links(b))
    out = [translate("HistoryPanel", "Links after #{0}: {1}; after #{2}: {3}").format(
        a["id"], len(la), b["id"], len(lb))]
    for link in sorted(la - lb):
        out.append(translate("HistoryPanel", "  only after #{0}: {1}").format(a["id"],
                                                                            say(link)))
    for link in sorted(lb - la):
        out.append(translate("HistoryPanel", "  only after #{0}: {1}").format(b["id"],
                                                                            say(link)))
    if la == lb:
        out.append(translate("HistoryPanel", "  the same links"))
    ca, cb = a.get("config_crc_after"), b.get("config_crc_after")
    out.append(
        translate(
            "HistoryPanel", "Stored configuration CRC after #{0}: {1}; after #{2}: {3}{4}"
        ).format(
            a["id"],
            ca or "none",
            b["id"],
            cb or "none",
            "" if ca != cb else translate("HistoryPanel", " (the same)"),
        )
    )
    return out


def workstation_lines(entry: Entry) -> list[str]:
    """Where the change was made (the clinic's archive is shared by every workstation) and,
    for an entry moved in from another archive, where it came from."""
    out = []
    origin = entry.get("origin") if isinstance(entry.get("origin"), dict) else None
    where = entry.get("workstation") or (origin or {}).get("workstation")
    if where:
        out.append(translate("HistoryPanel", "Workstation: {0}").format(where))
    if origin is not None:
        out.append(translate("HistoryPanel", "Imported from {0}, where it was entry #{1}").format(
            origin.get("archive") or "—", origin.get("id")))
    return out


def matches_patient(entry: Entry, text: str) -> bool:
    """The patient filter: the reference contains ``text`` (any case); empty matches all."""
    wanted = text.strip().casefold()
    return not wanted or wanted in str(entry.get("patient") or "").casefold()


def entry_details(entry: Entry, say: LinkWords = str) -> list[str]:
    """One entry in plain words: who, when, what, why, and how it ended (``say`` words
    each link of its plan; the lines are the same, one for one, whatever it says)."""
    plan = entry.get("plan") or {}
    outcome = entry.get("outcome") or {}
    out = [translate("HistoryPanel", "#{0} {1} — {2}").format(entry["id"], entry.get("time", ""),
                                        entry.get("action", "")),
           translate("HistoryPanel", "Operator: {0}    Patient: {1}    Bus: {2}").format(
               entry.get("operator") or "—", entry.get("patient") or "—",
               entry.get("bus") or "—"),
           *workstation_lines(entry),
           translate("HistoryPanel", "Outcome: {0}{1}").format(outcome.get("status", ""),
                                          f" at {outcome['step']}: {outcome['reason']}"
                                          if outcome.get("reason") else ""),
           translate("HistoryPanel", "Motion interlock: {0}").format(entry.get("interlock") or "—"),
           translate("HistoryPanel", "Stored configuration CRC: {0} → {1}").format(
               entry.get("config_crc_before") or "none", entry.get("config_crc_after")
               or "none")]
    for a in plan.get("actions", ()):
        from pdcp_studio.bus.transaction import link_from_json

        sign = "+" if a.get("op") == "add" else "−"
        why = f"  ({a['reason']})" if a.get("reason") else ""
        out.append(f"  {sign} {say(link_from_json(a))}{why}")
    for p in plan.get("parameters", ()):
        d = p.get("device", {})
        out.append(
            translate(
                "HistoryPanel", "  parameter 0x{0:02X} of {1}/{2}/{3} channel {4} = {5}"
            ).format(
                int(p.get("param", 0)),
                d.get("vid"),
                d.get("pid"),
                d.get("serial"),
                p.get("channel"),
                p.get("value"),
            )
        )
    for note in outcome.get("notes", ()):
        out.append(f"  note: {note}")
    return [shown(line) for line in out]  # operator, patient, reasons: shown, never run


#: What reading the archive gives: every entry, the chain's verification, the archive's path.
HistoryRead = tuple[list[Entry], "VerifyReport", str]


def read_history(_progress: ProgressFn | None = None,
                 _cancel: threading.Event | None = None) -> HistoryRead:
    """Every entry and the chain's verification (a worker's job: file or server I/O), from
    the archive in use (``$PDCP_STUDIO_ARCHIVE``, the clinic's, or this computer's)."""
    from pdcp_studio.storage.history import History

    with History.open() as archive:
        return archive.entries(), archive.verify(), archive.location


class DetailsView(QPlainTextEdit):
    """The details pane: plain text whose lines may carry a tooltip of their own (a
    worded link keeps its numbers one hover away)."""

    def tip_at(self, pos: QPoint) -> str:
        """The tooltip of the line at ``pos`` (viewport coordinates), or ""."""
        cursor = self.cursorForPosition(pos)
        tip = cursor.charFormat().toolTip()
        if not tip and not cursor.atBlockEnd():
            cursor.movePosition(QTextCursor.MoveOperation.Right)
            tip = cursor.charFormat().toolTip()
        return tip

    def viewportEvent(self, event: QEvent) -> bool:
        if event.type() == QEvent.Type.ToolTip and isinstance(event, QHelpEvent):
            tip = self.tip_at(event.pos())
            if tip:
                QToolTip.showText(event.globalPos(), tip, self.viewport())
            else:
                QToolTip.hideText()
            return True
        return super().viewportEvent(event)


class HistoryPanel(QWidget):
    """The fitting history (see the module docstring). ``window`` (kept as ``main``: a
    widget's ``window()`` must stay Qt's) gives ``doc``, ``flow``, ``live``, ``error_box``,
    ``show_message``."""

    loaded = Signal()

    def __init__(self, window: Any, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.main = window
        self._entries: list[Entry] = []
        self.shown: list[Entry] = []
        self.verify_report: VerifyReport | None = None
        self.path = ""
        self._worker: Worker | None = None

        self.scope = QComboBox()
        self.scope.addItem(self.tr("This prosthesis"), THIS)
        self.scope.addItem(self.tr("All prostheses"), ALL)
        self.scope.currentIndexChanged.connect(lambda _i: self._fill())
        self.patient_filter = QLineEdit()
        self.patient_filter.setPlaceholderText(self.tr("Patient reference"))
        self.patient_filter.setClearButtonEnabled(True)
        self.patient_filter.setToolTip(self.tr("Show only the changes of the patients whose "
                                               "reference contains this text"))
        self.patient_filter.textChanged.connect(lambda _t: self._fill())
        self.chain = QLabel()
        self.refresh_button = QPushButton(self.tr("Refresh"))
        self.refresh_button.clicked.connect(self.refresh)
        self.table = QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels([self.tr(c) for c in COLUMNS])
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        self.table.setSelectionBehavior(QTableWidget.SelectionBehavior.SelectRows)
        self.table.verticalHeader().setVisible(False)
        self.table.setAlternatingRowColors(True)
        self.table.setWordWrap(False)
        header = self.table.horizontalHeader()
        for col in range(len(COLUMNS)):
            header.setSectionResizeMode(col, QHeaderView.ResizeMode.ResizeToContents)
        header.setStretchLastSection(True)
        self.table.itemSelectionChanged.connect(self._show_selection)
        self.details = DetailsView()
        self.details.setReadOnly(True)
        self.technical_button = QToolButton()
        self.technical_button.setText(self.tr("Technical detail"))
        self.technical_button.setCheckable(True)
        self.technical_button.setAutoRaise(True)
        self.technical_button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextBesideIcon)
        self.technical_button.setArrowType(Qt.ArrowType.RightArrow)
        self.technical = QPlainTextEdit()
        self.technical.setReadOnly(True)
        self.technical.hide()
        self.technical_button.toggled.connect(self._show_technical)
        detail_side = QWidget()
        side = QVBoxLayout(detail_side)
        side.setContentsMargins(0, 0, 0, 0)
        side.addWidget(self.details, 3)
        side.addWidget(self.technical_button, 0, Qt.AlignmentFlag.AlignLeft)
        side.addWidget(self.technical, 2)
        self.technical.setMinimumHeight(60)
        #: The refusal on screen when a restore needs a part not on the bus (tests read it).
        self.refusal: QMessageBox | None = None
        self.restore_button = QPushButton(self.tr("Restore on the prosthesis…"))
        self.restore_button.setToolTip(self.tr("Put the connected prosthesis back as it was "
                                               "after this entry (previewed, confirmed)"))
        self.report_button = QPushButton(self.tr("Fitting report…"))
        self.restore_button.clicked.connect(lambda: self.restore_selected())
        self.report_button.clicked.connect(lambda: self.ask_report())

        bar = QHBoxLayout()
        bar.addWidget(QLabel(self.tr("Show:")))
        bar.addWidget(self.scope)
        bar.addWidget(QLabel(self.tr("Patient:")))
        bar.addWidget(self.patient_filter)
        bar.addWidget(self.chain, 1)
        bar.addWidget(self.refresh_button)
        buttons = QHBoxLayout()
        self.hint = QLabel()
        self.hint.setWordWrap(True)
        buttons.addWidget(self.hint, 1)
        buttons.addWidget(self.report_button)
        buttons.addWidget(self.restore_button)
        split = QSplitter(Qt.Orientation.Horizontal)
        split.addWidget(self.table)
        split.addWidget(detail_side)
        split.setStretchFactor(0, 3)
        split.setStretchFactor(1, 2)
        split.setChildrenCollapsible(False)
        self.split = split
        self._shared = False  # the details' share is set once the panel has its width
        box = QVBoxLayout(self)
        box.setContentsMargins(6, 6, 6, 6)
        box.addLayout(bar)
        box.addWidget(split, 1)
        box.addLayout(buttons)
        self._update_hint(0)
        self._update_buttons()

    def resizeEvent(self, event: QResizeEvent) -> None:
        """The first time the panel has a real width, the details get their share of it
        (sizes set before that were scaled down to a 130 px sliver)."""
        super().resizeEvent(event)
        width = self.split.width()
        if not self._shared and width > 200:
            self._shared = True
            details = round(width * DETAILS_SHARE)
            self.split.setSizes([width - details, details])

    # -- reading -------------------------------------------------------------------------
    def refresh(self) -> Worker:
        """Read the archive again (on a worker); ``loaded`` follows."""
        worker = Worker(read_history, "Read the fitting history")
        # (bound methods: their connections end with the panel; _read shows only the latest)
        worker.finished.connect(self._read)
        worker.failed.connect(self._read_failed)
        self._worker = worker
        return worker.start()

    def _overtaken(self) -> bool:
        """The read reporting now is not the latest: an earlier one that ended later (a
        loaded machine) read the archive before the entries that followed."""
        sender = self.sender()
        return sender is not None and sender is not self._worker

    def _read(self, result: HistoryRead) -> None:
        if self._overtaken():
            return
        self._entries, report, self.path = result
        self.verify_report = report
        if report.ok:
            self.chain.setText(self.tr("{0} entries · chain intact").format(report.entries))
            self.chain.setStyleSheet("color: #0b7a4b;")
        else:
            self.chain.setText(self.tr("The history was altered: {0}").format(report.reason))
            self.chain.setStyleSheet("color: #b91c1c; font-weight: bold;")
        self.chain.setToolTip(self.path)
        self._fill()
        self.loaded.emit()

    def _read_failed(self, message: str) -> None:
        if self._overtaken():
            return
        self.chain.setText(self.tr("Cannot read the fitting history: {0}").format(message))
        self.chain.setStyleSheet("color: #b91c1c;")

    def all_entries(self) -> list[Entry]:
        return list(self._entries)

    def _prosthesis(self) -> set[DeviceKey]:
        bus = self.main.doc.bus_system
        return set(bus.devices) if bus is not None else set()

    def _fill(self) -> None:
        devices = self._prosthesis()
        scope = self.scope.currentData()
        entries = self._entries if scope == ALL or not devices else for_prosthesis(
            self._entries, devices)
        text = self.patient_filter.text()
        entries = [e for e in entries if matches_patient(e, text)]
        self.shown = list(reversed(entries))  # newest first
        self.table.setRowCount(len(self.shown))
        for row, e in enumerate(self.shown):
            before, after = len(e.get("links_before") or ()), len(e.get("links_after") or ())
            cells = [str(e["id"]), str(e.get("time", "")).replace("T", " ").rstrip("Z"),
                     entry_summary(e), outcome_text(e), e.get("operator") or "",
                     e.get("patient") or "", f"{before} → {after}", e.get("bus") or ""]
            failed = (e.get("outcome") or {}).get("status") in ("failed", "rolled_back")
            for col, text in enumerate(cells):
                text = shown(text)  # the operator and the patient as typed: never raw escapes
                item = QTableWidgetItem(text)
                item.setToolTip(summary_tip(e) if col == ACTION_COLUMN else text)
                if failed:
                    item.setBackground(QBrush(FAILED_COLOUR))
                self.table.setItem(row, col, item)
        self._show_selection()

    # -- selection -----------------------------------------------------------------------
    def selected(self) -> list[Entry]:
        rows = sorted({i.row() for i in self.table.selectedIndexes()})
        return [self.shown[r] for r in rows if r < len(self.shown)]

    def select_ids(self, *ids: int) -> None:
        """Select the rows of these entries (tests, and the report of a new write)."""
        self.table.clearSelection()
        mode = self.table.selectionMode()
        self.table.setSelectionMode(QTableWidget.SelectionMode.MultiSelection)
        for row, e in enumerate(self.shown):
            if e["id"] in ids:
                self.table.selectRow(row)
        self.table.setSelectionMode(mode)

    def link_words(self, link: Link) -> str:
        """A link by part and channel names, as the plan table says it (what each channel
        carries where the window's system knows it)."""
        from pdcp_studio.app.words import plan_words as W

        doc = self.main.doc
        system = getattr(doc, "system", None)
        names: dict[ChannelRef, str] = {}
        for ref in (link.output, link.input):
            ch = system.channel(ref) if system is not None else None
            name = doc.profile_name(ch.profile) if ch is not None and ch.profile else ""
            if name and not name.startswith("0x"):
                names[ref] = name
        return W.link_words(system, link.output, link.input, names)

    def _show_lines(self, worded: list[str], raw: list[str]) -> None:
        """The details in words; a line that words links keeps its numbers as its tooltip."""
        self.details.clear()
        cursor = QTextCursor(self.details.document())
        for n, (line, tip) in enumerate(zip(worded, raw, strict=True)):
            fmt = QTextCharFormat()
            if tip != line:
                fmt.setToolTip(tip)
            if n:
                cursor.insertBlock()
            cursor.insertText(line, fmt)

    def _show_selection(self) -> None:
        chosen = self.selected()
        if len(chosen) == 2:
            older, newer = sorted(chosen, key=lambda e: e["id"])
            self._show_lines(entries_difference(older, newer, self.link_words),
                             entries_difference(older, newer))
        elif len(chosen) == 1:
            self._show_entry(chosen[0])
            self._update_hint(1)
            self._update_buttons()
            return
        else:
            self.details.setPlainText(self.tr("Select an entry to see what it changed, or two "
                                              "to compare them."))
        self.technical.clear()
        self.technical_button.setChecked(False)
        self.technical_button.setVisible(False)
        self._update_hint(len(chosen))
        self._update_buttons()

    def _show_entry(self, entry: Entry) -> None:
        """One entry: who, when and how it ended, then its effect in words and the next
        power-on (the codes under Technical detail); an older entry as it was recorded."""
        worded, raw = entry_details(entry, self.link_words), entry_details(entry)
        said = entry_words(entry)
        effect = entry_effect(entry)
        if said is None or effect is None:
            self._show_lines([*worded[:3], predates(), *worded[3:]],
                             [*raw[:3], predates(), *raw[3:]])
            technical = raw[3:]
        else:
            lines = [*worded[:3], "", *said]
            self._show_lines(lines, lines)
            technical = [*effect.technical(), *raw[3:]]
        self.technical.setPlainText("\n".join(technical))
        self.technical_button.setVisible(True)

    def _show_technical(self, shown: bool) -> None:
        self.technical.setVisible(shown)
        self.technical_button.setArrowType(Qt.ArrowType.DownArrow if shown
                                           else Qt.ArrowType.RightArrow)

    def _update_hint(self, chosen: int) -> None:
        """What a further selection would show; nothing once two are compared."""
        if chosen == 0:
            text = self.tr("Select two entries to see how they differ.")
        elif chosen == 1:
            text = self.tr("Ctrl+click a second entry to see how the two differ.")
        else:
            text = ""
        self.hint.setText(text)
        self.hint.setVisible(bool(text))

    def _update_buttons(self) -> None:
        one = len(self.selected()) == 1
        live = self.main.live.bridge is not None and self.main.doc.bus_system is not None
        self.restore_button.setEnabled(one and live)
        self.report_button.setEnabled(one)

    # -- actions -------------------------------------------------------------------------
    def restore_selected(self) -> bool:
        """Restore the selected entry on the connected prosthesis (a previewed transaction)."""
        chosen = self.selected()
        if len(chosen) != 1:
            return False
        entry = chosen[0]
        bus = self.main.doc.bus_system
        if bus is None:
            self.main.error_box(self.tr("Restore"), self.tr("connect to the prosthesis "
                                                              "first"))
            return False
        from pdcp_studio.app.widgets.restore_refusal import (
            keep_recorded_configuration,
            missing_words,
            refuse,
        )
        from pdcp_studio.bus.transaction import NotRestorable, restore_change

        title = self.tr("Restore history entry {0}").format(entry["id"])
        try:
            change = restore_change(entry, bus)  # the CLI's restore too
        except NotRestorable as err:
            if err.missing:  # refused before anything is written, before any progress
                self.refusal = refuse(self, title, missing_words(entry["id"], err.missing, bus),
                                      lambda: self.main.open_task("replace"))
            else:
                self.main.error_box(self.tr("Restore"), str(err))
            return False
        # As ``history restore``: the stored configuration the entry recorded goes back
        # unless the confirmation's box is unticked.
        return bool(self.main.flow.run(change, title, store=True,
                                       choose=keep_recorded_configuration))

    def ask_report(self) -> None:
        chosen = self.selected()
        if len(chosen) != 1:
            return
        path, _ = QFileDialog.getSaveFileName(
            self,
            self.tr("Fitting report"),
            str(Path(self.main._last_dir()) / f"fitting-{chosen[0]['id']}.pdf"),
            self.tr("PDF (*.pdf)"),
        )
        if path:
            self.main.write_fitting_report(path, entry=chosen[0])
