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

from collections import Counter
from collections.abc import Callable
from typing import Any

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtGui import QColor, QFont
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QListWidgetItem,
    QPushButton,
    QScrollArea,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)
from shiboken6 import isValid

from pdcp_studio.app.documents import commands
from pdcp_studio.app.documents.document import Document
from pdcp_studio.errors import ParameterError
from pdcp_studio.model import param_fields
from pdcp_studio.model import parameters as params
from pdcp_studio.model import profile as prof
from pdcp_studio.model.channel_type import (
    BYTE_SIZE_BITS,
    PRESCALER_HINTS,
    ControlMode,
    DataType,
)
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Channel, Device, Link

ERROR_STYLE = "color: #b91c1c;"
DIM_STYLE = "color: #66707b;"
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


def parse_profile(text: str, tree_items: dict[str, int], *, allow_null: bool = False) -> int:
    """A profile from a tree entry's text or typed hex; ValueError says why not."""
    text = text.strip()
    if text in tree_items:
        return tree_items[text]
    if "(" in text and text.endswith(")"):  # "Power Grip (0x2220)" edited around the name
        text = text[text.rindex("(") + 1 : -1]
    try:
        value = int(text, 16)
    except ValueError:
        raise ValueError(f"“{text}” is neither a profile of the tree nor a hex value") from None
    if not 0 <= value <= 0xFFFF:
        raise ValueError(f"0x{value:X} does not fit in 16 bits")
    if value == prof.NULL_PROFILE:
        if allow_null:
            return value
        raise ValueError("0x0000 is the null profile, which is invalid for a channel")
    if not prof.is_well_formed(value):
        raise ValueError(f"{prof.fmt(value)}: a component follows a zero component")
    return value


