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

The window composes its parts: the configuration list (:mod:`.config_list_panel`), the
link table (:mod:`.config_links_panel`), the Fit tab (:mod:`.config_fit_panel`), their
words (:mod:`.config_words`) and dialogs (:mod:`.config_dialogs`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

from PySide6.QtCore import Qt, QTimer
from PySide6.QtGui import QAction, QCloseEvent, QKeySequence, QShowEvent
from PySide6.QtWidgets import (
    QDialog,
    QFileDialog,
    QLabel,
    QListWidgetItem,
    QMainWindow,
    QMessageBox,
    QSplitter,
    QTabWidget,
    QWidget,
)

from pdcp_studio.app.configuration.dialogs import AddLinkDialog, ChannelDialog
from pdcp_studio.app.configuration.fit_panel import FitPanel, wrapping_list
from pdcp_studio.app.configuration.links_panel import LinksPanel
from pdcp_studio.app.configuration.list_panel import ConfigListPanel
from pdcp_studio.app.configuration.words import ConfigWords
from pdcp_studio.app.documents.config_document import ConfigDocument
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.words import part_names
from pdcp_studio.app.words.plural import count
from pdcp_studio.engine.config_checks import ConfigFinding, check_configuration
from pdcp_studio.errors import PdcpError
from pdcp_studio.model.config_edit import channels_of
from pdcp_studio.model.configuration import StoredChannel, StoredConfiguration
from pdcp_studio.model.names import Names
from pdcp_studio.model.refs import Direction
from pdcp_studio.model.system import Channel, Device, Link, System

#: Where the prosthesis to fit against comes from: () → (system or None, its name).
ProsthesisSource = Callable[[], tuple[System | None, str]]

SEVERITY_WORDS = {"error": "Error", "warning": "Warning", "info": "Note"}


def configuration_names(system: System | None,
                        configurations: Iterable[StoredConfiguration]) -> Names:
    """The one naming (``model/names.py``) of the parts a stored configuration names: a
    part on the prosthesis fitted to (``system``) as every panel calls it, any other by its
    catalogue product; the configurations' parts are named together, so two alike get
    their serial numbers (a stored configuration knows only VID, PID and serial)."""
    keys = {ref.device for cfg in configurations for ref in channels_of(cfg)}
    among = [Device(k.vid, k.pid, k.serial) for k in sorted(keys)]
    return part_names.names(system, among)


def system_for_configuration(cfg: StoredConfiguration | None, names: Names) -> System:
    """The devices and links one configuration names, for drawing only.

    Each device is named by ``names`` (the one naming: the prosthesis's name, else the
    catalogue's product, the serial number only for twins); each
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
                                              name=names.part(key)))
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
        self.findings: list[ConfigFinding] = []
        self.names: Names = part_names.names(None)
        self.resize(1500, 920)

        self.graph_doc = Document()
        self.scene = BusScene(self.graph_doc, self)
        self.view = GraphView(self.scene, self)
        self.view.setInteractive(False)  # edits go through the link list, one undo step each
        self.words = ConfigWords(lambda: self.names, lambda: self.graph_doc.tree)

        left = ConfigListPanel(doc)
        self.config_list = left.config_list
        self.btn_add_cfg, self.btn_dup_cfg = left.btn_add_cfg, left.btn_dup_cfg
        self.btn_del_cfg, self.btn_up_cfg = left.btn_del_cfg, left.btn_up_cfg
        self.btn_down_cfg = left.btn_down_cfg
        self.config_panel = left

        self.links_panel = LinksPanel(self.words)
        self.links = self.links_panel.links
        self.btn_add_link, self.btn_del_link = (self.links_panel.btn_add_link,
                                                self.links_panel.btn_del_link)
        self.btn_edit_out, self.btn_edit_in = (self.links_panel.btn_edit_out,
                                               self.links_panel.btn_edit_in)
        self.links.itemSelectionChanged.connect(self._update_buttons)
        self.links.itemSelectionChanged.connect(self._show_selected_in_graph)
        self.links.cellDoubleClicked.connect(self._on_double_click)
        self.btn_add_link.clicked.connect(self.ask_add_link)
        self.btn_del_link.clicked.connect(self.remove_selected_links)
        self.btn_edit_out.clicked.connect(lambda: self.ask_edit_channel("output"))
        self.btn_edit_in.clicked.connect(lambda: self.ask_edit_channel("input"))

        middle = QSplitter(Qt.Orientation.Vertical)
        middle.addWidget(self.view)
        middle.addWidget(self.links_panel)
        middle.setSizes([560, 300])

        self.checks = wrapping_list()
        self.checks.itemClicked.connect(self._on_finding)
        self.fit_panel = FitPanel(doc, self.words)
        self.fit_label, self.fit_choice = self.fit_panel.fit_label, self.fit_panel.fit_choice
        self.fit_list = self.fit_panel.fit_list
        self.btn_fit_main, self.btn_fit_file = (self.fit_panel.btn_fit_main,
                                                self.fit_panel.btn_fit_file)
        self.btn_fit_main.clicked.connect(self.fit_to_main)
        self.btn_fit_file.clicked.connect(self.ask_fit_file)
        self.side = QTabWidget()
        self.side.addTab(self.checks, self.tr("Checks"))
        self.side.addTab(self.fit_panel, self.tr("Fit"))

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

    @property
    def fit(self) -> Any:
        """The fit shown in the Fit tab (None: none)."""
        return self.fit_panel.fit

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
    def showEvent(self, event: QShowEvent) -> None:
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
        self.names = configuration_names(system, doc.collection.configurations)
        self.config_panel.fill()
        cfg = doc.configuration()
        self.links_panel.fill(cfg)
        self.findings = check_configuration(cfg) if cfg is not None else []
        self._fill_checks()
        self.graph_doc.set_system(system_for_configuration(cfg, self.names), None, None,
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

    def _fill_checks(self) -> None:
        self.checks.clear()
        if not self.findings:
            self.checks.addItem(self.tr(
                "Nothing to report: the stored links can all be made together and their ends "
                "fit each other."))
        colours = {"error": Qt.GlobalColor.darkRed, "warning": Qt.GlobalColor.darkYellow}
        for f in self.findings:
            item = QListWidgetItem(f"{self.tr(SEVERITY_WORDS[f.severity.value])}: "
                                   f"{self.words.finding_words(f)}")
            item.setToolTip(f"{f.message}\n({f.code})")  # the engineer's words and the rule
            item.setData(Qt.ItemDataRole.UserRole, list(f.links))
            if f.severity.value in colours:
                item.setForeground(colours[f.severity.value])
            self.checks.addItem(item)
        QTimer.singleShot(0, self.checks.doItemsLayout)

    def refresh_fit(self) -> None:
        """Fit the current configuration to the prosthesis (if one is open)."""
        self.fit_panel.show_fit(*self.prosthesis())

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
    def selected_links(self) -> list[int]:
        return self.links_panel.selected()

    def select_links(self, positions: list[int]) -> None:
        self.links_panel.select(positions)

    def _on_finding(self, item: QListWidgetItem) -> None:
        positions = item.data(Qt.ItemDataRole.UserRole) or []
        self.select_links(list(positions))

    def _update_buttons(self) -> None:
        self.config_panel.update_buttons()
        self.links_panel.update_buttons(self.doc.configuration() is not None)

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
        title = self.tr("Stored channel %1").replace("%1", self.words.channel_text(ch))
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
                    out[ref] = (self.words.channel_text(ch), ch)
        system, _name = self.prosthesis()
        if system is not None:
            for ref, sch in system.channels():
                if sch.direction.value == direction and ref not in out:
                    ch = StoredChannel(ref.index, ref.vid, ref.pid, ref.serial, sch.type,
                                       sch.profile)
                    out[ref] = (self.words.channel_text(ch), ch)
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
