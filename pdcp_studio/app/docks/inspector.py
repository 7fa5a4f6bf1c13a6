"""The inspector: every catalog parameter of the selected device or channel, editable.

One row per parameter of :mod:`pdcp_studio.model.parameters` (name, value, unit, layout),
edited through a widget that fits the layout: type flags as check boxes and choices, a
profile chosen from the named tree or typed in hex, required/desired inputs as a checkable
list of the device's inputs, numbers as spin boxes. A value is checked before it becomes
an undo step; a refused one stays in its field with the reason beneath it. Read-only
parameters (identity, versions, the input's source, kept in step with the links) are
shown as text. The form is rebuilt from the document after every change, so undo and
redo show up here too.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtGui import QColor
from PySide6.QtWidgets import (
    QCheckBox,
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QListWidgetItem,
    QMainWindow,
    QPushButton,
    QScrollArea,
    QVBoxLayout,
    QWidget,
)
from shiboken6 import isValid

from pdcp_studio.app.docks.inspector_editors import (
    ChannelEditors,
    spin_box,
    spin_value,
)
from pdcp_studio.app.docks.inspector_form import DIM_STYLE, Form, selectable
from pdcp_studio.app.documents import commands
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.words.plural import count
from pdcp_studio.errors import ParameterError
from pdcp_studio.model import param_fields
from pdcp_studio.model import parameters as params
from pdcp_studio.model import profile as prof
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Channel, Device, Link

#: Channel parameters shown only in the Details section: how a channel is sent and who
#: sends to it, set by the arbitrator (transfer type, the source's identity and node IDs,
#: an output's node ID).
_DETAIL_PARAMS = frozenset({params.CH_TRANSFER_TYPE, params.IN_SOURCE_VID_PID,
                            params.IN_SOURCE_SN_INDEX, params.IN_SOURCE_NODE_IDS,
                            params.IN_SOURCE_TYPE_PROFILE})
#: Device parameters (channel index 0) → Device attribute edited through them.
DEVICE_FIELD = {m.param: m.fields[0] for m in param_fields.FIELD_MAPS
                if m.scope == "device" and len(m.fields) == 1 and not m.identity
                and params.device_parameter(m.param).writable}


def checks_title(n: int) -> str:
    """``Checks — 3 findings``: the count with the language's own plural (never "(s)")."""
    if not n:
        return translate("Inspector", "<b>Checks</b> — no findings")
    return count("Inspector", "<b>Checks</b> — %n finding(s)", n)


