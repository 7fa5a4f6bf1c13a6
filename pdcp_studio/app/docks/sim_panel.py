"""The simulator panel: plug, unplug and replace simulated devices, reset the arbitrator and
run scripted events, so a hot-swap can be watched on the graph as it happens.

Public API
    ``SimPanel(bridge, parent=None)`` — a QWidget (dock it with ``SimPanel.as_dock()``) over a
    ``SessionBridge`` of a ``sim:`` session. Every control goes through the bridge (off the GUI
    thread, one at a time); the device list is refreshed after each control and follows the
    bridge's ``deviceJoined`` / ``deviceLeft`` (the "On bus" column and the event log).
    Methods: ``refresh() -> Worker | None``, ``select(key)``, ``selected_key()``,
    ``plug_selected()``, ``unplug_selected()``, ``replace_selected(new_key)``,
    ``reset(keep_memory)``, ``save_links()``, ``run_script(name)``, ``state(key)`` →
    ``(plugged, on_bus)``, ``log_lines() -> list[str]``.
    Signals: ``message(str)`` — one line for a status bar (also in the panel's log).
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QBrush, QColor
from PySide6.QtWidgets import (
    QComboBox,
    QDockWidget,
    QGridLayout,
    QGroupBox,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QListWidget,
    QPushButton,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.widgets.combo_popups import keep_whole
from pdcp_studio.app.widgets.tree_items import set_current, top_level_items
from pdcp_studio.app.workers import Worker
from pdcp_studio.bus.session.capabilities import SimulatorControls
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Device

if TYPE_CHECKING:
    from pdcp_studio.app.live.session_bridge import SessionBridge
    from pdcp_studio.bus.sim.rigs import ScriptResult

KEY_ROLE = Qt.ItemDataRole.UserRole
COL_NAME, COL_KEY, COL_PLUGGED, COL_BUS = range(4)
MAX_LOG = 500
_GONE = QColor(150, 150, 150)

#: The simulator's scripts (``bus/sim/rigs.py``) in the user's words: their names, and what
#: each does (the rigs hold them in English, as data for the CLI's ``sim`` commands).
_SCRIPTS = "SimScripts"
SCRIPT_NAMES = {
    "start-up": QT_TRANSLATE_NOOP(_SCRIPTS, "Start-up"),
    "thesis": QT_TRANSLATE_NOOP(_SCRIPTS, "Thesis test"),
    "hot-swap": QT_TRANSLATE_NOOP(_SCRIPTS, "Swap while running"),
    "unplug-replug": QT_TRANSLATE_NOOP(_SCRIPTS, "Unplug and plug back in"),
    "reset-keep-memory": QT_TRANSLATE_NOOP(_SCRIPTS, "Reset, keep memory"),
    "reset-erase-memory": QT_TRANSLATE_NOOP(_SCRIPTS, "Reset, erase memory"),
}
SCRIPT_DESCRIPTIONS = (
    QT_TRANSLATE_NOOP(_SCRIPTS, "power on: the arbitrator binds, sets up and runs start-up"),
    QT_TRANSLATE_NOOP(_SCRIPTS, "Test 1: D1.O1 → D2.I1 autoconfigured and stored; D2 is "
                                "replaced by D3 and the prosthesis restarts: "
                                "find_replacements links D1.O1 → D3.I1"),
    QT_TRANSLATE_NOOP(_SCRIPTS, "Test 1 without a restart: D2 is pulled and D3 plugged in "
                                "while running; the duty cycle repairs the link"),
    QT_TRANSLATE_NOOP(_SCRIPTS, "Test 2: no stored configuration: autoconfigure (appendix "
                                "D's links)"),
    QT_TRANSLATE_NOOP(_SCRIPTS, "Test 3: configure, save, reset the arbitrator keeping its "
                                "memory: start-up recalls the stored configuration"),
    QT_TRANSLATE_NOOP(_SCRIPTS, "Test 4: D1.O1 → D3.I2 autoconfigured and stored; D1 is "
                                "replaced by D2 and the prosthesis restarts: "
                                "find_replacements links D2.O2 → D3.I2"),
    QT_TRANSLATE_NOOP(_SCRIPTS, "Test 4 without a restart: D1 is pulled and D2 plugged in "
                                "while running"),
    QT_TRANSLATE_NOOP(_SCRIPTS, "Test 5: configure, then reset the arbitrator with its "
                                "memory erased (a replaced arbitrator): start-up rebuilds the "
                                "links from the devices' source fields"),
    QT_TRANSLATE_NOOP(_SCRIPTS, "reset the arbitrator keeping its memory"),
    QT_TRANSLATE_NOOP(_SCRIPTS, "reset the arbitrator with its memory erased: rebuild from "
                                "devices"),
)
_REPLUG = re.compile(r"pull (\d+)/(\d+)/(\d+) and plug it back in: .*")
REPLUG_WORDS = QT_TRANSLATE_NOOP(_SCRIPTS, "pull {device} and plug it back in: it keeps its "
                                           "sources and the arbitrator links it again")


def script_name_words(name: str) -> str:
    """A script's name as the panel shows it (an unknown one, e.g. from a file, as it is)."""
    words = SCRIPT_NAMES.get(name)
    return translate(_SCRIPTS, words) if words else name