def _selectable(text: str) -> QLabel:
    label = QLabel(text)
    label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
    label.setWordWrap(True)
    return label


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

    def _title(self, box: QVBoxLayout, title: str, subtitle: str) -> None:
        t = QLabel(title)
        f = QFont(t.font())
        f.setBold(True)
        f.setPointSizeF(f.pointSizeF() * 1.15)
        t.setFont(f)
        t.setWordWrap(True)
        box.addWidget(t)
        s = _selectable(subtitle)
        s.setStyleSheet(DIM_STYLE)
        box.addWidget(s)

    def _grid(self, box: QVBoxLayout) -> QGridLayout:
        if self.doc.session is not None:
            note = QLabel(self.tr("Live bus: an edit here is a pending change (one undo "
                                  "step); Write to prosthesis writes the pending changes "
                                  "in one transaction."))
            note.setWordWrap(True)
            note.setStyleSheet("color: #b45309;")
            box.addWidget(note)
        grid = QGridLayout()
        grid.setHorizontalSpacing(8)
        grid.setVerticalSpacing(3)
        grid.setColumnStretch(1, 1)
        for col, text in enumerate(("Parameter", "Value")):
            h = QLabel(self.tr("<b>{text}</b>").format(text=text))
            grid.addWidget(h, 0, col)
        box.addLayout(grid)
        return grid

    def _details(self, box: QVBoxLayout, expanded: bool = False) -> QGridLayout:
        """A collapsible "Details" section (collapsed at first): the engineer's encoding,
        codes and numbers, one click away from what a prosthetist sets."""
        from PySide6.QtWidgets import QToolButton

        button = QToolButton()
        button.setText(self.tr("Details for engineers"))
        button.setCheckable(True)
        button.setChecked(expanded)
        button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextBesideIcon)
        button.setArrowType(Qt.ArrowType.DownArrow if expanded else Qt.ArrowType.RightArrow)
        button.setAutoRaise(True)
        body = QWidget()
        grid = QGridLayout(body)
        grid.setContentsMargins(0, 0, 0, 0)
        grid.setHorizontalSpacing(8)
        grid.setVerticalSpacing(3)
        grid.setColumnStretch(1, 1)
        body.setVisible(expanded)

        def toggle(on: bool) -> None:
            body.setVisible(on)
            button.setArrowType(Qt.ArrowType.DownArrow if on else Qt.ArrowType.RightArrow)

        button.toggled.connect(toggle)
        box.addWidget(button)
        box.addWidget(body)
        self.editors["details"] = button
        return grid

    def _plain_grid(self, box: QVBoxLayout) -> QGridLayout:
        """:meth:`_grid` whose rows show names only (their encoding in the tooltip)."""
        grid = self._grid(box)
        grid.setProperty("plainRows", True)
        return grid

    def _row(self, grid: QGridLayout, spec: params.ParameterSpec | None, name: str,
             field: str, editor: QWidget, meta: str | None = None) -> None:
        """One parameter: name, editor, unit and layout; an error line below it."""
        row = grid.rowCount()
        if meta is None:
            meta = " · ".join(x for x in (spec.unit if spec else "",
                                           spec.layout if spec else "PDCP Studio only") if x)
        title = spec.name if spec else name
        plain = bool(grid.property("plainRows")) and bool(title)
        if plain:  # a prosthetist's setting: the encoding is the engineer's, in the tooltip
            label = QLabel(title)
        else:
            label = QLabel(
            self.tr("{title}<br><span style='color:#66707b; font-size:small'>{meta}</span>").format(
                title=title, meta=meta
            )
            if title
            else self.tr("<span style='color:#66707b; font-size:small'>{meta}</span>").format(
                meta=meta
            )
            )
        label.setWordWrap(True)
        label.setMinimumWidth(90)
        label.setMaximumWidth(130)
        tip = f"parameter {spec.id}: {spec.doc}" if spec and spec.doc else (
            f"parameter {spec.id}" if spec else "kept by PDCP Studio only")
        if spec and not spec.writable:
            tip += " (read-only)"
        if plain and meta:
            tip += f"\n{meta}"
        label.setToolTip(tip)
        grid.addWidget(label, row, 0, Qt.AlignmentFlag.AlignTop)
        grid.addWidget(editor, row, 1)
        err = QLabel()
        err.setStyleSheet(ERROR_STYLE)
        err.setWordWrap(True)
        err.hide()
        grid.addWidget(err, row + 1, 1)
        self.editors[field] = editor
        self.errors[field] = err

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
        status = getattr(window, "statusBar", None)
        if callable(status) and getattr(window, "_catalog_warned", None) != problems:
            window._catalog_warned = problems  # once per set of problems, not per rebuild
            status().showMessage(text, 20000)

    # -- the whole system (nothing selected) ---------------------------------------
    def _build_system(self, box: QVBoxLayout) -> None:
        """An overview and the engine's checks; a finding selects its channel."""
        from pdcp_studio.app.docks.inspector_checks import checked_findings

        system = self.doc.system
        missing = sum(1 for d in system.devices.values() if not d.present)
        where = (self.tr("live: {0}").format(getattr(self.doc.session, 'url', '') or 'bus')
                 if self.doc.session is not None else self.doc.title)
        self._title(box, self.tr("System"), self.tr("{0} devices").format(len(system.devices))
                    + (self.tr(" ({0} missing)").format(missing) if missing else "")
                    + self.tr(", {0} links · {1}").format(len(system.links), where))
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
        box.addWidget(
            QLabel(
                self.tr("<b>Checks</b> — {v0} finding{v1}").format(
                    v0=len(findings) or self.tr("no"), v1="s" * (len(findings) != 1)
                )
            )
        )
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
        self._title(box, part_name(self.doc.system, d.key), f"{product}{state}")
        grid = self._plain_grid(box)
        name = QLineEdit(d.name)
        name.setPlaceholderText(self.tr("a name for this device (not sent to it)"))
        name.editingFinished.connect(
            lambda w=name: self._commit_device(d.key, "name", w.text().strip(), None, "name"))
        self._row(grid, None, self.tr("Name (PDCP Studio)"), "name", name)
        self._row(grid, None, self.tr("Product"), "product", _selectable(
            entry.product if entry is not None else self.tr("not in the catalogue")))
        self._row(grid, None, self.tr("Maker"), "vendor", _selectable(
            entry.vendor if entry is not None and entry.vendor else "—"))
        if entry is not None and entry.kind:
            self._row(grid, None, self.tr("Kind"), "kind", _selectable(entry.kind))
        grid = self._details(box)
        self._row(grid, None, self.tr("Identity"), "identity", _selectable(numbers(d.key)),
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
                self._row(grid, spec, spec.name, f"p{spec.id}", _selectable(values[spec.id]))
            elif spec.layout == "string":
                edit = QLineEdit(getattr(d, field))
                edit.editingFinished.connect(
                    lambda w=edit, s=spec, f=field: self._commit_device(
                        d.key, f, w.text(), s, f))
                self._row(grid, spec, spec.name, field, edit)
            else:
                spin = self._spin(spec, getattr(d, field))
                spin.editingFinished.connect(
                    lambda w=spin, s=spec, f=field: self._commit_device(
                        d.key, f, self._spin_value(w), s, f))
                self._row(grid, spec, spec.name, field, spin)

    def _spin(self, spec: params.ParameterSpec, value: int | None) -> QSpinBox:
        spin = QSpinBox()
        top = 0xFF if spec.layout == "u8" else 0xFFFF
        nullable = spec.id in (params.DEVICE_NODE_ID, params.OUT_NODE_ID) and spec.layout == "u8"
        spin.setRange(-1 if nullable else 0, top)
        if nullable:
            spin.setSpecialValueText(self.tr("not assigned"))
        spin.setValue(-1 if value is None else int(value))
        if spec.unit:
            spin.setSuffix(f" {spec.unit}")
        spin.setKeyboardTracking(False)
        return spin

    @staticmethod
    def _spin_value(spin: QSpinBox) -> int | None:
        return None if spin.value() < 0 else spin.value()

    # -- channels -------------------------------------------------------------------
    def _build_channel(self, box: QVBoxLayout, ref: ChannelRef, ch: Channel) -> None:
        from pdcp_studio.app.words.part_names import part_name

        d = self.doc.device(ref.device)
        name = self.doc.tree.name_of(ch.profile)
        head = (self.tr("Input {n}: {what}") if ch.is_input else
                self.tr("Output {n}: {what}")).format(n=ch.index, what=ch.descriptor or name)
        self._title(box, head, f"{part_name(self.doc.system, d.key)} · {name}")
        box.addWidget(self._links_summary(ref, ch))
        grid = self._plain_grid(box)
        holder = QVBoxLayout()
        box.addLayout(holder)
        self._detail_grid = self._details(holder)
        for spec in params.parameters_for(ch.direction):
            if spec.id not in _DETAIL_PARAMS:
                self._channel_row(grid, spec, ref, ch, d)
        self._row(self._detail_grid, None, self.tr("Profile code"), "profile_code",
                  _selectable(prof.fmt(ch.profile)), meta=self.tr("parameter 1, bytes 2–3"))
        for spec in params.parameters_for(ch.direction):
            if spec.id in _DETAIL_PARAMS:
                self._channel_row(self._detail_grid, spec, ref, ch, d)

    def _channel_row(self, grid: QGridLayout, spec: params.ParameterSpec, ref: ChannelRef,
                     ch: Channel, d: Device) -> None:
        pid = spec.id
        if pid == params.CH_TYPE_PROFILE:
            main, detail = self._type_editor(ref, ch)
            self._row(grid, None, self.tr("Control mode"), "type", main,
                      meta="parameter 1, byte 0–1")
            self._row(self._detail_grid, spec, self.tr("Channel type"), "type.detail", detail)
            self._row(grid, None, "Profile", "profile",
                      self._profile_editor(ref, "profile", ch.profile, allow_null=False),
                      meta="parameter 1, bytes 2–3")
            self.editors["profile"].setToolTip(self.tr("the profile (bytes 2–3 of parameter 1)"))
        elif pid == params.CH_DESCRIPTOR:
            edit = QLineEdit(ch.descriptor)
            edit.editingFinished.connect(
                lambda w=edit, s=spec: self._commit_channel(ref, "descriptor", w.text(), s))
            self._row(grid, spec, spec.name, "descriptor", edit)
        elif pid == params.CH_TRANSFER_TYPE:
            self._row(grid, spec, spec.name, "transfer_type", _selectable(
                f"{ch.direction.transfer_type} ({ch.direction.value})"))
        elif pid == params.CH_DATA_ENABLED:
            box = QCheckBox(self.tr("enabled"))
            box.setChecked(ch.data_enabled)
            box.toggled.connect(
                lambda on: self._commit_channel(ref, "data_enabled", bool(on), None))
            self._row(grid, spec, spec.name, "data_enabled", box)
        elif pid in (params.CH_REQUIRED_INPUTS, params.CH_DESIRED_INPUTS):
            field = "required_inputs" if pid == params.CH_REQUIRED_INPUTS else "desired_inputs"
            self._row(grid, spec, spec.name, field, self._inputs_list(ref, ch, d, field, spec))
        elif ch.is_input and pid == params.IN_TERMINAL_PROFILE:
            self._row(grid, spec, spec.name, "terminal_profile",
                      self._profile_editor(ref, "terminal_profile", ch.terminal_profile,
                                           allow_null=True))
        elif ch.is_output and pid == params.OUT_NODE_ID:
            spin = self._spin(spec, ch.node_id)
            spin.editingFinished.connect(
                lambda w=spin, s=spec: self._commit_channel(
                    ref, "node_id", self._spin_value(w), s))
            self._row(grid, spec, spec.name, "node_id", spin)
        else:
            self._row(grid, spec, spec.name, f"p{pid}", _selectable(self._source_text(ch, pid)))

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
        label = _selectable(text)
        return label

    def _describe(self, ref: ChannelRef) -> str:
        """``Multi-grip hand, channel 1 (Power grip)``: the graph's words for a channel."""
        from pdcp_studio.app.words.plan_words import channel_words

        ch = self.doc.system.channel(ref)
        name = self.doc.profile_name(ch.profile) if ch else ""
        return channel_words(self.doc.system, ref, "" if name.startswith("0x") else name)

    def _type_editor(self, ref: ChannelRef, ch: Channel) -> tuple[QWidget, QWidget]:
        """The channel type's editors: the control mode (what a prosthetist reads) and,
        for the Details section, its encoding: size, value type, prescaler code (the
        thesis's suggested factor a hint only, reference §2), sole access, terminal."""
        ct = ch.ctype
        w = QWidget()
        grid = QGridLayout(w)
        grid.setContentsMargins(0, 0, 0, 0)
        grid.setVerticalSpacing(2)
        size = QComboBox()
        size.addItems([f"{b}-bit" for b in BYTE_SIZE_BITS])
        size.setCurrentIndex(ct.byte_size_code)
        dtype = QComboBox()
        dtype.addItems([t.label for t in DataType])
        dtype.setCurrentIndex(int(ct.data_type))
        mode = QComboBox()
        mode.addItems([m.label for m in ControlMode])
        mode.setCurrentIndex(int(ct.control_mode))
        pres = QComboBox()
        pres.addItems([self.tr("code {code} (suggested ×{hint})").format(code=i, hint=h)
                       for i, h in enumerate(PRESCALER_HINTS)])
        pres.setToolTip(self.tr("The prescaler's raw 3-bit code; the factor is the thesis's "
                                "suggestion only and nothing is computed from it"))
        pres.setCurrentIndex(ct.prescaler)
        sole = QCheckBox(self.tr("sole access"))
        sole.setChecked(ct.sole_access)
        term = QCheckBox(self.tr("terminal"))
        term.setChecked(ct.terminal)
        if ch.is_output:
            sole.setToolTip(self.tr("sole access is a property of input channels"))
            term.setToolTip(self.tr("terminal is a property of input channels"))
        for combo in (size, dtype, mode, pres):
            combo.setSizeAdjustPolicy(
                QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
            combo.setMinimumContentsLength(6)
        hex_label = QLabel(f"= {ct}")
        hex_label.setStyleSheet(DIM_STYLE)
        grid.addWidget(size, 0, 0)
        grid.addWidget(dtype, 0, 1)
        grid.addWidget(pres, 1, 0, 1, 2)
        grid.addWidget(sole, 2, 0)
        grid.addWidget(term, 2, 1)
        grid.addWidget(hex_label, 3, 0, 1, 2)
        parts = {"type.bits": size, "type.data_type": dtype, "type.control_mode": mode,
                 "type.prescaler": pres, "type.sole_access": sole, "type.terminal": term}
        self.editors.update(parts)

        def commit() -> None:
            try:
                new = ct.replace(bits=BYTE_SIZE_BITS[size.currentIndex()],
                                 data_type=DataType(dtype.currentIndex()),
                                 control_mode=ControlMode(mode.currentIndex()),
                                 prescaler=pres.currentIndex(),
                                 sole_access=sole.isChecked(), terminal=term.isChecked())
            except ValueError as err:
                self._refuse("type", str(err))
                return
            self._commit_channel(ref, "type", new.value, None, "type")

        for combo in (size, dtype, mode, pres):
            combo.currentIndexChanged.connect(lambda _i: commit())
        for check in (sole, term):
            check.toggled.connect(lambda _on: commit())
        return mode, w

    def _tree_items(self) -> dict[str, int]:
        """The tree's profiles by name (``Terminal device › Hand › Power Grip``); the code is
        in each entry's tooltip, and in the name only where two profiles share a name."""
        named = [(self.doc.tree.name_of(value), value) for value, _node in self.doc.tree.walk()]
        times = Counter(name for name, _value in named)
        return {name if times[name] == 1 else f"{name} ({prof.fmt(value)})": value
                for name, value in named}

    def _profile_editor(self, ref: ChannelRef, field: str, value: int, *,
                        allow_null: bool) -> QComboBox:
        items = self._tree_items()
        combo = QComboBox()
        combo.setEditable(True)
        combo.setInsertPolicy(QComboBox.InsertPolicy.NoInsert)
        combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        combo.setMinimumContentsLength(14)
        none = self.tr("(none)")
        if allow_null:
            combo.addItem(none, 0)
            items[none] = 0
        current = next((t for t, v in items.items() if v == value), None)
        if current is None:  # not in the tree: named so, its code in the tooltip and details
            current = self.tr("Not in the profile tree")
            items = {current: value, **items}
            combo.addItem(current, value)
        for text, v in items.items():
            if (v or not allow_null) and combo.findText(text) < 0:
                combo.addItem(text, v)
        for i in range(combo.count()):
            combo.setItemData(i, self.tr("Profile code {code}").format(
                code=prof.fmt(combo.itemData(i))), Qt.ItemDataRole.ToolTipRole)
        combo.setCurrentText(current)
        combo.lineEdit().setCursorPosition(0)  # the start of the name, not its tail
        combo.lineEdit().setToolTip(
            self.tr("{name}: profile code {code} (parameter 1, bytes 2–3).\nChoose a profile "
                    "of the named tree or type one in hex.").format(name=current,
                                                                    code=prof.fmt(value))
        )

        def commit() -> None:
            if self._building:
                return
            try:
                new = parse_profile(combo.currentText(), items, allow_null=allow_null)
            except ValueError as err:
                self._refuse(field, str(err))
                return
            self._commit_channel(ref, field, new, None, field)

        combo.lineEdit().editingFinished.connect(commit)
        combo.activated.connect(lambda _i: commit())
        return combo

    def _inputs_list(self, ref: ChannelRef, ch: Channel, d: Device, field: str,
                     spec: params.ParameterSpec) -> QListWidget:
        lst = QListWidget()
        chosen = set(getattr(ch, field))
        inputs = sorted(d.inputs(), key=lambda c: c.index)
        for inp in inputs:
            item = QListWidgetItem(f"#{inp.index} {inp.descriptor or ''} "
                                   f"({self.doc.profile_name(inp.profile)})".replace("  ", " "))
            item.setData(Qt.ItemDataRole.UserRole, inp.index)
            item.setFlags(item.flags() | Qt.ItemFlag.ItemIsUserCheckable)
            item.setCheckState(Qt.CheckState.Checked if inp.index in chosen
                               else Qt.CheckState.Unchecked)
            lst.addItem(item)
        if not inputs:
            lst.addItem("(this device has no input channels)")
            lst.setEnabled(False)
        lst.setMaximumHeight(22 * max(1, min(len(inputs), 5)) + 6)

        def commit(_item: QListWidgetItem) -> None:
            if self._building:
                return
            picked = [lst.item(i).data(Qt.ItemDataRole.UserRole) for i in range(lst.count())
                      if lst.item(i).checkState() == Qt.CheckState.Checked]
            self._commit_channel(ref, field, tuple(picked), spec, field)

        lst.itemChanged.connect(commit)
        return lst

    # -- links ----------------------------------------------------------------------
    def _build_link(self, box: QVBoxLayout, link: Link) -> None:
        self._title(
            box, self.tr("Link"), f"{self._describe(link.output)}\n→ {self._describe(link.input)}"
        )
        out = self.doc.system.channel(link.output)
        inp = self.doc.system.channel(link.input)
        if out is not None and inp is not None:
            from pdcp_studio.engine.similarity import determine_similarity

            sim = determine_similarity(out.type, out.profile, inp.type, inp.profile)
            box.addWidget(_selectable(f"Similarity {sim.describe()}"))
        row = QHBoxLayout()
        delete = QPushButton(self.tr("Delete link"))
        delete.clicked.connect(lambda: self._delete_link(link))
        row.addWidget(delete)
        row.addStretch(1)
        box.addLayout(row)
        self.editors["delete"] = delete

    def _delete_link(self, link: Link) -> None:
        if commands.push_remove_links(self.doc, [link]):
            self.statusMessage.emit(self.tr("Removed link {link}").format(link=link))

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
