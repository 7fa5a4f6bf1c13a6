"""Compare the links of the on-screen system, a file and the arbitrator's stored configuration.

Public API
    ``CompareDialog(system, *, bridge=None, parent=None)`` — non-modal; one row per link found
    in any source, one tick column per source, and a status ("in all", "only in X",
    "in X and Y"). Sources: the on-screen system (always), a file (``.json`` system file or
    ``.pdcfg`` stored configuration; one column per configuration it holds) and the
    arbitrator's stored configuration (read through ``bridge``, a ``SessionBridge``).
    Methods: ``set_system(system)``, ``load_file(path) -> Worker`` (read on a worker),
    ``read_arbitrator() -> Worker | None``, ``set_file_sources(list[LinkSource])``,
    ``set_arbitrator(collection)``, ``rows() -> list[CompareRow]``,
    ``set_differences_only(bool)``. Signals: ``compared()`` after the table was rebuilt,
    ``error(str)``.

Pure helpers (no widgets): ``links_of_system``, ``links_of_configuration``,
``sources_of_collection``, ``load_file_sources(path)``, ``compare(sources)``.

When a stored configuration is known on both sides (a ``.pdcfg`` and the arbitrator's), the
summary also says how they differ record by record — with the one configuration diff
(:mod:`pdcp_studio.model.config_diff`) that ``config diff`` and the write dialog use.
"""

from __future__ import annotations

import html
import threading
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, NamedTuple