def script_words(description: str, name_of: Callable[[DeviceKey], str]) -> str:
    """What a script does, in the user's language (its parts by name)."""
    replug = _REPLUG.fullmatch(description)
    if replug is not None:
        key = DeviceKey(*(int(n) for n in replug.groups()))
        return translate(_SCRIPTS, REPLUG_WORDS).format(device=name_of(key))
    return translate(_SCRIPTS, description) if description in SCRIPT_DESCRIPTIONS \
        else description


#: ``name_of(key)``: the name the graph shows for a part (None: it is not on the graph).
NameOf = Callable[[DeviceKey], "str | None"]
#: One simulated device as the simulator lists it: (key, its label, powered).
SimDevice = tuple[DeviceKey, str, bool]


def default_name(key: DeviceKey) -> str:
    """A part the panel does not list: by its one name (as last named, else its product)."""
    from pdcp_studio.app.words.part_names import part_name

    return part_name(None, key)


def _bus_name(key: DeviceKey, model: Device | None, label: str) -> str:
    """What the graph will call a simulated device once it is on the bus: the name it
    tells the bus (its descriptor, else its own name, as ``bus/sim/device.py`` answers),
    else its product from the catalogue. The simulator's label for a part that tells a
    descriptor ("Spare hand" beside the hand's descriptor) is never read from the bus, so
    it is not the part's name."""
    from pdcp_studio.model.catalog import default_catalog

    catalog = default_catalog()
    if model is not None:
        own = (model.descriptor or model.name or "").strip()
        return own or catalog.product_name(key) or catalog.label(key)
    own = "" if label in (str(key), f"Device {key}") else label
    return catalog.product_name(key) or catalog.label(key, own)


def sim_names(keys_labels: list[tuple[DeviceKey, str]], name_of: NameOf | None,
              models: dict[DeviceKey, Device]) -> dict[DeviceKey, str]:
    """The Simulator panel's names: the graph's name for a part on it (``name_of``); for
    the others the name the graph will give them (:func:`_bus_name`), with the serial
    number where it would read like another part's (the spare hand beside the hand)."""
    from pdcp_studio.app.words.part_names import twin_format

    shown = {k: name_of(k) for k, _lb in keys_labels} if name_of is not None else {}
    names = {k: n for k, n in shown.items() if n}
    rest = {k: _bus_name(k, models.get(k), lb) for k, lb in keys_labels if k not in names}
    taken = list(names.values()) + list(rest.values())
    for k, base in rest.items():
        names[k] = (twin_format().format(name=base, serial=k.serial)
                    if taken.count(base) > 1 else base)
    return {k: names[k] for k, _lb in keys_labels}


