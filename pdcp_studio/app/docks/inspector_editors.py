"""The inspector's editors, one builder per kind of parameter: a number (spin box), a
channel type (its control mode, and its encoding for the Details section), a profile
(chosen from the named tree or typed in hex) and a set of inputs (a checkable list).

Each editor hands a value it was given to ``commit(ref, field, value, spec)``; one it
cannot even read goes to ``refuse(field, reason)``. Neither fires while ``building()``.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable
from typing import Any

from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QGridLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QListWidgetItem,
    QSpinBox,
    QWidget,
)

from pdcp_studio.app.docks.inspector_form import DIM_STYLE
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.i18n import translate
from pdcp_studio.model import parameters as params
from pdcp_studio.model import profile as prof
from pdcp_studio.model.channel_type import (
    BYTE_SIZE_BITS,
    PRESCALER_HINTS,
    ControlMode,
    DataType,
)
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Channel, Device

#: ``commit(ref, field, value, spec)``: check and push one channel edit; True if pushed.
Commit = Callable[[ChannelRef, str, Any, params.ParameterSpec | None], bool]


def _tr(text: str) -> str:
    return translate("Inspector", text)


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


def spin_box(spec: params.ParameterSpec, value: int | None) -> QSpinBox:
    """A number parameter's editor (a node ID may be "not assigned": -1)."""
    spin = QSpinBox()
    top = 0xFF if spec.layout == "u8" else 0xFFFF
    nullable = spec.id in (params.DEVICE_NODE_ID, params.OUT_NODE_ID) and spec.layout == "u8"
    spin.setRange(-1 if nullable else 0, top)
    if nullable:
        spin.setSpecialValueText(_tr("not assigned"))
    spin.setValue(-1 if value is None else int(value))
    if spec.unit:
        spin.setSuffix(f" {spec.unit}")
    spin.setKeyboardTracking(False)
    return spin


def spin_value(spin: QSpinBox) -> int | None:
    return None if spin.value() < 0 else spin.value()


class ChannelEditors:
    """Editors of one channel form (``editors``: the inspector's table by field name)."""

    def __init__(self, doc: Document, editors: dict[str, QWidget], commit: Commit,
                 refuse: Callable[[str, str], None], building: Callable[[], bool]) -> None:
        self._doc = doc
        self._editors = editors
        self._commit = commit
        self._refuse = refuse
        self._building = building

    def type_editor(self, ref: ChannelRef, ch: Channel) -> tuple[QWidget, QWidget]:
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
        pres.addItems([_tr("code {code} (suggested ×{hint})").format(code=i, hint=h)
                       for i, h in enumerate(PRESCALER_HINTS)])
        pres.setToolTip(_tr("The prescaler's raw 3-bit code; the factor is the thesis's "
                            "suggestion only and nothing is computed from it"))
        pres.setCurrentIndex(ct.prescaler)
        sole = QCheckBox(_tr("sole access"))
        sole.setChecked(ct.sole_access)
        term = QCheckBox(_tr("terminal"))
        term.setChecked(ct.terminal)
        if ch.is_output:
            sole.setToolTip(_tr("sole access is a property of input channels"))
            term.setToolTip(_tr("terminal is a property of input channels"))
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
        parts: dict[str, QWidget] = {
            "type.bits": size, "type.data_type": dtype, "type.control_mode": mode,
            "type.prescaler": pres, "type.sole_access": sole, "type.terminal": term}
        self._editors.update(parts)

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
            self._commit(ref, "type", new.value, None)

        for combo in (size, dtype, mode, pres):
            combo.currentIndexChanged.connect(lambda _i: commit())
        for check in (sole, term):
            check.toggled.connect(lambda _on: commit())
        return mode, w

    def tree_items(self) -> dict[str, int]:
        """The tree's profiles by name (``Terminal device › Hand › Power Grip``); the code is
        in each entry's tooltip, and in the name only where two profiles share a name."""
        tree = self._doc.tree
        named = [(tree.name_of(value), value) for value, _node in tree.walk()]
        times = Counter(name for name, _value in named)
        return {name if times[name] == 1 else f"{name} ({prof.fmt(value)})": value
                for name, value in named}

    def profile_editor(self, ref: ChannelRef, field: str, value: int, *,
                       allow_null: bool) -> QComboBox:
        items = self.tree_items()
        combo = QComboBox()
        combo.setEditable(True)
        combo.setInsertPolicy(QComboBox.InsertPolicy.NoInsert)
        combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        combo.setMinimumContentsLength(14)
        none = _tr("(none)")
        if allow_null:
            combo.addItem(none, 0)
            items[none] = 0
        current = next((t for t, v in items.items() if v == value), None)
        if current is None:  # not in the tree: named so, its code in the tooltip and details
            current = _tr("Not in the profile tree")
            items = {current: value, **items}
            combo.addItem(current, value)
        for text, v in items.items():
            if (v or not allow_null) and combo.findText(text) < 0:
                combo.addItem(text, v)
        for i in range(combo.count()):
            combo.setItemData(i, _tr("Profile code {code}").format(
                code=prof.fmt(combo.itemData(i))), Qt.ItemDataRole.ToolTipRole)
        combo.setCurrentText(current)
        line = combo.lineEdit()
        assert isinstance(line, QLineEdit)  # an editable combo box has one
        line.setCursorPosition(0)  # the start of the name, not its tail
        line.setToolTip(
            _tr("{name}: profile code {code} (parameter 1, bytes 2–3).\nChoose a profile "
                "of the named tree or type one in hex.").format(name=current,
                                                                code=prof.fmt(value))
        )

        def commit() -> None:
            if self._building():
                return
            try:
                new = parse_profile(combo.currentText(), items, allow_null=allow_null)
            except ValueError as err:
                self._refuse(field, str(err))
                return
            self._commit(ref, field, new, None)

        line.editingFinished.connect(commit)
        combo.activated.connect(lambda _i: commit())
        return combo

    def inputs_list(self, ref: ChannelRef, ch: Channel, d: Device, field: str,
                    spec: params.ParameterSpec) -> QListWidget:
        """Required or desired inputs: the device's inputs, the chosen ones checked."""
        lst = QListWidget()
        chosen = set(getattr(ch, field))
        inputs = sorted(d.inputs(), key=lambda c: c.index)
        for inp in inputs:
            item = QListWidgetItem(f"#{inp.index} {inp.descriptor or ''} "
                                   f"({self._doc.profile_name(inp.profile)})".replace("  ", " "))
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
            if self._building():
                return
            picked = [lst.item(i).data(Qt.ItemDataRole.UserRole) for i in range(lst.count())
                      if lst.item(i).checkState() == Qt.CheckState.Checked]
            self._commit(ref, field, tuple(picked), spec)

        lst.itemChanged.connect(commit)
        return lst
