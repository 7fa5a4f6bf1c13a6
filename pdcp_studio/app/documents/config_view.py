"""The window of one stored-configuration file: its configurations, each as a graph of the
channels it stores, its links, checks of what it holds, and how it fits a prosthesis.

Opened from the main window's File ▸ Open for a ``.pdcfg`` (see :func:`open_config_window`);
the main window stays on its prosthesis (a system file or the live bus), which is what the
configuration is fitted against. Edits go through :class:`ConfigDocument` (one undo step
each); saving writes the file atomically and keeps every record other tools wrote.

The graph reuses the bus scene on a private :class:`Document` built from the configuration
alone: devices are named from the catalogue of the open prosthesis where known and plainly
"unknown device (VID/PID/serial)" otherwise; the scene's own problem marks cannot fire
because a configuration holds no terminal profiles, required inputs or sources.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QCoreApplication, Qt, QTimer
from PySide6.QtGui import QAction, QCloseEvent, QKeySequence
from PySide6.QtWidgets import (
    QAbstractItemView,
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QFileDialog,
    QFormLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListView,
    QListWidget,
    QListWidgetItem,
    QMainWindow,
    QMessageBox,
    QPushButton,
    QSpinBox,
    QSplitter,
    QTableWidget,
    QTableWidgetItem,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.documents.config_document import ConfigDocument
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.words.plural import count
from pdcp_studio.engine.config_checks import ConfigFinding, check_configuration
from pdcp_studio.errors import PdcpError
from pdcp_studio.model import profile as prof
from pdcp_studio.model.catalog import default_catalog
from pdcp_studio.model.config_edit import channels_of
from pdcp_studio.model.configuration import StoredChannel, StoredConfiguration
from pdcp_studio.model.device_names import DeviceCatalogue
from pdcp_studio.model.refs import DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link, System

#: Where the prosthesis to fit against comes from: () → (system or None, its name).
ProsthesisSource = Callable[[], tuple[System | None, str]]

SEVERITY_WORDS = {"error": "Error", "warning": "Warning", "info": "Note"}


def _tr(text: str) -> str:
    return QCoreApplication.translate("ConfigWindow", text)


def system_for_configuration(cfg: StoredConfiguration | None,
                             catalogue: DeviceCatalogue) -> System:
    """The devices and links one configuration names, for drawing only.

    Each device is named from ``catalogue`` (or "unknown device (VID/PID/serial)"); each
    channel carries the stored type and profile; a link whose ends cannot coexist (a
    channel stored as both an output and an input) is left out of the drawing, and the
    checks name it.
    """
    system = System()
    if cfg is None:
        return system
    for ref, (direction, ch) in channels_of(cfg).items():
        key = ref.device
        device = system.devices.get(key)
        if device is None:
            device = system.add_device(Device(key.vid, key.pid, key.serial,
                                              name=catalogue.label(key)))
        if ref.index not in device.channels:
            device.add_channel(Channel(ref.index, Direction(direction), type=ch.type,
                                       profile=ch.profile))
    for sl in cfg.links:
        link = Link(sl.output.ref, sl.input.ref)
        out_ch, in_ch = system.channel(link.output), system.channel(link.input)
        if (out_ch is not None and out_ch.is_output and in_ch is not None and in_ch.is_input
                and not system.has_link(link)):
            system.add_link(link, check=False)
    return system


def _wrapping_list() -> QListWidget:
    """A list of sentences: wrapped to the width, never cut short."""
    lst = QListWidget()
    lst.setWordWrap(True)
    lst.setSpacing(3)
    lst.setTextElideMode(Qt.TextElideMode.ElideNone)
    lst.setResizeMode(QListView.ResizeMode.Adjust)
    return lst


def _hex(value: int) -> str:
    return f"0x{value:04X}"


def parse_word(text: str) -> int:
    """``0x2110``, ``2110h`` is not accepted: hex with 0x, or a decimal number, 0…0xFFFF."""
    text = text.strip()
    value = int(text, 16) if text.lower().startswith("0x") else int(text, 10)
    if not 0 <= value <= 0xFFFF:
        raise ValueError(f"{text} is out of range 0…0xFFFF")
    return value


class ChannelDialog(QDialog):
    """Type and profile of one stored channel."""

    def __init__(self, title: str, ch: StoredChannel, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(title)
        form = QFormLayout(self)
        self.type_edit = QLineEdit(_hex(ch.type))
        self.profile_edit = QLineEdit(_hex(ch.profile))
        form.addRow(self.tr("Channel type"), self.type_edit)
        form.addRow(self.tr("Channel profile"), self.profile_edit)
        self.error = QLabel("")
        self.error.setStyleSheet("color: #b3261e;")
        form.addRow(self.error)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok
                                   | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def values(self) -> tuple[int, int] | None:
        try:
            return parse_word(self.type_edit.text()), parse_word(self.profile_edit.text())
        except ValueError:
            return None

    def accept(self) -> None:
        if self.values() is None:
            self.error.setText(self.tr("Type and profile are numbers from 0 to 0xFFFF "
                                       "(write hex as 0x2110)."))
            return
        super().accept()


class _EndEditor(QGroupBox):
    """One end of a new link: pick a known channel or enter its numbers."""

    def __init__(self, title: str, known: list[tuple[str, StoredChannel]]) -> None:
        super().__init__(title)
        form = QFormLayout(self)
        self.pick = QComboBox()
        self.pick.addItem(self.tr("Enter the numbers below"), None)
        for label, ch in known:
            self.pick.addItem(label, ch)
        form.addRow(self.tr("Channel"), self.pick)
        self.spins: dict[str, QSpinBox] = {}
        for name, label, lo, hi in (("vid", self.tr("Vendor ID"), 0, 0xFFFF),
                                    ("pid", self.tr("Product ID"), 0, 0xFFFF),
                                    ("serial", self.tr("Serial number"), 0, 0xFFFF),
                                    ("index", self.tr("Channel index"), 1, 255)):
            spin = QSpinBox()
            spin.setRange(lo, hi)
            self.spins[name] = spin
            form.addRow(label, spin)
        self.type_edit, self.profile_edit = QLineEdit("0x0000"), QLineEdit("0x0000")
        form.addRow(self.tr("Channel type"), self.type_edit)
        form.addRow(self.tr("Channel profile"), self.profile_edit)
        self.pick.currentIndexChanged.connect(self._picked)

    def _picked(self) -> None:
        ch = self.pick.currentData()
        if ch is None:
            return
        for name, spin in self.spins.items():
            spin.setValue(getattr(ch, name))
        self.type_edit.setText(_hex(ch.type))
        self.profile_edit.setText(_hex(ch.profile))

    def channel(self) -> StoredChannel:
        """The channel as entered (ValueError naming a bad number)."""
        v = {name: spin.value() for name, spin in self.spins.items()}
        return StoredChannel(index=v["index"], vid=v["vid"], pid=v["pid"], serial=v["serial"],
                             type=parse_word(self.type_edit.text()),
                             profile=parse_word(self.profile_edit.text()))


class AddLinkDialog(QDialog):
    """A new stored link: an output and an input, known channels offered first."""

    def __init__(self, outputs: list[tuple[str, StoredChannel]],
                 inputs: list[tuple[str, StoredChannel]], parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(self.tr("Add a link"))
        layout = QVBoxLayout(self)
        row = QHBoxLayout()
        self.output = _EndEditor(self.tr("From (output)"), outputs)
        self.input = _EndEditor(self.tr("To (input)"), inputs)
        row.addWidget(self.output)
        row.addWidget(self.input)
        layout.addLayout(row)
        self.error = QLabel("")
        self.error.setStyleSheet("color: #b3261e;")
        layout.addWidget(self.error)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok
                                   | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        layout.addWidget(buttons)

    def ends(self) -> tuple[StoredChannel, StoredChannel] | None:
        try:
            return self.output.channel(), self.input.channel()
        except ValueError:
            return None

    def accept(self) -> None:
        ends = self.ends()
        if ends is None:
            self.error.setText(self.tr("Type and profile are numbers from 0 to 0xFFFF "
                                       "(write hex as 0x2110)."))
            return
        if ends[0].ref == ends[1].ref:
            self.error.setText(self.tr("A link joins two different channels."))
            return
        super().accept()


class ConfigWindow(QMainWindow):
    """One ``.pdcfg`` file: configurations, graph, links, checks, fit."""

    def __init__(self, doc: ConfigDocument, prosthesis: ProsthesisSource | None = None,
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        from pdcp_studio.app.documents.document import Document
        from pdcp_studio.app.graph.scene import BusScene
        from pdcp_studio.app.graph.view import GraphView

        self.doc = doc
        self.quiet = False
        self._prosthesis_source: ProsthesisSource | None = prosthesis
        self._file_system: tuple[System, str] | None = None
        self.fit: Any = None
        self.findings: list[ConfigFinding] = []
        self.catalogue = DeviceCatalogue()
        self.resize(1500, 920)

        self.graph_doc = Document()
        self.scene = BusScene(self.graph_doc, self)
        self.view = GraphView(self.scene, self)
        self.view.setInteractive(False)  # edits go through the link list, one undo step each

        self.config_list = QListWidget()
        self.config_list.currentRowChanged.connect(self._on_row)
        self.btn_add_cfg = QPushButton(self.tr("Add"))
        self.btn_dup_cfg = QPushButton(self.tr("Duplicate"))
        self.btn_del_cfg = QPushButton(self.tr("Remove"))
        self.btn_up_cfg = QPushButton(self.tr("Move up"))
        self.btn_down_cfg = QPushButton(self.tr("Move down"))
        self.btn_add_cfg.clicked.connect(doc.add_configuration)
        self.btn_dup_cfg.clicked.connect(lambda: doc.duplicate_configuration())
        self.btn_del_cfg.clicked.connect(lambda: doc.remove_configuration())
        self.btn_up_cfg.clicked.connect(lambda: doc.move_configuration(-1))
        self.btn_down_cfg.clicked.connect(lambda: doc.move_configuration(+1))
        left = QWidget()
        lv = QVBoxLayout(left)
        lv.setContentsMargins(6, 6, 6, 6)
        title = QLabel(self.tr("Configurations"))
        title.setStyleSheet("font-weight: bold;")
        lv.addWidget(title)
        lv.addWidget(self.config_list, 1)
        hint = QLabel(self.tr("At start-up the arbitrator picks the configuration that best "
                              "fits the devices present; on a tie, the higher one."))
        hint.setWordWrap(True)
        hint.setStyleSheet("color: #66707b;")
        lv.addWidget(hint)
        for row in ((self.btn_add_cfg, self.btn_dup_cfg), (self.btn_del_cfg,),
                    (self.btn_up_cfg, self.btn_down_cfg)):
            h = QHBoxLayout()
            for b in row:
                h.addWidget(b)
            lv.addLayout(h)

        self.links = QTableWidget(0, 7)
        self.links.setHorizontalHeaderLabels([
            self.tr("Link"), self.tr("From (output)"), self.tr("Form"),
            self.tr("What it carries"), self.tr("To (input)"), self.tr("Form"),
            self.tr("What it carries")])
        self.links.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.links.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        self.links.verticalHeader().hide()
        self.links.horizontalHeader().setStretchLastSection(True)
        self.links.itemSelectionChanged.connect(self._update_buttons)
        self.links.itemSelectionChanged.connect(self._show_selected_in_graph)
        self.links.cellDoubleClicked.connect(self._on_double_click)
        self.btn_add_link = QPushButton(self.tr("Add link…"))
        self.btn_del_link = QPushButton(self.tr("Remove link"))
        self.btn_edit_out = QPushButton(self.tr("Edit output channel…"))
        self.btn_edit_in = QPushButton(self.tr("Edit input channel…"))
        self.btn_add_link.clicked.connect(self.ask_add_link)
        self.btn_del_link.clicked.connect(self.remove_selected_links)
        self.btn_edit_out.clicked.connect(lambda: self.ask_edit_channel("output"))
        self.btn_edit_in.clicked.connect(lambda: self.ask_edit_channel("input"))
        links_box = QWidget()
        bv = QVBoxLayout(links_box)
        bv.setContentsMargins(0, 0, 0, 0)
        bv.addWidget(self.links, 1)
        h = QHBoxLayout()
        for b in (self.btn_add_link, self.btn_del_link, self.btn_edit_out, self.btn_edit_in):
            h.addWidget(b)
        h.addStretch(1)
        bv.addLayout(h)

        middle = QSplitter(Qt.Orientation.Vertical)
        middle.addWidget(self.view)
        middle.addWidget(links_box)
        middle.setSizes([560, 300])

        self.checks = _wrapping_list()
        self.checks.itemClicked.connect(self._on_finding)
        self.fit_label = QLabel("")
        self.fit_label.setWordWrap(True)
        self.fit_choice = QLabel("")
        self.fit_choice.setWordWrap(True)
        self.fit_list = _wrapping_list()
        self.btn_fit_main = QPushButton(self.tr("Fit to the prosthesis in the main window"))
        self.btn_fit_file = QPushButton(self.tr("Fit to a system file…"))
        self.btn_fit_main.clicked.connect(self.fit_to_main)
        self.btn_fit_file.clicked.connect(self.ask_fit_file)
        fit_box = QWidget()
        fv = QVBoxLayout(fit_box)
        fv.addWidget(self.fit_label)
        fv.addWidget(self.fit_choice)
        fv.addWidget(self.fit_list, 1)
        fv.addWidget(self.btn_fit_main)
        fv.addWidget(self.btn_fit_file)
        self.side = QTabWidget()
        self.side.addTab(self.checks, self.tr("Checks"))
        self.side.addTab(fit_box, self.tr("Fit"))

        split = QSplitter(Qt.Orientation.Horizontal)
        split.addWidget(left)
        split.addWidget(middle)
        split.addWidget(self.side)
        split.setSizes([230, 820, 450])
        split.setStretchFactor(1, 1)
        self.setCentralWidget(split)
        self._build_menus()
        self.info = QLabel("")
        self.statusBar().addPermanentWidget(self.info)

        self._fit_timer = QTimer(self)
        self._fit_timer.setSingleShot(True)
        self._fit_timer.setInterval(150)
        self._fit_timer.timeout.connect(self.refresh_fit)
        #: Started when the prosthesis changes (names and fit follow it, debounced).
        self.prosthesis_timer = QTimer(self)
        self.prosthesis_timer.setSingleShot(True)
        self.prosthesis_timer.setInterval(250)
        self.prosthesis_timer.timeout.connect(self.prosthesis_changed)
        doc.changed.connect(self.refresh)
        doc.currentChanged.connect(lambda _p: self.refresh())
        doc.dirtyChanged.connect(lambda _d: self._update_title())
        doc.pathChanged.connect(lambda _p: self._update_title())
        self.refresh()
        # Problems in the file first; otherwise how it fits the prosthesis, if one is open.
        if not self.findings and self.prosthesis()[0] is not None:
            self.side.setCurrentIndex(1)
            self.refresh_fit()

    # -- construction -----------------------------------------------------------------
    def _build_menus(self) -> None:
        doc = self.doc
        file_menu = self.menuBar().addMenu(self.tr("&File"))
        self.act_save = QAction(self.tr("&Save"), self)
        self.act_save.setShortcut(QKeySequence.StandardKey.Save)
        self.act_save.triggered.connect(self.save)
        self.act_save_as = QAction(self.tr("Save &as…"), self)
        self.act_save_as.setShortcut(QKeySequence.StandardKey.SaveAs)
        self.act_save_as.triggered.connect(self.ask_save_as)
        act_close = QAction(self.tr("&Close"), self)
        act_close.setShortcut(QKeySequence.StandardKey.Close)
        act_close.triggered.connect(self.close)
        for a in (self.act_save, self.act_save_as, act_close):
            file_menu.addAction(a)
        edit_menu = self.menuBar().addMenu(self.tr("&Edit"))
        self.act_undo = doc.undo_stack.createUndoAction(self, self.tr("&Undo"))
        self.act_undo.setShortcut(QKeySequence.StandardKey.Undo)
        self.act_redo = doc.undo_stack.createRedoAction(self, self.tr("&Redo"))
        self.act_redo.setShortcut(QKeySequence.StandardKey.Redo)
        edit_menu.addAction(self.act_undo)
        edit_menu.addAction(self.act_redo)
        act_del = QAction(self.tr("Remove link"), self)
        act_del.setShortcut(QKeySequence.StandardKey.Delete)
        act_del.triggered.connect(self.remove_selected_links)
        edit_menu.addAction(act_del)
        cfg_menu = self.menuBar().addMenu(self.tr("&Configuration"))
        for text, slot in ((self.tr("Add configuration"), doc.add_configuration),
                           (self.tr("Duplicate configuration"),
                            lambda: doc.duplicate_configuration()),
                           (self.tr("Remove configuration"), lambda: doc.remove_configuration()),
                           (self.tr("Move up"), lambda: doc.move_configuration(-1)),
                           (self.tr("Move down"), lambda: doc.move_configuration(+1)),
                           (self.tr("Add link…"), self.ask_add_link)):
            act = QAction(text, self)
            act.triggered.connect(slot)
            cfg_menu.addAction(act)
        fit_menu = self.menuBar().addMenu(self.tr("F&it"))
        for text, slot in ((self.tr("Fit to the prosthesis in the main window"),
                            self.fit_to_main),
                           (self.tr("Fit to a system file…"), self.ask_fit_file)):
            act = QAction(text, self)
            act.triggered.connect(slot)
            fit_menu.addAction(act)

    # -- showing ----------------------------------------------------------------------
    def showEvent(self, event: Any) -> None:
        """Fit the graph once the window has its real size."""
        super().showEvent(event)
        QTimer.singleShot(0, self.view.fit_all)

    def _update_title(self) -> None:
        self.setWindowTitle(f"{self.doc.title}[*] — " + self.tr("Stored configurations")
                            + self.tr(" — PDCP Studio"))
        self.setWindowModified(self.doc.is_dirty)

    def prosthesis(self) -> tuple[System | None, str]:
        """The system to fit against and its name (a file chosen here wins)."""
        if self._file_system is not None:
            return self._file_system
        if self._prosthesis_source is not None:
            return self._prosthesis_source()
        return None, ""

    def refresh(self) -> None:
        """Bring every part up to date with the document (after any change)."""
        doc = self.doc
        system, _name = self.prosthesis()
        self.catalogue = (DeviceCatalogue.from_system(system) if system is not None
                          else DeviceCatalogue()).with_catalog(default_catalog())
        self.config_list.blockSignals(True)
        self.config_list.clear()
        for each in doc.collection.configurations:
            text = self.tr("Configuration %1 · %2").replace("%1", str(each.index)) \
                .replace("%2", count("ConfigWindow", "%n link(s)", len(each.links)))
            item = QListWidgetItem(text)
            problems = [f for f in check_configuration(each) if f.severity.value == "error"]
            if problems:
                item.setToolTip(count("ConfigWindow", "%n problem(s) found", len(problems)))
                item.setForeground(Qt.GlobalColor.darkRed)
            self.config_list.addItem(item)
        self.config_list.setCurrentRow(doc.current)
        self.config_list.blockSignals(False)
        cfg = doc.configuration()
        self._fill_links(cfg)
        self.findings = check_configuration(cfg) if cfg is not None else []
        self._fill_checks()
        self.graph_doc.set_system(system_for_configuration(cfg, self.catalogue), None, None,
                                  positions={})
        self.view.fit_all()
        self._update_title()
        self._update_buttons()
        self._update_info()
        self._fit_timer.start()

    def _update_info(self) -> None:
        coll = self.doc.collection
        kept = len(coll.unknown) + sum(
            len(c.unknown) + sum(len(lk.unknown) + len(lk.input.unknown)
                                 + len(lk.output.unknown) for lk in c.links)
            for c in coll.configurations)
        text = count("ConfigWindow", "%n configuration(s)", len(coll.configurations))
        if kept:
            text += "  ·  " + count("ConfigWindow", "%n record(s) from newer firmware or tools "
                                    "kept as they are", kept)
        self.info.setText(text)

    def _channel_text(self, ch: StoredChannel) -> str:
        key = DeviceKey(ch.vid, ch.pid, ch.serial)
        return self.tr("%1, channel %2").replace("%1", self.catalogue.label(key)) \
            .replace("%2", str(ch.index))

    def _profile_text(self, profile: int) -> str:
        """What a channel carries, by the profile tree's names (the code is the tooltip)."""
        if profile == prof.NULL_PROFILE:
            return self.tr("not stored")
        if self.graph_doc.tree.node(profile) is None:
            return self.tr("not named in the profile tree")
        return self.graph_doc.tree.name_of(profile)

    def _type_text(self, value: int) -> str:
        """A channel type in words: its data type, size and control mode."""
        from pdcp_studio.model.channel_type import ChannelType

        try:
            t = ChannelType(value)
        except ValueError:
            return self.tr("unknown form")
        kind = (self.tr("signed number"), self.tr("number"), self.tr("decimal number"),
                self.tr("on/off"))[int(t.data_type)]
        mode = (self.tr("position"), self.tr("speed"), self.tr("acceleration"),
                self.tr("other"))[int(t.control_mode)]
        return self.tr("{kind} ({bits} bits), {mode}").format(kind=kind, bits=t.bits, mode=mode)

    def _fill_links(self, cfg: StoredConfiguration | None) -> None:
        links = cfg.links if cfg is not None else []
        self.links.setRowCount(len(links))
        for row, sl in enumerate(links):
            cells = [str(sl.index or row + 1), self._channel_text(sl.output),
                     self._type_text(sl.output.type), self._profile_text(sl.output.profile),
                     self._channel_text(sl.input), self._type_text(sl.input.type),
                     self._profile_text(sl.input.profile)]
            for col, text in enumerate(cells):
                item = QTableWidgetItem(text)
                ch = sl.output if col in (1, 2, 3) else sl.input
                if col in (1, 4):  # the engineer's detail, one hover away
                    item.setToolTip(f"{ch.vid}/{ch.pid}/{ch.serial} #{ch.index}")
                elif col in (2, 5):
                    item.setToolTip(self.tr("type {code}").format(code=_hex(ch.type)))
                elif col in (3, 6):
                    item.setToolTip(self.tr("profile {code}").format(code=prof.fmt(ch.profile)))
                self.links.setItem(row, col, item)
        self.links.resizeColumnsToContents()

    def _fill_checks(self) -> None:
        self.checks.clear()
        if not self.findings:
            self.checks.addItem(self.tr(
                "Nothing to report: the stored links can all be made together and their ends "
                "fit each other."))
        colours = {"error": Qt.GlobalColor.darkRed, "warning": Qt.GlobalColor.darkYellow}
        for f in self.findings:
            item = QListWidgetItem(f"{self.tr(SEVERITY_WORDS[f.severity.value])}: "
                                   f"{self._finding_words(f)}")
            item.setToolTip(f"{f.message}\n({f.code})")  # the engineer's words and the rule
            item.setData(Qt.ItemDataRole.UserRole, list(f.links))
            if f.severity.value in colours:
                item.setForeground(colours[f.severity.value])
            self.checks.addItem(item)
        QTimer.singleShot(0, self.checks.doItemsLayout)

    def _finding_words(self, f: ConfigFinding) -> str:
        """A configuration check in plain words with what to do (the engine's as tooltip)."""
        names = [self._ref_words(r) for r in f.refs]
        links = ", ".join(str(p + 1) for p in f.links)
        a = names[0] if names else ""
        b = names[1] if len(names) > 1 else ""
        text = {
            "same-device": self.tr("Link {links} joins {a} to its own device. Remove it."),
            "duplicate-link": self.tr("Links {links} store the same link {a} → {b}; it is made "
                                      "once. Remove the extra ones."),
            "two-sources": self.tr("{a} is given more than one source (links {links}); only "
                                   "the first would be made. Keep one of them."),
            "both-directions": self.tr("{a} is stored as an output and as an input (links "
                                       "{links}); a channel is one or the other. Correct the "
                                       "wrong link."),
            "sole-access": self.tr("{a} feeds several inputs that each need it for themselves "
                                   "(links {links}). Keep one of these links."),
            "inconsistent-records": self.tr("{a} is stored with different descriptions in "
                                            "links {links}. Edit the channel so they agree."),
            "profile-misfit": self.tr("Link {links}: {a} and {b} carry different kinds of "
                                      "signal; {b} may not understand what it is sent."),
            "type-differs": self.tr("Link {links}: {a} and {b} carry the same kind of signal in "
                                    "different forms; the input adapts to the output."),
        }.get(f.code)
        if text is None:
            return f.message
        return text.format(links=links, a=a, b=b)

    def _ref_words(self, ref: Any) -> str:
        return self.tr("%1, channel %2").replace("%1", self.catalogue.label(ref.device)) \
            .replace("%2", str(ref.index))

    def _plan_step_words(self, a: Any, system: System) -> str:
        from pdcp_studio.app.words import plan_words as W

        verb = self.tr("Add") if a.op.value == "add" else self.tr("Remove")
        return (f"{verb} {W.link_words(system, a.link.output, a.link.input)}: "
                f"{W.rule_words(a.rule)}")

    def _link_fit_words(self, lf: Any, system: System) -> str:
        """What happens to one stored link on this prosthesis, in words."""
        from pdcp_studio.app.words import plan_words as W
        from pdcp_studio.engine.config_fit import MISSING, PRESENT

        if lf.whole:
            return self.tr("both ends are on the prosthesis: made as stored")
        parts = []
        for end, state in ((self.tr("the output"), lf.output), (self.tr("the input"), lf.input)):
            if state == MISSING:
                parts.append(self.tr("{end} is missing").format(end=end))
            elif state != PRESENT:
                parts.append(self.tr("{end} has the other direction on the prosthesis").format(
                    end=end))
        adds = [a for a in lf.actions if a.op.value == "add"]
        if adds:
            made = "; ".join(self.tr("replaced by {link} ({similar})").format(
                link=W.link_words(system, a.link.output, a.link.input),
                similar=W.similarity_words(a, self.fit.plan) if self.fit else "")
                for a in adds)
            return f"{', '.join(parts)}: {made}"
        return self.tr("{parts}: no replacement found, the link is not made").format(
            parts=", ".join(parts))

    def refresh_fit(self) -> None:
        """Fit the current configuration to the prosthesis (if one is open)."""
        from pdcp_studio.engine.config_fit import fit_configuration

        self.fit_list.clear()
        self.fit = None
        system, name = self.prosthesis()
        cfg = self.doc.configuration()
        if system is None or not system.devices:
            self.fit_label.setText(self.tr(
                "No prosthesis to fit to. Open a system file or connect to a bus in the main "
                "window, or choose a system file here."))
            self.fit_choice.setText("")
            return
        self.fit_label.setText(self.tr("Fitted to %1.").replace("%1", name))
        if cfg is None:
            self.fit_choice.setText("")
            return
        try:
            fit = fit_configuration(system, self.doc.collection, self.doc.current)
        except PdcpError as err:
            self.fit_choice.setText(str(err))
            return
        self.fit = fit
        self.fit_choice.setText(self.tr("At start-up: %1").replace("%1", fit.chosen_reason))
        self.fit_choice.setStyleSheet("font-weight: bold;" if fit.chosen_index == fit.index
                                      else "")
        for lf in fit.links:
            sl = lf.link
            number = str(sl.index or lf.position + 1)
            label = self.tr("Link %1: %2 → %3\n%4").replace("%1", number) \
                .replace("%2", self._channel_text(sl.output)) \
                .replace("%3", self._channel_text(sl.input)) \
                .replace("%4", self._link_fit_words(lf, system))
            item = QListWidgetItem(label)
            item.setToolTip(lf.summary())  # the engineer's words
            if not lf.whole:
                item.setForeground(Qt.GlobalColor.darkRed if not lf.actions
                                   else Qt.GlobalColor.darkYellow)
            self.fit_list.addItem(item)
        if fit.plan.actions:
            head = QListWidgetItem(count("ConfigWindow", "What start-up would do with this "
                                         "configuration (%n step(s)):", len(fit.plan.actions)))
            head.setForeground(Qt.GlobalColor.darkBlue)
            self.fit_list.addItem(head)
            for a in fit.plan.actions:
                step = QListWidgetItem("    " + self._plan_step_words(a, system))
                step.setToolTip(f"{a.op.value} {a.link.output} → {a.link.input}: {a.reason}")
                self.fit_list.addItem(step)
        QTimer.singleShot(0, self.fit_list.doItemsLayout)  # wrap at the width it has now

    def set_prosthesis_source(self, source: ProsthesisSource | None) -> None:
        self._prosthesis_source = source
        self._fit_timer.start()

    def prosthesis_changed(self) -> None:
        """The prosthesis fitted to changed (the main window's system or bus)."""
        if self._file_system is None:
            self.refresh()

    def fit_to_main(self) -> None:
        self._file_system = None
        self.refresh()
        self.refresh_fit()
        self.side.setCurrentIndex(1)

    def fit_to_file(self, path: str | Path) -> bool:
        from pdcp_studio.storage import system_file

        try:
            system = system_file.load_path(path)
        except (PdcpError, OSError) as err:
            self._warn(self.tr("Cannot open"), f"{path}: {err}")
            return False
        self._file_system = (system, Path(path).name)
        self.refresh()
        self.refresh_fit()
        self.side.setCurrentIndex(1)
        return True

    def ask_fit_file(self) -> None:
        path, _ = QFileDialog.getOpenFileName(self, self.tr("Fit to a system file"), "",
                                              self.tr("System files (*.json)"))
        if path:
            self.fit_to_file(path)

    # -- selection and edits ----------------------------------------------------------
    def _on_row(self, row: int) -> None:
        self.doc.set_current(row)

    def selected_links(self) -> list[int]:
        return sorted({i.row() for i in self.links.selectionModel().selectedRows()})

    def select_links(self, positions: list[int]) -> None:
        self.links.clearSelection()
        mode = self.links.selectionMode()
        self.links.setSelectionMode(QAbstractItemView.SelectionMode.MultiSelection)
        for p in positions:
            self.links.selectRow(p)
        self.links.setSelectionMode(mode)

    def _on_finding(self, item: QListWidgetItem) -> None:
        positions = item.data(Qt.ItemDataRole.UserRole) or []
        self.select_links(list(positions))

    def _update_buttons(self) -> None:
        has_cfg = self.doc.configuration() is not None
        n = len(self.doc.collection.configurations)
        selected = self.selected_links() if has_cfg else []
        self.btn_dup_cfg.setEnabled(has_cfg)
        self.btn_del_cfg.setEnabled(has_cfg)
        self.btn_up_cfg.setEnabled(has_cfg and self.doc.current > 0)
        self.btn_down_cfg.setEnabled(has_cfg and self.doc.current < n - 1)
        self.btn_add_link.setEnabled(has_cfg)
        self.btn_del_link.setEnabled(bool(selected))
        self.btn_edit_out.setEnabled(len(selected) == 1)
        self.btn_edit_in.setEnabled(len(selected) == 1)

    def _show_selected_in_graph(self) -> None:
        """The link picked in the list is highlighted in the graph."""
        cfg = self.doc.configuration()
        rows = self.selected_links()
        if cfg is None or len(rows) != 1 or rows[0] >= len(cfg.links):
            self.graph_doc.select(None)
            return
        sl = cfg.links[rows[0]]
        link = Link(sl.output.ref, sl.input.ref)
        self.graph_doc.select(link if self.graph_doc.system.has_link(link) else None)

    def remove_selected_links(self) -> None:
        self.doc.remove_links(self.selected_links())

    def _on_double_click(self, row: int, col: int) -> None:
        self.select_links([row])
        self.ask_edit_channel("input" if col >= 4 else "output")

    def ask_edit_channel(self, end: str) -> None:
        cfg = self.doc.configuration()
        rows = self.selected_links()
        if cfg is None or len(rows) != 1:
            return
        ch: StoredChannel = getattr(cfg.links[rows[0]], end)
        title = self.tr("Stored channel %1").replace("%1", self._channel_text(ch))
        dialog = ChannelDialog(title, ch, self)
        if dialog.exec() == QDialog.DialogCode.Accepted:
            values = dialog.values()
            if values is not None:
                self.edit_channel(end, rows[0], *values)

    def edit_channel(self, end: str, link_position: int, type: int, profile: int) -> None:
        """Set the type and profile of one end of a link (every record of that channel)."""
        cfg = self.doc.configuration()
        if cfg is None:
            return
        ch: StoredChannel = getattr(cfg.links[link_position], end)
        self.doc.set_channel(ch.ref, type=type, profile=profile)
        self.select_links([link_position])

    def known_channels(self, direction: str) -> list[tuple[str, StoredChannel]]:
        """Channels to offer for a new link: this configuration's, then the prosthesis's."""
        out: dict[Any, tuple[str, StoredChannel]] = {}
        cfg = self.doc.configuration()
        if cfg is not None:
            for ref, (dirn, ch) in channels_of(cfg).items():
                if dirn == direction:
                    out[ref] = (self._channel_text(ch), ch)
        system, _name = self.prosthesis()
        if system is not None:
            for ref, sch in system.channels():
                if sch.direction.value == direction and ref not in out:
                    ch = StoredChannel(ref.index, ref.vid, ref.pid, ref.serial, sch.type,
                                       sch.profile)
                    out[ref] = (self._channel_text(ch), ch)
        return list(out.values())

    def ask_add_link(self) -> None:
        if self.doc.configuration() is None:
            return
        dialog = AddLinkDialog(self.known_channels("output"), self.known_channels("input"),
                               self)
        if dialog.exec() == QDialog.DialogCode.Accepted:
            ends = dialog.ends()
            if ends is not None:
                self.doc.add_link(*ends)

    # -- files ------------------------------------------------------------------------
    def save(self) -> bool:
        if self.doc.path is None:
            return self.ask_save_as()
        return self.save_to(self.doc.path)

    def ask_save_as(self) -> bool:
        start = str(self.doc.path) if self.doc.path else "configuration.pdcfg"
        path, _ = QFileDialog.getSaveFileName(self, self.tr("Save as"), start,
                                              self.tr("Stored configurations (*.pdcfg)"))
        return self.save_to(path) if path else False

    def save_to(self, path: str | Path) -> bool:
        try:
            target = self.doc.save(path)
        except (PdcpError, OSError, ValueError) as err:
            self._warn(self.tr("Cannot save"), f"{path}: {err}")
            return False
        self.statusBar().showMessage(self.tr("Saved %1").replace("%1", str(target)), 8000)
        return True

    def _warn(self, title: str, text: str) -> None:
        self.statusBar().showMessage(f"{title}: {text}", 0)
        if not self.quiet:
            QMessageBox.warning(self, title, text)

    def ask_save_changes(self) -> QMessageBox.StandardButton:
        """Save, Discard or Cancel (tests replace this method)."""
        SB = QMessageBox.StandardButton
        return QMessageBox.question(
            self, self.tr("Unsaved changes"),
            self.tr("Save the changes to %1?").replace("%1", self.doc.title),
            SB.Save | SB.Discard | SB.Cancel, SB.Save)

    def closeEvent(self, event: QCloseEvent) -> None:
        if self.doc.is_dirty:
            answer = self.ask_save_changes()
            SB = QMessageBox.StandardButton
            if answer == SB.Cancel or (answer == SB.Save and not self.save()):
                event.ignore()
                return
        event.accept()