class SimPanel(QWidget):
    """Simulator controls for a simulated prosthesis (see the module docstring)."""

    message = Signal(str)

    def __init__(self, bridge: SessionBridge, parent: QWidget | None = None,
                 name_of: NameOf | None = None) -> None:
        super().__init__(parent)
        self.bridge = bridge
        #: ``name_of(key) -> str | None``: the name the graph shows (None: not on it).
        self.name_of = name_of
        self._devices: dict[DeviceKey, tuple[str, bool]] = {}
        self._on_bus: dict[DeviceKey, bool] = {}
        self._raw: list[SimDevice] | None = None  # the simulator's last list, as it came

        self.tree = QTreeWidget()
        self.tree.setHeaderLabels(
            [self.tr("Device"), self.tr("Product"), self.tr("Power"), self.tr("On bus")]
        )
        self.tree.setRootIsDecorated(False)
        from pdcp_studio.app.words.part_names import keep_serials_seen

        keep_serials_seen(self.tree)  # a twin's serial number stays seen in a narrow column
        header = self.tree.header()  # the name takes the room the other columns leave
        header.setStretchLastSection(False)
        header.setSectionResizeMode(COL_NAME, QHeaderView.ResizeMode.Stretch)
        for col in (COL_KEY, COL_PLUGGED, COL_BUS):
            header.setSectionResizeMode(col, QHeaderView.ResizeMode.ResizeToContents)
        self.tree.currentItemChanged.connect(lambda *_: self._update_buttons())

        self.plug_button = QPushButton(self.tr("Plug in"))
        self.unplug_button = QPushButton(self.tr("Unplug"))
        self.replace_combo = QComboBox()
        self.replace_combo.setToolTip(self.tr("An unplugged simulated device to put in its place"))
        self.replace_button = QPushButton(self.tr("Replace by"))
        self.reset_keep_button = QPushButton(self.tr("Reset arbitrator"))
        self.reset_keep_button.setToolTip(
            self.tr("Restart the arbitrator; its stored configuration is kept, start-up recalls it")
        )
        self.reset_erase_button = QPushButton(self.tr("Reset, erase memory"))
        self.reset_erase_button.setToolTip(
            self.tr(
                "A replaced arbitrator: start-up rebuilds the links from what the devices store"
            )
        )
        self.save_button = QPushButton(self.tr("Store links"))
        self.save_button.setToolTip(
            self.tr("Store the current links as the arbitrator's configuration")
        )
        self.script_combo = QComboBox()
        self.script_button = QPushButton(self.tr("Run script"))
        self.script_info = QLabel()
        self.script_info.setWordWrap(True)
        self.log = QListWidget()
        self.log.setUniformItemSizes(True)

        self.plug_button.clicked.connect(self.plug_selected)
        self.unplug_button.clicked.connect(self.unplug_selected)
        self.replace_button.clicked.connect(
            lambda: self.replace_selected(self.replace_combo.currentData()))
        self.reset_keep_button.clicked.connect(lambda: self.reset(True))
        self.reset_erase_button.clicked.connect(lambda: self.reset(False))
        self.save_button.clicked.connect(self.save_links)
        self.script_button.clicked.connect(
            lambda: self.run_script(str(self.script_combo.currentData() or "")))
        self.script_combo.currentIndexChanged.connect(
            lambda _i: self._describe_script(str(self.script_combo.currentData() or "")))

        devices = QGroupBox(self.tr("Devices"))
        grid = QGridLayout(devices)
        grid.addWidget(self.tree, 0, 0, 1, 4)
        grid.addWidget(self.plug_button, 1, 0)
        grid.addWidget(self.unplug_button, 1, 1)
        grid.addWidget(self.replace_button, 1, 2)
        grid.addWidget(self.replace_combo, 2, 0, 1, 4)  # a row of its own: the whole name
        keep_whole(self.replace_combo)
        keep_whole(self.script_combo)
        arbitrator = QGroupBox(self.tr("Arbitrator"))
        row = QHBoxLayout(arbitrator)
        for w in (self.reset_keep_button, self.reset_erase_button, self.save_button):
            row.addWidget(w)
        scripts = QGroupBox(self.tr("Scripted events"))
        script_box = QVBoxLayout(scripts)
        line = QHBoxLayout()
        line.addWidget(self.script_combo, 1)
        line.addWidget(self.script_button)
        script_box.addLayout(line)
        script_box.addWidget(self.script_info)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(4, 4, 4, 4)
        layout.addWidget(devices, 3)
        layout.addWidget(arbitrator)
        layout.addWidget(scripts)
        layout.addWidget(QLabel(self.tr("Events")))
        layout.addWidget(self.log, 2)

        # Bound methods only: Qt drops them with the panel, which may go before the bridge.
        bridge.deviceJoined.connect(self._joined)
        bridge.deviceLeft.connect(self._left)
        bridge.simDevices.connect(self._show_devices)
        bridge.simChanged.connect(self._sim_changed)
        bridge.namer = lambda key: self._label(DeviceKey(*key))
        bridge.scriptFinished.connect(self._script_finished)
        bridge.busyChanged.connect(self._busy_changed)
        bridge.error.connect(self._error)
        for name in bridge.script_names():
            self.script_combo.addItem(script_name_words(name), name)
        self._initial_presence()
        self.refresh()

    def as_dock(self, parent: QWidget | None = None) -> QDockWidget:
        """This panel in a dock widget titled "Simulator"."""
        dock = QDockWidget(self.tr("Simulator"), parent)
        dock.setObjectName("SimulatorDock")
        dock.setWidget(self)
        return dock

    # -- state -----------------------------------------------------------------------------
    def _initial_presence(self) -> None:
        try:
            system = self.bridge.system()
        except Exception:  # a closed session: the list stays empty until a refresh
            return
        self._on_bus = {key: dev.present for key, dev in system.devices.items()}

    def refresh(self) -> Worker | None:
        """Ask the simulator for its devices (the list updates when they arrive)."""
        return self.bridge.refresh_sim_devices()

    def state(self, key: DeviceKey) -> tuple[bool | None, bool | None]:
        """(powered, on the bus as the arbitrator sees it); None where unknown."""
        entry = self._devices.get(key)
        return (None if entry is None else entry[1]), self._on_bus.get(key)

    def selected_key(self) -> DeviceKey | None:
        """The key of the selected simulated device, or None."""
        item = self.tree.currentItem()
        return None if item is None else self._key_of(item)

    @staticmethod
    def _key_of(item: QTreeWidgetItem) -> DeviceKey:
        key: DeviceKey = item.data(COL_NAME, KEY_ROLE)
        return key

    def select(self, key: DeviceKey | None) -> None:
        """Select the row of ``key`` (None or unknown: no selection)."""
        rows = (item for item in top_level_items(self.tree) if self._key_of(item) == key)
        set_current(self.tree, next(rows, None))

    def unplugged(self) -> list[tuple[DeviceKey, str]]:
        """The simulated devices that can be plugged in now, with the names shown here."""
        return [(key, name) for key, (name, plugged) in self._devices.items() if not plugged]

    def log_lines(self) -> list[str]:
        """The event log's lines, oldest first."""
        return [self.log.item(i).text() for i in range(self.log.count())]

    def relabel(self) -> None:
        """Name the devices again (the graph's names changed: a new snapshot of the bus)."""
        raw = self._raw
        if raw is not None:
            if self._names(raw) != {k: v[0] for k, v in self._devices.items()}:
                self._show_devices(raw)

    def _names(self, devices: list[SimDevice]) -> dict[DeviceKey, str]:
        """Every simulated device's name (:func:`sim_names`)."""
        session = self.bridge.session
        models = dict(session.initial_system.devices) if isinstance(
            session, SimulatorControls) else {}
        return sim_names([(DeviceKey(*k), str(lb)) for k, lb, _p in devices], self.name_of,
                         models)

    def _label(self, key: DeviceKey) -> str:
        entry = self._devices.get(key)
        return entry[0] if entry else default_name(key)

    def _log(self, text: str) -> None:
        self.log.addItem(f"{time.strftime('%H:%M:%S')}  {text}")
        while self.log.count() > MAX_LOG:
            self.log.takeItem(0)
        self.log.scrollToBottom()
        self.message.emit(text)

    # -- bridge signals ----------------------------------------------------------------
    def _show_devices(self, devices: list[SimDevice]) -> None:
        selected = self.selected_key()
        self._raw = list(devices)
        names = self._names(self._raw)
        self._devices = {DeviceKey(*key): (names[DeviceKey(*key)], bool(plugged))
                         for key, _label, plugged in devices}
        self.tree.clear()
        for key, (label, _plugged) in self._devices.items():
            item = QTreeWidgetItem(self.tree)
            item.setData(COL_NAME, KEY_ROLE, key)
            item.setText(COL_NAME, label)
            item.setToolTip(COL_NAME, label)  # whole, when the column is narrower
            from pdcp_studio.app.widgets.kind_icons import entry_of
            from pdcp_studio.app.words.part_names import numbers

            entry = entry_of(key)  # the numbers are the engineer's: in the tooltip
            item.setText(COL_KEY, entry.product if entry is not None else self.tr("unknown"))
            item.setToolTip(COL_KEY, numbers(key))
            self._paint(item, key)
        self._fill_replacements()
        self.select(selected)
        self._update_buttons()

    def _paint(self, item: QTreeWidgetItem, key: DeviceKey) -> None:
        plugged, on_bus = self.state(key)
        item.setText(COL_PLUGGED, self.tr("on") if plugged else self.tr("off"))
        item.setText(COL_BUS, {True: self.tr("joined"), False: self.tr("left"),
                               None: "—"}[on_bus])
        brush = QBrush(_GONE) if not plugged else QBrush()
        for col in range(4):
            item.setForeground(col, brush)

    def _joined(self, key: DeviceKey) -> None:
        self._presence(key, True)

    def _left(self, key: DeviceKey) -> None:
        self._presence(key, False)

    def _busy_changed(self, _busy: bool) -> None:
        self._update_buttons()

    def _error(self, message: str) -> None:
        self._log(self.tr("Problem: {message}").format(message=message))

    def _presence(self, key: DeviceKey, joined: bool) -> None:
        key = DeviceKey(*key)
        self._on_bus[key] = joined
        self._log((self.tr("{device} joined the bus") if joined else
                   self.tr("{device} left the bus")).format(device=self._label(key)))
        for item in top_level_items(self.tree):
            if self._key_of(item) == key:
                self._paint(item, key)

    def _sim_changed(self, what: str) -> None:
        self._log(what)  # the bridge's sentence, with the part's name
        self.refresh()

    def _script_finished(self, result: ScriptResult) -> None:
        name = script_name_words(result.script.name)
        if result.ok:
            self._log(self.tr("Script {name}: ended in the expected links").format(name=name))
        else:
            self._log(self.tr("Script {name}: the links differ from the expected ones — {diff}")
                      .format(name=name, diff=result.mismatch()))

    def _fill_replacements(self) -> None:
        from pdcp_studio.app.words.part_names import numbers

        current = self.replace_combo.currentData()
        self.replace_combo.clear()
        for key, (label, plugged) in self._devices.items():
            if not plugged:
                self.replace_combo.addItem(label, key)
                self.replace_combo.setItemData(self.replace_combo.count() - 1,
                                               f"{label}\n{numbers(key)}",
                                               Qt.ItemDataRole.ToolTipRole)
        index = self.replace_combo.findData(current)
        if index >= 0:
            self.replace_combo.setCurrentIndex(index)

    def _describe_script(self, name: str) -> None:
        description = ""
        session = self.bridge.session
        if isinstance(session, SimulatorControls) and name:
            try:
                description = session.prosthesis.script(name).description
            except Exception:
                description = ""
        self.script_info.setText(script_words(description, self._label))

    def _update_buttons(self) -> None:
        key = self.selected_key()
        plugged = self.state(key)[0] if key is not None else None
        idle = not self.bridge.busy
        self.plug_button.setEnabled(idle and plugged is False)
        self.unplug_button.setEnabled(idle and plugged is True)
        self.replace_button.setEnabled(idle and plugged is True
                                       and self.replace_combo.count() > 0)
        for w in (self.reset_keep_button, self.reset_erase_button, self.save_button):
            w.setEnabled(idle)
        self.script_button.setEnabled(idle and self.script_combo.count() > 0)

    # -- controls --------------------------------------------------------------------------
    def _started(self, worker: Worker | None, text: str) -> Worker | None:
        if worker is not None:
            self._log(text)
        return worker

    def plug_selected(self) -> Worker | None:
        """Plug the selected device in."""
        key = self.selected_key()
        if key is None:
            return None
        return self._started(self.bridge.plug(key), self.tr("Plugging in {device}…").format(
            device=self._label(key)))

    def unplug_selected(self) -> Worker | None:
        """Unplug the selected device."""
        key = self.selected_key()
        if key is None:
            return None
        return self._started(self.bridge.unplug(key), self.tr("Unplugging {device}…").format(
            device=self._label(key)))

    def replace_selected(self, new_key: DeviceKey | None) -> Worker | None:
        """Replace the selected device by the unplugged device ``new_key``."""
        key = self.selected_key()
        if key is None or new_key is None:
            return None
        return self._started(self.bridge.replace(key, DeviceKey(*new_key)),
                             self.tr("Replacing {old} by {new}…").format(
                                 old=self._label(key), new=self._label(new_key)))

    def reset(self, keep_memory: bool) -> Worker | None:
        """Reset the arbitrator, keeping or erasing its memory."""
        text = (self.tr("Resetting the arbitrator, keeping its memory…") if keep_memory else
                self.tr("Resetting the arbitrator, erasing its memory…"))
        return self._started(self.bridge.reset_arbitrator(keep_memory), text)

    def save_links(self) -> Worker | None:
        """Store the current links as the arbitrator's configuration."""
        worker = self.bridge.save_configuration()
        if worker is not None:
            worker.finished.connect(self._links_stored)
        return self._started(worker, self.tr("Storing the current links…"))

    def _links_stored(self, _read_back: object) -> None:
        self._log(self.tr("Stored the current links in the arbitrator's memory"))

    def run_script(self, name: str) -> Worker | None:
        """Run the simulator script ``name``."""
        if not name:
            return None
        return self._started(self.bridge.run_script(name),
                             self.tr("Running script {name}…").format(
                                 name=script_name_words(name)))