class Inspector(QScrollArea):
    """Parameters of ``doc.selection``; edits become undo steps on the document's stack."""

    #: A short message for the status bar (an edit refused, a link deleted).
    statusMessage = Signal(str)

    def __init__(self, doc: Document, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.setWidgetResizable(True)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self.setMinimumWidth(300)
        #: Editors and error labels of the current form by field name (tests drive them).
        self.editors: dict[str, QWidget] = {}
        self.errors: dict[str, QLabel] = {}
        self.form = Form(self.editors, self.errors)
        self.channel_editors = ChannelEditors(
            doc, self.editors, self._commit_channel, self._refuse, lambda: self._building)
        self.subject: object = None
        self._building = False
        self._pending: object = None
        self._refresh_timer = QTimer(self)
        self._refresh_timer.setSingleShot(True)
        self._refresh_timer.setInterval(0)
        self._refresh_timer.timeout.connect(self._refresh_now)
        #: Findings and their words checked on a worker for the overview being refreshed
        #: (else None), and the number of the newest check: an older check is dropped.
        self._checked: tuple[list[Any], Any] | None = None
        self._check_number = 0
        #: The catalogue problems last said in the window's status bar.
        self._catalog_warned: list[str] | None = None
        doc.selectionChanged.connect(self.show_object)
        doc.channelChanged.connect(self._on_channel_changed)
        doc.deviceChanged.connect(self._on_device_changed)
        # A new system: rebuilt when the event loop is free — Document.set_system's
        # selectionChanged right after usually builds it first (once, not twice).
        doc.systemReset.connect(self._system_reset)
        doc.linksChanged.connect(self._on_links_changed)
        doc.policyChanged.connect(self._on_policy_changed)
        self.show_object(None)

    def _system_reset(self) -> None:
        self._pending = self.doc.selection
        self._refresh_timer.start()

    # -- building -------------------------------------------------------------------
    def show_object(self, obj: object) -> None:
        """Rebuild the form for a device, channel, link or nothing."""
        self._refresh_timer.stop()
        if self._checked is None:
            self._check_number += 1  # a check still running on a worker is not shown
        self._building = True
        try:
            self.subject = obj
            self.editors.clear()
            self.errors.clear()
            form = QWidget()
            box = QVBoxLayout(form)
            box.setContentsMargins(10, 10, 10, 10)
            if isinstance(obj, DeviceKey) and obj in self.doc.system.devices:
                self._build_device(box, self.doc.system.devices[obj])
            elif isinstance(obj, ChannelRef) and self.doc.system.channel(obj) is not None:
                self._build_channel(box, obj, self.doc.channel(obj))
            elif isinstance(obj, Link) and self.doc.system.has_link(obj):
                self._build_link(box, obj)
            else:
                self.subject = None
                self._build_system(box)
            if obj is not None:
                box.addStretch(1)
            old = self.takeWidget()
            if old is not None:
                old.deleteLater()
            self.setWidget(form)
        finally:
            self._building = False

    def _catalogue_warning(self, box: QVBoxLayout) -> None:
        """Device catalogue files that were skipped (file and why), here and once in the
        window's status bar: the parts they describe are named by their numbers."""
        from pdcp_studio.model.catalog import default_catalog_problems

        problems = default_catalog_problems()
        if not problems:
            return
        text = self.tr("A device catalogue file was skipped, so the parts it describes "
                       "are not named from it: {0}").format("; ".join(problems))
        label = QLabel(text)
        label.setWordWrap(True)
        label.setStyleSheet("color: #b45309;")
        label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        box.addWidget(label)
        self.editors["catalog_problems"] = label
        window = self.window()
        if isinstance(window, QMainWindow) and self._catalog_warned != problems:
            self._catalog_warned = problems  # once per set of problems, not per rebuild
            window.statusBar().showMessage(text, 20000)

    # -- the whole system (nothing selected) ---------------------------------------
    def _build_system(self, box: QVBoxLayout) -> None:
        """An overview and the engine's checks; a finding selects its channel."""
        from pdcp_studio.app.docks.inspector_checks import checked_findings

        system = self.doc.system
        missing = sum(1 for d in system.devices.values() if not d.present)
        where = (self.tr("live: {0}").format(getattr(self.doc.session, 'url', '') or 'bus')
                 if self.doc.session is not None else self.doc.title)
        self.form.title(box, self.tr("System"),
                        count("Inspector", "%n device(s)", len(system.devices))
                        + (self.tr(" ({0} missing)").format(missing) if missing else "")
                        + ", " + count("Inspector", "%n link(s)", len(system.links))
                        + f" · {where}")
        hint = QLabel(self.tr("Select a device, channel or link on the graph or in the tree to see "
                      "and edit its parameters."))
        hint.setWordWrap(True)
        hint.setStyleSheet(DIM_STYLE)
        box.addWidget(hint)
        self._catalogue_warning(box)
        checked = self._checked
        if checked is None:
            checked = checked_findings(system, self.doc.autoconfigure)
        findings, texts = checked
        box.addWidget(QLabel(checks_title(len(findings))))
        lst = QListWidget()
        lst.setWordWrap(True)
        colours = {"error": "#b91c1c", "warning": "#b45309", "info": "#475569"}
        severity = {"error": self.tr("Error"), "warning": self.tr("Warning"),
                    "info": self.tr("Note")}
        for f, (plain, detail) in zip(findings, texts, strict=True):
            item = QListWidgetItem(f"{severity[f.severity.value]}: {plain}")
            item.setForeground(QColor(colours.get(f.severity.value, "#1f2933")))
            item.setData(Qt.ItemDataRole.UserRole, f.refs[0] if f.refs else None)
            item.setToolTip(detail)
            lst.addItem(item)
        if not findings:
            lst.addItem(self.tr("Nothing to report: every check passed."))
        lst.itemClicked.connect(lambda it: self._select_finding(it))
        box.addWidget(lst, 1)
        self.editors["findings"] = lst

    def _select_finding(self, item: QListWidgetItem) -> None:
        ref = item.data(Qt.ItemDataRole.UserRole)
        if ref is not None:
            self.doc.select(ref)

    # -- devices --------------------------------------------------------------------
    def _build_device(self, box: QVBoxLayout, d: Device) -> None:
        from pdcp_studio.app.words.part_names import numbers, part_name
        from pdcp_studio.model.catalog import default_catalog

        entry = default_catalog().lookup(d.vid, d.pid)
        product = (self.tr("{product} by {vendor}").format(product=entry.product,
                                                           vendor=entry.vendor)
                   if entry is not None and entry.vendor else
                   entry.product if entry is not None else
                   self.tr("a product no device catalogue knows"))
        state = "" if d.present else "  —  " + self.tr("missing from the bus")
        self.form.title(box, part_name(self.doc.system, d.key), f"{product}{state}")
        grid = self.form.plain_grid(box, self.doc.session is not None)
        name = QLineEdit(d.name)
        name.setPlaceholderText(self.tr("a name for this device (not sent to it)"))
        name.editingFinished.connect(
            lambda w=name: self._commit_device(d.key, "name", w.text().strip(), None, "name"))
        self.form.row(grid, None, self.tr("Name (PDCP Studio)"), "name", name)
        self.form.row(grid, None, self.tr("Product"), "product", selectable(
            entry.product if entry is not None else self.tr("not in the catalogue")))
        self.form.row(grid, None, self.tr("Maker"), "vendor", selectable(
            entry.vendor if entry is not None and entry.vendor else "—"))
        if entry is not None and entry.kind:
            self.form.row(grid, None, self.tr("Kind"), "kind", selectable(entry.kind))
        grid = self.form.details(box)
        self.form.row(grid, None, self.tr("Identity"), "identity", selectable(numbers(d.key)),
                  meta=self.tr("VID/PID/serial"))
        values = {
            params.DEVICE_VID_PID: f"0x{d.vid:04X} / 0x{d.pid:04X}  ({d.vid} / {d.pid})",
            params.DEVICE_SERIAL: str(d.serial),
            params.DEVICE_EAN_LOW: f"0x{d.ean_low:08X}",
            params.DEVICE_EAN_HIGH: f"0x{d.ean_high:08X}",
            params.DEVICE_VERSION: f"FW 0x{d.fw_version:04X} / HW 0x{d.hw_version:04X}",
            params.DEVICE_TYPE_PROFILE: f"0x{d.device_type:04X} / 0x{d.device_profile:04X}",
            params.DEVICE_CHANNEL_COUNT: f"{len(d.channels)} ({len(d.inputs())} in, "
                                         f"{len(d.outputs())} out)",
        }
        for spec in params.parameters_for("device"):
            field = DEVICE_FIELD.get(spec.id)
            if field is None:
                self.form.row(grid, spec, spec.name, f"p{spec.id}", selectable(values[spec.id]))
            elif spec.layout == "string":
                edit = QLineEdit(getattr(d, field))
                edit.editingFinished.connect(
                    lambda w=edit, s=spec, f=field: self._commit_device(
                        d.key, f, w.text(), s, f))
                self.form.row(grid, spec, spec.name, field, edit)
            else:
                spin = spin_box(spec, getattr(d, field))
                spin.editingFinished.connect(
                    lambda w=spin, s=spec, f=field: self._commit_device(
                        d.key, f, spin_value(w), s, f))
                self.form.row(grid, spec, spec.name, field, spin)

    # -- channels -------------------------------------------------------------------
    def _build_channel(self, box: QVBoxLayout, ref: ChannelRef, ch: Channel) -> None:
        from pdcp_studio.app.words.part_names import names, part_name

        d = self.doc.device(ref.device)
        name = self.doc.tree.name_of(ch.profile)
        what = names(self.doc.system).channel_only(ref, self.doc.profile_name(ch.profile))
        head = (self.tr("Input {n}: {what}") if ch.is_input else
                self.tr("Output {n}: {what}")).format(n=ch.index, what=what)
        self.form.title(box, head, f"{part_name(self.doc.system, d.key)} · {name}")
        box.addWidget(self._links_summary(ref, ch))
        grid = self.form.plain_grid(box, self.doc.session is not None)
        holder = QVBoxLayout()
        box.addLayout(holder)
        self._detail_grid = self.form.details(holder)
        for spec in params.parameters_for(ch.direction):
            if spec.id not in _DETAIL_PARAMS:
                self._channel_row(grid, spec, ref, ch, d)
        self.form.row(self._detail_grid, None, self.tr("Profile code"), "profile_code",
                  selectable(prof.fmt(ch.profile)), meta=self.tr("parameter 1, bytes 2–3"))
        for spec in params.parameters_for(ch.direction):
            if spec.id in _DETAIL_PARAMS:
                self._channel_row(self._detail_grid, spec, ref, ch, d)

    def _channel_row(self, grid: QGridLayout, spec: params.ParameterSpec, ref: ChannelRef,
                     ch: Channel, d: Device) -> None:
        pid, row, editors = spec.id, self.form.row, self.channel_editors
        if pid == params.CH_TYPE_PROFILE:
            main, detail = editors.type_editor(ref, ch)
            row(grid, None, self.tr("Control mode"), "type", main, meta="parameter 1, byte 0–1")
            row(self._detail_grid, spec, self.tr("Channel type"), "type.detail", detail)
            row(grid, None, "Profile", "profile",
                editors.profile_editor(ref, "profile", ch.profile, allow_null=False),
                meta="parameter 1, bytes 2–3")
            self.editors["profile"].setToolTip(self.tr("the profile (bytes 2–3 of parameter 1)"))
        elif pid == params.CH_DESCRIPTOR:
            edit = QLineEdit(ch.descriptor)
            edit.editingFinished.connect(
                lambda w=edit, s=spec: self._commit_channel(ref, "descriptor", w.text(), s))
            row(grid, spec, spec.name, "descriptor", edit)
        elif pid == params.CH_TRANSFER_TYPE:
            row(grid, spec, spec.name, "transfer_type", selectable(
                f"{ch.direction.transfer_type} ({ch.direction.value})"))
        elif pid == params.CH_DATA_ENABLED:
            box = QCheckBox(self.tr("enabled"))
            box.setChecked(ch.data_enabled)
            box.toggled.connect(
                lambda on: self._commit_channel(ref, "data_enabled", bool(on), None))
            row(grid, spec, spec.name, "data_enabled", box)
        elif pid in (params.CH_REQUIRED_INPUTS, params.CH_DESIRED_INPUTS):
            field = "required_inputs" if pid == params.CH_REQUIRED_INPUTS else "desired_inputs"
            row(grid, spec, spec.name, field, editors.inputs_list(ref, ch, d, field, spec))
        elif ch.is_input and pid == params.IN_TERMINAL_PROFILE:
            row(grid, spec, spec.name, "terminal_profile",
                editors.profile_editor(ref, "terminal_profile", ch.terminal_profile,
                                       allow_null=True))
        elif ch.is_output and pid == params.OUT_NODE_ID:
            spin = spin_box(spec, ch.node_id)
            spin.editingFinished.connect(
                lambda w=spin, s=spec: self._commit_channel(ref, "node_id", spin_value(w), s))
            row(grid, spec, spec.name, "node_id", spin)
        else:
            row(grid, spec, spec.name, f"p{pid}", selectable(self._source_text(ch, pid)))

    @staticmethod
    def _source_text(ch: Channel, pid: int) -> str:
        s = ch.source
        if pid == params.IN_SOURCE_VID_PID:
            text = f"0x{s.vid:04X} / 0x{s.pid:04X}"
        elif pid == params.IN_SOURCE_SN_INDEX:
            text = f"SN {s.serial}, channel {s.index}"
        elif pid == params.IN_SOURCE_NODE_IDS:
            text = "set by the arbitrator when linked"
        elif pid == params.IN_SOURCE_TYPE_PROFILE:
            text = f"0x{s.type:04X} / 0x{s.profile:04X}"
        else:
            return "—"
        return text + ("" if s.connected else "  (not connected)")

    def _links_summary(self, ref: ChannelRef, ch: Channel) -> QLabel:
        system = self.doc.system
        if ch.is_input:
            src = system.source_of(ref)
            text = (self.tr("Fed by {0}").format(self._describe(src)) if src else
                    self.tr("Nothing feeds it (not linked)"))
        else:
            fed = system.inputs_fed_by(ref)
            text = (self.tr("Feeds {0}").format("; ".join(self._describe(r) for r in fed))
                    if fed else self.tr("Feeds nothing"))
        label = selectable(text)
        return label

    def _describe(self, ref: ChannelRef) -> str:
        """``Multi-grip hand, channel 1 (Power grip)``: the graph's words for a channel."""
        from pdcp_studio.app.words.plan_words import channel_words

        ch = self.doc.system.channel(ref)
        name = self.doc.profile_name(ch.profile) if ch else ""
        return channel_words(self.doc.system, ref, "" if name.startswith("0x") else name)

    # -- links ----------------------------------------------------------------------
    def _build_link(self, box: QVBoxLayout, link: Link) -> None:
        self.form.title(
            box, self.tr("Link"), f"{self._describe(link.output)}\n→ {self._describe(link.input)}"
        )
        out = self.doc.system.channel(link.output)
        inp = self.doc.system.channel(link.input)
        if out is not None and inp is not None:
            from pdcp_studio.engine.similarity import determine_similarity

            sim = determine_similarity(out.type, out.profile, inp.type, inp.profile)
            box.addWidget(selectable(f"Similarity {sim.describe()}"))
        row = QHBoxLayout()
        delete = QPushButton(self.tr("Delete link"))
        delete.clicked.connect(lambda: self._delete_link(link))
        row.addWidget(delete)
        row.addStretch(1)
        box.addLayout(row)
        self.editors["delete"] = delete

    def _delete_link(self, link: Link) -> None:
        if commands.push_remove_links(self.doc, [link]):
            self.statusMessage.emit(self.tr("Removed link {link}").format(
                link=f"{self._describe(link.output)} → {self._describe(link.input)}"))

    # -- committing -----------------------------------------------------------------
    def _refuse(self, field: str, reason: str) -> None:
        label = self.errors.get(field)
        if label is not None:
            label.setText(self.tr("Refused: {reason}").format(reason=reason))
            label.show()
        self.statusMessage.emit(self.tr("Refused: {reason}").format(reason=reason))

    def _validate(self, spec: params.ParameterSpec | None, value: Any) -> str | None:
        if spec is None or value is None:
            return None
        try:
            params.encode_value(spec, value)
        except ParameterError as err:
            return str(err)
        return None

    def _commit(self, field: str, spec: params.ParameterSpec | None, value: Any,
                push: Callable[[], bool]) -> bool:
        if self._building:
            return False
        reason = self._validate(spec, value)
        if reason is not None:
            self._refuse(field, reason)
            return False
        label = self.errors.get(field)
        if label is not None:
            label.hide()
        return push()

    def _commit_channel(self, ref: ChannelRef, name: str, value: Any,
                        spec: params.ParameterSpec | None, field: str | None = None) -> bool:
        """Check and push one channel edit; a refusal shows beside the field."""
        live = commands.live_write_refusal(self.doc, name, device=False)
        if live is not None and not self._building:
            self._refuse(field or name, live)
            return False
        return self._commit(field or name, spec, value,
                            lambda: commands.push_channel_field(self.doc, ref, name, value))

    def _commit_device(self, key: DeviceKey, name: str, value: Any,
                       spec: params.ParameterSpec | None, field: str) -> bool:
        live = commands.live_write_refusal(self.doc, name, device=True)
        if live is not None and not self._building:
            self._refuse(field, live)
            return False
        return self._commit(field, spec, value,
                            lambda: commands.push_device_field(self.doc, key, name, value))

    # -- document → form ------------------------------------------------------------
    def _refresh_later(self, obj: object) -> None:
        """Rebuild the form for ``obj`` once the event loop is free: a live snapshot changes
        many devices at once, and the overview runs every check on the whole system."""
        self._pending = obj
        self._check_number += 1  # what a running check looked at is out of date
        self._refresh_timer.start()

    def _refresh_now(self) -> None:
        """The deferred rebuild. The overview of a live bus has its checks run on a worker
        (on a copy of the system) and is rebuilt when they arrive: the bus changes it
        while a scan runs, and the checks of a 93-device bus took the GUI thread ~15 ms
        (more while the bus threads hold the GIL). Other forms are rebuilt at once."""
        if self._pending is not None or self.doc.session is None or not self.doc.system.devices:
            self.show_object(self._pending)
            return
        from pdcp_studio.app.docks.inspector_checks import checked_findings
        from pdcp_studio.app.workers import Worker

        self._check_number += 1
        number, system = self._check_number, self.doc.system.copy()
        autoconfigure = self.doc.autoconfigure
        worker = Worker(lambda _p, _c: checked_findings(system, autoconfigure),
                        "Check the system")
        worker.finished.connect(lambda checked: self._show_checked(number, checked))
        worker.start()

    def _show_checked(self, number: int, checked: tuple[list[Any], Any]) -> None:
        """A worker's checks arrived: show them unless something newer was asked for."""
        if not isValid(self) or number != self._check_number or self.doc.selection is not None:
            return
        self._checked = checked
        try:
            self.show_object(None)
        finally:
            self._checked = None

    def _on_channel_changed(self, ref: ChannelRef) -> None:
        if self.subject == ref or (isinstance(self.subject, DeviceKey)
                                   and self.subject == ref.device):
            self._refresh_later(self.subject)

    def _on_device_changed(self, key: DeviceKey) -> None:
        subj = self.subject
        if subj is None or subj == key or (isinstance(subj, ChannelRef) and subj.device == key):
            self._refresh_later(subj)

    def _on_policy_changed(self, _policy: object) -> None:
        if self.subject is None:  # the system's checks follow the prosthesis's policy
            self._refresh_later(None)

    def _on_links_changed(self) -> None:
        if self.subject is None or isinstance(self.subject, ChannelRef | Link):
            self._refresh_later(self.doc.selection)