from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QBrush, QColor
from PySide6.QtWidgets import (
    QCheckBox,
    QDialog,
    QDialogButtonBox,
    QFileDialog,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.words.plural import count
from pdcp_studio.app.workers import ProgressFn, Worker
from pdcp_studio.model.configuration import ConfigCollection, StoredConfiguration
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link, System

if TYPE_CHECKING:
    from pdcp_studio.app.live.session_bridge import SessionBridge

ON_SCREEN = QT_TRANSLATE_NOOP("CompareDialog", "On screen")
ARBITRATOR = "Arbitrator"
ONLY_COLOUR = QColor(255, 236, 200)
TICK = "✓"


class LinkSource(NamedTuple):
    """A named set of links (one column of the comparison)."""

    name: str
    links: frozenset[Link]


class CompareRow(NamedTuple):
    """One link and, per source in column order, whether that source has it."""

    link: Link
    present: tuple[bool, ...]

    def status(self, names: Sequence[str]) -> str:
        """Where this link is, in words: ``in all``, ``only in X``, ``in X and Y``."""
        where = [n for n, p in zip(names, self.present, strict=True) if p]
        if len(where) == len(names):
            return (translate("CompareDialog", "in all") if len(names) > 1
                    else translate("CompareDialog", "present"))
        if len(where) == 1:
            return translate("CompareDialog", "only in {0}").format(where[0])
        return translate("CompareDialog", "in {0}").format(
            translate("CompareDialog", " and ").join(where))

    @property
    def everywhere(self) -> bool:
        """True when every source has this link."""
        return all(self.present)


def links_of_system(system: System) -> frozenset[Link]:
    """The system's links as a set."""
    return frozenset(system.links)


def links_of_configuration(cfg: StoredConfiguration) -> frozenset[Link]:
    """A stored configuration's links as output → input references (types are not compared;
    the records are, by :func:`~pdcp_studio.model.config_diff.diff_configurations`)."""
    from pdcp_studio.model.config_diff import link_ends

    return frozenset(Link(out, inp) for out, inp in link_ends(ConfigCollection([cfg])))


def sources_of_collection(name: str, collection: ConfigCollection | None) -> list[LinkSource]:
    """One source per configuration (``name #2`` when there are several; empty: one, no links)."""
    configs = list(collection.configurations) if collection is not None else []
    if not configs:
        return [LinkSource(name, frozenset())]
    if len(configs) == 1:
        return [LinkSource(name, links_of_configuration(configs[0]))]
    return [LinkSource(f"{name} #{c.index}", links_of_configuration(c)) for c in configs]


def load_file_sources(path: str | Path) -> list[LinkSource]:
    """Read a ``.pdcfg`` (config_codec) or a system file; errors name the file and where."""
    return load_file(path)[0]


#: A file's link sources, and its stored configuration when it is a ``.pdcfg``.
FileSources = tuple[list[LinkSource], ConfigCollection | None]


def load_file(path: str | Path) -> FileSources:
    """The file's sources, and its stored configuration when it is a ``.pdcfg``."""
    path = Path(path)
    if path.suffix.lower() == ".pdcfg":
        from pdcp_studio.app.documents.config_document import load_config_file

        collection = load_config_file(path)  # a bad file's error names it
        return sources_of_collection(path.name, collection), collection
    from pdcp_studio.storage import system_file

    return [LinkSource(path.name, links_of_system(system_file.load_path(path)))], None


def compare(sources: Sequence[LinkSource]) -> list[CompareRow]:
    """Every link of any source, sorted, with where it is present."""
    union: set[Link] = set()
    for s in sources:
        union |= s.links
    return [CompareRow(link, tuple(link in s.links for s in sources)) for link in sorted(union)]


def ref_label(system: System | None, ref: ChannelRef) -> str:
    """``Control unit #3 (2/2/5)`` when the system knows the device, else the reference."""
    device = system.device(ref.device) if system is not None else None
    if device is None:
        return str(ref)
    name = device.name or device.descriptor
    return f"{name} #{ref.index} ({ref.device})" if name else str(ref)


class CompareDialog(QDialog):
    """Links side by side: on screen, a file and the arbitrator (see the module docstring)."""

    compared = Signal()
    error = Signal(str)

    def __init__(self, system: System, *, bridge: SessionBridge | None = None,
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(self.tr("Compare configurations"))
        self.resize(860, 480)
        self.system = system
        self.bridge = bridge
        self.file_sources: list[LinkSource] = []
        self.arbitrator_sources: list[LinkSource] = []
        #: The stored configurations behind the file and arbitrator columns (when known).
        self.file_collection: ConfigCollection | None = None
        self.arbitrator_collection: ConfigCollection | None = None
        self._rows: list[CompareRow] = []
        self._workers: set[Worker] = set()

        self.table = QTableWidget()
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        self.table.setSelectionBehavior(QTableWidget.SelectionBehavior.SelectRows)
        self.table.verticalHeader().setVisible(False)
        self.table.setWordWrap(False)
        self.table.setTextElideMode(Qt.TextElideMode.ElideMiddle)  # keep the keys visible
        self.summary = QLabel()
        self.summary.setWordWrap(True)
        self.open_button = QPushButton(self.tr("Open file…"))
        self.open_button.clicked.connect(self._ask_file)
        self.read_button = QPushButton(self.tr("Read arbitrator"))
        self.read_button.clicked.connect(self.read_arbitrator)
        self.read_button.setEnabled(bridge is not None)
        if bridge is None:
            self.read_button.setToolTip(self.tr("Connect to a bus to read its arbitrator"))
        self.diff_only = QCheckBox(self.tr("Differences only"))
        self.diff_only.toggled.connect(lambda _on: self._fill())
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Close)
        buttons.rejected.connect(self.reject)

        bar = QHBoxLayout()
        for w in (self.open_button, self.read_button, self.diff_only):
            bar.addWidget(w)
        bar.addStretch(1)
        layout = QVBoxLayout(self)
        layout.addLayout(bar)
        layout.addWidget(self.table)
        layout.addWidget(self.summary)
        layout.addWidget(buttons)
        self.error.connect(
            lambda msg: self.summary.setText(self.tr("<b>Error:</b> {msg}").format(msg=msg))
        )
        self.refresh()

    # -- sources ---------------------------------------------------------------------------
    def sources(self) -> list[LinkSource]:
        """The compared sources in column order: on screen, file, arbitrator."""
        return [
            LinkSource(translate("CompareDialog", ON_SCREEN), links_of_system(self.system)),
            *self.file_sources,
            *self.arbitrator_sources,
        ]

    def set_system(self, system: System) -> None:
        """Compare another on-screen system."""
        self.system = system
        self.refresh()

    def set_file_sources(self, sources: list[LinkSource],
                         collection: ConfigCollection | None = None) -> None:
        """Use these sources as the file's columns (``collection``: its stored configuration)."""
        self.file_sources = list(sources)
        self.file_collection = collection
        self.refresh()

    def _file_loaded(self, loaded: FileSources) -> None:
        self.set_file_sources(*loaded)

    def set_arbitrator(self, collection: ConfigCollection | None) -> None:
        """Show a stored configuration read from the arbitrator (None: it stores none)."""
        self.arbitrator_sources = sources_of_collection(ARBITRATOR, collection)
        self.arbitrator_collection = collection
        self.refresh()

    def _track(self, worker: Worker) -> Worker:
        self._workers.add(worker)  # kept until the dialog goes: its slots must still run
        return worker

    def load_file(self, path: str | Path) -> Worker:
        """Read a system file or ``.pdcfg`` on a worker; the table follows when it is read."""
        self.summary.setText(self.tr("Reading {name}…").format(name=Path(path).name))

        def work(_p: ProgressFn, _c: threading.Event) -> FileSources:
            return load_file(path)

        worker = Worker(work, f"Read {path}")
        worker.finished.connect(self._file_loaded)  # bound slots only: Qt drops them
        worker.failed.connect(self._file_failed)  # if the dialog is deleted meanwhile
        return self._track(worker).start()

    def _file_failed(self, message: str) -> None:
        self.error.emit(message)

    def read_arbitrator(self) -> Worker | None:
        """Read the arbitrator's stored configuration through the bridge."""
        if self.bridge is None:
            self.error.emit(self.tr("Not connected to a bus: there is no arbitrator to read"))
            return None
        worker = self.bridge.read_configuration()
        if worker is None:
            return None
        self.read_button.setEnabled(False)
        self.summary.setText(self.tr("Reading the arbitrator's stored configuration…"))
        worker.finished.connect(self.set_arbitrator)
        worker.failed.connect(self._read_failed)
        worker.done.connect(self._read_done)
        return self._track(worker)

    def _read_failed(self, message: str) -> None:
        self.error.emit(self.tr("Reading the arbitrator: {message}").format(message=message))

    def _read_done(self) -> None:
        self.read_button.setEnabled(self.bridge is not None)

    def _ask_file(self) -> None:
        path, _ = QFileDialog.getOpenFileName(
            self, self.tr("Compare with a file"), "",
            self.tr("Configurations and systems (*.pdcfg *.json);;All files (*)"))
        if path:
            self.load_file(path)

    # -- table -----------------------------------------------------------------------------
    def rows(self) -> list[CompareRow]:
        """Every compared link (the filter does not apply)."""
        return list(self._rows)

    def set_differences_only(self, on: bool) -> None:
        """Hide the links every source has."""
        self.diff_only.setChecked(on)

    def refresh(self) -> None:
        """Compare again and rebuild the table."""
        self._rows = compare(self.sources())
        self._fill()

    def _fill(self) -> None:
        sources = self.sources()
        names = [s.name for s in sources]
        shown = [r for r in self._rows if not (self.diff_only.isChecked() and r.everywhere)]
        self.table.clear()
        self.table.setColumnCount(3 + len(names))
        self.table.setHorizontalHeaderLabels(
            [self.tr("Output"), self.tr("Input"), *names, self.tr("Status")]
        )
        self.table.setRowCount(len(shown))
        for i, row in enumerate(shown):
            cells = [ref_label(self.system, row.link.output),
                     ref_label(self.system, row.link.input),
                     *[TICK if p else "" for p in row.present], row.status(names)]
            for col, text in enumerate(cells):
                item = QTableWidgetItem(text)
                item.setToolTip(text)
                if 2 <= col < 2 + len(names):
                    item.setTextAlignment(Qt.AlignmentFlag.AlignCenter)
                if not row.everywhere:
                    item.setBackground(QBrush(ONLY_COLOUR))
                    item.setForeground(QBrush(QColor(0, 0, 0)))
                self.table.setItem(i, col, item)
        header = self.table.horizontalHeader()
        header.setStretchLastSection(False)
        for col in range(self.table.columnCount()):  # the ends share the width; ticks fit
            header.setSectionResizeMode(col, QHeaderView.ResizeMode.Stretch if col < 2
                                        else QHeaderView.ResizeMode.ResizeToContents)
        counts: dict[str, int] = {}
        for row in self._rows:
            status = row.status(names)
            counts[status] = counts.get(status, 0) + 1
        parts = [f"{n} {status}" for status, n in sorted(counts.items())]
        text = self.tr("{0}: {1}").format(count("CompareDialog", "%n link(s)", len(self._rows)),
                                                  ", ".join(parts) or self.tr("none"))
        if self.file_collection is not None and self.arbitrator_collection is not None:
            from pdcp_studio.model.config_diff import diff_configurations

            name = self.file_sources[0].name.split(" #")[0] if self.file_sources else "file"
            diff = diff_configurations(self.file_collection, self.arbitrator_collection)
            text += ("<br>Stored configurations, record by record: "
                     + html.escape(diff.describe(name, ARBITRATOR)))
        self.summary.setText(text)
        self.compared.emit()
