"""The bus's events in plain words: parts that came and went, and every link the bus made.

A hot-swap repairs itself on the prosthesis (the arbitrator's duty cycle); this list says
what happened: which link was made (device and channel names → device and channel names),
why (a part replaced while running, start-up, automatic set-up…) and how similar the new
part is to the missing one ("same product, other serial number; the same kind of signal").
The engineer's text (the engine's reason and the similarity score) is in each row's tooltip.

Fed by ``SessionBridge.busEvent``; :func:`describe_event` turns one event into rows and is
used without a window too.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING, NamedTuple

from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QAbstractItemView,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.words import plan_words as W
from pdcp_studio.app.words.plan_words import ProfileName
from pdcp_studio.app.words.plural import count
from pdcp_studio.bus import events as ev
from pdcp_studio.model.refs import ChannelRef

if TYPE_CHECKING:
    from pdcp_studio.engine.plan import Plan
    from pdcp_studio.model.system import Link, System

_CTX = "EventsPanel"
#: Rows kept; the oldest go first.
MAX_ROWS = 2000
COL_TIME, COL_WHAT, COL_WHY, COL_SIMILAR = range(4)
_EVENT_ROLE = Qt.ItemDataRole.UserRole
#: Bus errors worth a row (the others are frame-level noise for the monitor).
_ERROR_KINDS = ("duplicate_device", "node_ids_exhausted", "other_arbitrator", "transport")


class EventRow(NamedTuple):
    """One line of the list: what happened, why, how similar; ``detail`` for the tooltip."""

    what: str
    why: str = ""
    similar: str = ""
    detail: str = ""
    link: Link | None = None


def _t(text: str) -> str:
    return translate(_CTX, text)


def describe_event(event: object, system: System | None,
                   profile_name: ProfileName | None = None) -> list[EventRow]:
    """Rows for one bus event (none for events not worth a line).

    ``system`` names the devices (a device that left is still in it, marked missing);
    ``profile_name(profile) -> str`` names what a channel carries (optional)."""
    if isinstance(event, ev.DeviceJoined):
        return [EventRow(_t("{device} joined the bus").format(
            device=W.device_words(system, event.key)), detail=str(event.key))]
    if isinstance(event, ev.DeviceReplaced):  # (a DeviceLeft for good: before that)
        return [EventRow(_t("{device} is replaced by {new}").format(
            device=W.device_words(system, event.key), new=W.device_words(system, event.new)),
            _t("Its replacement's links are written and verified: it is no longer missing"),
            detail=f"{event.key} → {event.new}")]
    if isinstance(event, ev.DeviceLeft):
        return [EventRow(_t("{device} left the bus").format(
            device=W.device_words(system, event.key)), _left_why(event),
            detail="\n".join(t for t in (str(event.key), event.why) if t))]
    if isinstance(event, ev.PlanApplied):
        rows = _plan_rows(event.plan, system, profile_name)
        if event.own and event.plan.actions:
            rows.insert(0, _own_change_row(event, system))
        return rows
    if isinstance(event, ev.TerminalsUnconnected):
        names = ", ".join(W.channel_words(system, r) for r in event.refs)
        return [EventRow(_t("Left unconnected: {names}").format(names=names), event.why,
                         detail=event.why)]
    if isinstance(event, ev.BusState):
        return [EventRow(_bus_state_words(event.state), detail=event.message)]
    if isinstance(event, ev.BusError) and event.kind in _ERROR_KINDS:
        return [EventRow(_t("Bus problem"), event.message, detail=event.kind)]
    return []


def _left_why(event: ev.DeviceLeft) -> str:
    """Why a part left, as the arbitrator measured it on the bus: "No beacon for 1.9 s: 3
    beacon intervals" — from its figures (a CAN or simulated bus, and the host link since
    DEVICE_LEFT carries them), else its own words, else plainly that it did not say (an
    arbitrator from before reasons)."""
    if event.silent_s <= 0 or event.interval_s <= 0:
        if event.why:
            return event.why
        return _t("It is no longer heard on the bus; the arbitrator gave no details")
    intervals = int(event.silent_s / event.interval_s)
    return _t("No beacon for {seconds} s: {intervals} beacon intervals of {ms} ms").format(
        seconds=f"{event.silent_s:.1f}", intervals=intervals,
        ms=f"{event.interval_s * 1000:.0f}")


def mentions_unknown(event: object, system: System | None) -> bool:
    """True when the event names a device ``system`` does not know yet (it joined a moment
    ago): its rows are named again from a later snapshot."""
    keys = []
    if hasattr(event, "key"):
        keys.append(event.key)
    plan = getattr(event, "plan", None)
    for a in getattr(plan, "actions", ()):
        keys += [a.link.output.device, a.link.input.device]
    return system is None or any(k not in system.devices for k in keys)


def _bus_state_words(state: str) -> str:
    return {
        "listening": _t("Listening for another arbitrator before taking part"),
        "arbitrating": _t("PDCP Studio runs this bus"),
        "yielded": _t("Another arbitrator runs this bus: PDCP Studio sends nothing"),
        "disconnected": _t("The adapter is gone: reconnecting"),
        "reconnected": _t("The adapter is back: reading the bus again"),
    }.get(state, state)


def _own_change_row(event: ev.PlanApplied, system: System | None) -> EventRow:
    """The arbitrator changed the prosthesis on its own (start-up, a hot-swap repair): what,
    why, whom it held still while it wrote and whether the links read back as written."""
    plan, result = event.plan, event.result
    why_plan = W.mode_words(plan.mode)
    what = _t("The arbitrator changed links on its own: {why}").format(why=why_plan)
    held = list(getattr(result, "held", []) or [])
    verified = bool(getattr(result, "verified", False))
    outcome = _t("they read back as written") if verified else _t(
        "they did not all read back as written")
    if held:
        names = ", ".join(W.device_words(system, k) for k in held)
        why = _t("It held {parts} still while it wrote, read the links back and let go: "
                 "{outcome}").format(parts=names, outcome=outcome)
    else:
        why = _t("No part that moves the prosthesis needed holding; read back: "
                 "{outcome}").format(outcome=outcome)
    notes = list(getattr(result, "notes", []) or [])
    detail = "\n".join([f"{plan.mode}: {len(plan.added)} added, {len(plan.removed)} removed",
                        f"interlock: {getattr(result, 'interlock', '')}", *notes])
    return EventRow(what, why, detail=detail)


def _plan_rows(plan: Plan, system: System | None,
               profile_name: ProfileName | None) -> list[EventRow]:
    def names_of(*refs: ChannelRef) -> dict[ChannelRef, str]:
        out: dict[ChannelRef, str] = {}
        if profile_name is None:
            return out
        for ref in refs:
            facts = plan.channels.get(ref)
            if facts is not None and facts.profile:
                out[ref] = profile_name(facts.profile)
        return out

    rows = []
    why_plan = W.mode_words(plan.mode)
    for a in plan.actions:
        link = a.link
        words = W.link_words(system, link.output, link.input,
                             names_of(link.output, link.input))
        what = (_t("Linked {link}") if a.op.value == "add" else
                _t("Removed the link {link}")).format(link=words)
        why = f"{why_plan[:1].upper()}{why_plan[1:]}: {W.rule_words(a.rule)}"
        cause = a.cause
        if a.rule.value == "replacement" and isinstance(cause, ChannelRef):
            why += _t(" ({channel} is missing)").format(
                channel=W.channel_words(system, cause))
        rows.append(EventRow(what, why, W.similarity_words(a, plan),
                             W.engineer_detail(a), link))
    return rows


class EventsPanel(QWidget):
    """The list of bus events (newest last) with a Clear button."""

    def __init__(self, system_fn: Callable[[], System | None],
                 profile_name: ProfileName | None = None,
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._system_fn = system_fn
        self._profile_name = profile_name
        self._unnamed: list[QTableWidgetItem] = []
        self.view = QTableWidget(0, 4)
        self.view.setHorizontalHeaderLabels([self.tr("Time"), self.tr("What happened"),
                                             self.tr("Why"), self.tr("How similar")])
        self.view.verticalHeader().hide()
        self.view.setWordWrap(True)  # long names wrap onto more lines, never cut
        self.view.setTextElideMode(Qt.TextElideMode.ElideNone)
        self.view.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        self.view.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.view.setAlternatingRowColors(True)
        self.view.verticalHeader().setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
        header = self.view.horizontalHeader()
        header.setSectionResizeMode(COL_TIME, QHeaderView.ResizeMode.ResizeToContents)
        for col in (COL_WHAT, COL_WHY, COL_SIMILAR):
            header.setSectionResizeMode(col, QHeaderView.ResizeMode.Stretch)
        self.count_label = QLabel()
        self.count_label.setWordWrap(True)  # a long hint must not widen the dock
        self.clear_button = QPushButton(self.tr("Clear"))
        self.clear_button.clicked.connect(self.clear)
        row = QHBoxLayout()
        row.addWidget(self.count_label, 1)
        row.addWidget(self.clear_button)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(6, 6, 6, 6)
        layout.addWidget(self.view, 1)
        layout.addLayout(row)
        self._count()

    def add_event(self, event: object) -> int:
        """Slot for ``SessionBridge.busEvent``: add the event's rows; returns how many."""
        system = self._system_fn()
        rows = describe_event(event, system, self._profile_name)
        stamp = time.strftime("%H:%M:%S")
        provisional = bool(rows) and mentions_unknown(event, system)
        view = self.view
        for n, r in enumerate(rows):
            row = view.rowCount()
            view.insertRow(row)
            tip = "\n".join(t for t in (r.what, r.why, r.similar) if t)
            if r.detail:
                tip += "\n\n" + r.detail
            for col, text in enumerate((stamp, r.what, r.why, r.similar)):
                item = QTableWidgetItem(text)
                item.setTextAlignment(Qt.AlignmentFlag.AlignTop | Qt.AlignmentFlag.AlignLeft)
                item.setToolTip(tip)
                view.setItem(row, col, item)
            first = view.item(row, COL_WHAT)
            if provisional and first is not None:
                first.setData(_EVENT_ROLE, (event, n))
                self._unnamed.append(first)
        extra = view.rowCount() - MAX_ROWS
        for _ in range(max(0, extra)):
            view.removeRow(0)
        if rows:
            self.view.scrollToBottom()
            self._count()
        return len(rows)

    def name_devices(self, system: System | None) -> None:
        """Slot for each new snapshot of the bus: a device that joined before the window
        knew it gets its name now (as the graph shows it)."""
        still = []
        for item in self._unnamed:
            row = item.row()
            if row < 0:  # dropped meanwhile
                continue
            event, n = item.data(_EVENT_ROLE)
            if mentions_unknown(event, system):
                still.append(item)
                continue
            rows = describe_event(event, system, self._profile_name)
            if n < len(rows):
                for col, text in ((COL_WHAT, rows[n].what), (COL_WHY, rows[n].why),
                                  (COL_SIMILAR, rows[n].similar)):
                    cell = self.view.item(row, col)
                    if cell is not None:
                        cell.setText(text)
        self._unnamed = still

    def rows(self) -> list[tuple[str, str, str]]:
        """(what, why, how similar) of every row, oldest first (for tests and reports)."""
        def text(row: int, col: int) -> str:
            cell = self.view.item(row, col)
            return cell.text() if cell is not None else ""

        return [(text(i, COL_WHAT), text(i, COL_WHY), text(i, COL_SIMILAR))
                for i in range(self.view.rowCount())]

    def clear(self) -> None:
        self.view.setRowCount(0)
        self._unnamed = []
        self._count()

    def _count(self) -> None:
        n = self.view.rowCount()
        self.count_label.setText(count("EventsPanel", "%n event(s)", n) if n else
                                 self.tr("No bus events yet: parts that come and go and the "
                                         "links the bus makes appear here"))
