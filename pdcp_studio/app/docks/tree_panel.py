"""The device/channel tree beside the graph, its selection in step with the document.

Top level: one row per device (name, VID/PID/serial, role; grey when missing); children:
its channels (index, direction, profile name, hex). Clicking a row selects that device or
channel in the document, and the graph follows; selecting on the graph selects the row.
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtGui import QBrush, QColor
from PySide6.QtWidgets import QAbstractItemView, QHeaderView, QTreeWidget, QTreeWidgetItem, QWidget

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph import style
from pdcp_studio.app.graph.analysis import ROLE_LAYER, device_role
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.words.part_names import (
    keep_serials_seen,
    names,
    numbers,
    part_name,
)
from pdcp_studio.model import profile as prof
from pdcp_studio.model.names import Names
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link

ROLE = Qt.ItemDataRole.UserRole
#: What a device's rows show: its name, own name, descriptor, presence, role, and per
#: channel (index, is an output, descriptor, profile name).
RowSignature = tuple[str, str, str, bool, str, tuple[tuple[int, bool, str, str], ...]]


class DeviceTree(QTreeWidget):
    """Devices and channels of the document's system."""

    def __init__(self, doc: Document, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        keep_serials_seen(self)  # a twin's serial number stays seen in a narrow column
        self.doc = doc
        self.setColumnCount(2)
        self.setHeaderLabels([self.tr("Device / channel"), self.tr("Profile")])
        self.setSelectionMode(QAbstractItemView.SelectionMode.SingleSelection)
        self.setUniformRowHeights(True)
        self.setMinimumWidth(290)  # device names and profile names side by side
        self.setAlternatingRowColors(True)
        header = self.header()
        header.setStretchLastSection(False)
        header.setSectionResizeMode(0, QHeaderView.ResizeMode.Stretch)
        header.setSectionResizeMode(1, QHeaderView.ResizeMode.ResizeToContents)
        self._rows: dict[object, QTreeWidgetItem] = {}
        self._signatures: dict[DeviceKey, RowSignature] = {}
        self._names: dict[DeviceKey, str] = {}
        self._syncing = False
        doc.systemReset.connect(self.rebuild)
        doc.deviceChanged.connect(self._on_device_changed)
        doc.channelChanged.connect(lambda ref: self._on_device_changed(ref.device))
        doc.selectionChanged.connect(self._on_doc_selection)
        self.itemSelectionChanged.connect(self._on_tree_selection)
        self.rebuild()

    def rebuild(self) -> None:
        """Recreate every row (a new system)."""
        self._syncing = True
        try:
            self.clear()
            self._rows.clear()
            self._signatures.clear()
            naming = names(self.doc.system)  # once: each lookup reads the whole system
            self._names = naming.parts()
            for key in self.ordered_keys():
                self.addTopLevelItem(self._device_row(key, naming))
            self.expandAll()
            self._select_row(self.doc.selection)
        finally:
            self._syncing = False

    def ordered_keys(self) -> list[DeviceKey]:
        """Sensors, then control, then terminal devices; within a role top to bottom as on
        the graph (the order of the cards' remembered positions)."""
        devices, pos = self.doc.system.devices, self.doc.positions
        return sorted(devices, key=lambda k: (ROLE_LAYER[device_role(devices[k])],
                                              pos.get(k, (0.0, 0.0))[1],
                                              devices[k].label.lower(), k))

    def _device_row(self, key: DeviceKey, naming: Names) -> QTreeWidgetItem:
        """The device's row and its channels' rows, named by ``naming`` (the system's)."""
        device = self.doc.system.devices[key]
        role = device_role(device)
        name = naming.part(key)
        item = QTreeWidgetItem([name,
                                self.tr("missing") if not device.present
                                else translate("Style", str(style.ROLE_LABELS[role]))])
        item.setData(0, ROLE, key)
        self._signatures[key] = self._shown(key, name)
        item.setToolTip(0, numbers(key))
        from pdcp_studio.app.widgets.kind_icons import icon_for

        item.setIcon(0, icon_for(key))
        colour = style.MISSING_TEXT if not device.present else style.ROLE_COLOURS[role]
        item.setForeground(1, QBrush(colour))
        if not device.present:
            item.setForeground(0, QBrush(style.MISSING_TEXT))
        self._rows[key] = item
        channels = sorted(device.channels.values(), key=lambda c: (c.is_output, c.index))
        for ch in channels:
            ref = device.ref(ch.index)
            arrow = "→" if ch.is_output else "←"
            # The channel's one name (descriptor, else profile name), as the graph's row.
            profile = self.doc.profile_name(ch.profile)
            name = naming.channel_only(ref, profile)
            child = QTreeWidgetItem([f"{arrow} #{ch.index} {name}", profile])
            child.setToolTip(1, f"{self.doc.tree.name_of(ch.profile)} {prof.fmt(ch.profile)}")
            child.setData(0, ROLE, ref)
            if not device.present:
                child.setForeground(0, QBrush(style.MISSING_TEXT))
                child.setForeground(1, QBrush(style.MISSING_TEXT))
            else:
                child.setForeground(1, QBrush(QColor(style.TEXT_DIM)))
            item.addChild(child)
            self._rows[ref] = child
        return item

    def _shown(self, key: DeviceKey, name: str | None = None) -> RowSignature:
        """What a device's rows show (a live snapshot reports every device as changed;
        rows are made again only when this differs); ``name``: its part name, when known."""
        d = self.doc.system.devices[key]
        if name is None:
            name = part_name(self.doc.system, key)
        return (name, d.name, d.descriptor, d.present, device_role(d),
                tuple((c.index, c.is_output, c.descriptor, self.doc.profile_name(c.profile))
                      for c in sorted(d.channels.values(), key=lambda c: c.index)))

    def _on_device_changed(self, key: DeviceKey) -> None:
        old = self._rows.get(key)
        if old is None or key not in self.doc.system.devices:
            self.rebuild()
            return
        if self._signatures.get(key) == self._shown(key):
            return
        naming = names(self.doc.system)
        now = naming.parts()
        if any(now.get(k) != n for k, n in self._names.items() if k != key):
            self.rebuild()  # a renamed part changed another's name (two now read alike)
            return
        self._names = now
        self._syncing = True
        try:
            index = self.indexOfTopLevelItem(old)
            for ref in [r for r in self._rows if isinstance(r, ChannelRef) and r.device == key]:
                del self._rows[ref]
            self.takeTopLevelItem(index)
            row = self._device_row(key, naming)
            self.insertTopLevelItem(index, row)
            row.setExpanded(True)
            self._select_row(self.doc.selection)
        finally:
            self._syncing = False

    def row_for(self, obj: object) -> QTreeWidgetItem | None:
        if isinstance(obj, Link):
            obj = obj.input
        return self._rows.get(obj)

    def _select_row(self, obj: object) -> None:
        row = self.row_for(obj)
        self.clearSelection()
        if row is not None:
            row.setSelected(True)
            self.scrollToItem(row)

    def _on_doc_selection(self, obj: object) -> None:
        if self._syncing:
            return
        self._syncing = True
        try:
            self._select_row(obj)
        finally:
            self._syncing = False

    def _on_tree_selection(self) -> None:
        if self._syncing:
            return
        items = self.selectedItems()
        self._syncing = True
        try:
            self.doc.select(items[0].data(0, ROLE) if items else None)
        finally:
            self._syncing = False