def open_config_window(main: Any, path: str | Path, collection: Any = None) -> ConfigWindow:
    """Open ``path`` in its own window, fitted to the main window's prosthesis.

    ``collection`` is the already decoded file (the main window read it to check it).
    The window is kept in ``main.config_windows`` while it is open; the main window's plans
    use the collection as their stored configuration (``main.doc.config``), following edits.
    """
    doc = (ConfigDocument(collection, path) if collection is not None
           else ConfigDocument.open(path))

    def source() -> tuple[System | None, str]:
        system = main.doc.system
        if not system.devices:
            return None, ""
        live = getattr(main.live, "is_live", False) and main.doc.session is not None
        if live:
            return system, translate("ConfigWindow", "the live bus %1").replace(
                "%1", str(main.live.url)
            )
        name = (
            main.doc.path.name
            if main.doc.path is not None
            else translate("ConfigWindow", "the main window")
        )
        return system, translate("ConfigWindow", "the prosthesis in the main window (%1)").replace(
            "%1", name
        )

    window = ConfigWindow(doc, source)
    window.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose, True)
    window.quiet = getattr(main, "quiet", False)
    windows: list[ConfigWindow] = getattr(main, "config_windows", [])
    main.config_windows = windows
    windows.append(window)
    window.destroyed.connect(lambda *_: windows.remove(window) if window in windows else None)
    for signal in (main.doc.systemReset, main.doc.linksChanged, main.doc.deviceChanged):
        signal.connect(window.prosthesis_timer.start)
    main.doc.config = doc.collection
    shown = {"collection": doc.collection}

    def follow() -> None:
        if main.doc.config is shown["collection"]:
            main.doc.config = doc.collection
        shown["collection"] = doc.collection

    doc.changed.connect(follow)
    window.show()
    window.raise_()
    return window
