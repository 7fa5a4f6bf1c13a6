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

Pure helpers (no widgets): ``links_of_system``, ``links_of_configuration``, ``end_words``,
``link_label``,
``sources_of_collection``, ``load_file_sources(path)``, ``compare(sources)``.

Each end of a link is named as the plan table names it (part, channel, what it carries;
the serial number where two parts read alike), wrapped rather than cut, with the numbers in
its tooltip. The summary is in words (counts, the differing links by name); when a stored
configuration is known on both sides (a ``.pdcfg`` and the arbitrator's), how they differ
record by record — with the one configuration diff (:mod:`pdcp_studio.model.config_diff`)
that ``config diff`` and the write dialog use — is in the Technical details below it.
"""

from __future__ import annotations

import html
import threading
from collections.abc import Callable, Sequence
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
    QPlainTextEdit,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QToolButton,
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
#: The differing links the summary names (the table has them all).
SUMMARY_LINKS = 5
#: ``profile_name(profile)``: what a channel's profile is called (empty: unknown).
ProfileName = Callable[[int], str]


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
    """``Control unit #3 (2/2/5)`` when the system knows the device, else the reference
    (the write dialog's engineer's form)."""
    device = system.device(ref.device) if system is not None else None
    if device is None:
        return str(ref)
    name = device.name or device.descriptor
    return f"{name} #{ref.index} ({ref.device})" if name else str(ref)


def end_words(system: System | None, ref: ChannelRef,
              profile_name: ProfileName | None = None) -> str:
    """``Control unit, channel 3 (Power grip)``: the part as every panel names it (its
    serial number where two read alike), the channel and what it carries."""
    from pdcp_studio.app.words.plan_words import channel_words

    ch = system.channel(ref) if system is not None else None
    carries = ""
    if ch is not None and ch.profile and profile_name is not None:
        carries = profile_name(ch.profile)
        carries = "" if carries.startswith("0x") else carries
    return channel_words(system, ref, carries or (ch.descriptor if ch is not None else ""))


def link_label(system: System | None, link: Link,
               profile_name: ProfileName | None = None) -> str:
    """A link in words: its output's label → its input's."""
    return (f"{end_words(system, link.output, profile_name)} → "
            f"{end_words(system, link.input, profile_name)}")


class CompareDialog(QDialog):
    """Links side by side: on screen, a file and the arbitrator (see the module docstring)."""

    compared = Signal()
    error = Signal(str)

    def __init__(self, system: System, *, bridge: SessionBridge | None = None,
                 profile_name: ProfileName | None = None,
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(self.tr("Compare configurations"))
        self.resize(980, 520)
        self.system = system
        self.profile_name = profile_name
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
        self.table.setWordWrap(True)  # long names wrap: rows alike never read the same
        self.table.setTextElideMode(Qt.TextElideMode.ElideMiddle)  # cut, the channel stays
        self.table.verticalHeader().setSectionResizeMode(
            QHeaderView.ResizeMode.ResizeToContents)
        self.summary = QLabel()
        self.summary.setWordWrap(True)
        self.summary.setTextFormat(Qt.TextFormat.RichText)
        self.summary.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.details_button = QToolButton()
        self.details_button.setText(self.tr("Technical details"))
        self.details_button.setCheckable(True)
        self.details_button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextBesideIcon)
        self.details_button.setArrowType(Qt.ArrowType.RightArrow)
        self.details_button.toggled.connect(self._show_details)
        self.details = QPlainTextEdit()
        self.details.setReadOnly(True)
        self.details.setMaximumHeight(140)
        self.details.setVisible(False)
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
        layout.addWidget(self.table, 1)
        layout.addWidget(self.summary)
        layout.addWidget(self.details_button)
        layout.addWidget(self.details)
        layout.addWidget(buttons)
        self.error.connect(
            lambda msg: self.summary.setText(self.tr("<b>Error:</b> {msg}").format(msg=msg))
        )
        self.refresh()

    def _show_details(self, shown: bool) -> None:
        self.details.setVisible(shown)
        self.details_button.setArrowType(Qt.ArrowType.DownArrow if shown
                                         else Qt.ArrowType.RightArrow)

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
        label = {ref: end_words(self.system, ref, self.profile_name)
                 for row in shown for ref in (row.link.output, row.link.input)}
        for i, row in enumerate(shown):
            ends = (row.link.output, row.link.input)
            cells = [label[ends[0]], label[ends[1]],
                     *[TICK if p else "" for p in row.present], row.status(names)]
            for col, text in enumerate(cells):
                item = QTableWidgetItem(text)
                # The whole name, and the numbers an engineer reads.
                item.setToolTip(f"{text}\n{ends[col]}" if col < 2 else text)
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
        text, technical = self._summary(names)
        self.details.setPlainText(technical)
        self.details_button.setVisible(bool(technical))
        self.details.setVisible(bool(technical) and self.details_button.isChecked())
        self.summary.setText(text)
        self.compared.emit()

    def _summary(self, names: list[str]) -> tuple[str, str]:
        """The summary in words (rich text) and the technical part (codes; may be empty)."""
        counts: dict[str, int] = {}
        for row in self._rows:
            status = row.status(names)
            counts[status] = counts.get(status, 0) + 1
        parts = [f"{n} {status}" for status, n in sorted(counts.items())]
        text = html.escape(self.tr("{0}: {1}").format(
            count("CompareDialog", "%n link(s)", len(self._rows)),
            ", ".join(parts) or self.tr("none")))
        differing = [r for r in self._rows if not r.everywhere]
        if differing and len(names) > 1:
            lines = [html.escape(f"{link_label(self.system, r.link, self.profile_name)}: "
                                 f"{r.status(names)}") for r in differing[:SUMMARY_LINKS]]
            more = len(differing) - SUMMARY_LINKS
            if more > 0:
                lines.append(html.escape(count("CompareDialog", "and %n more", more)))
            text += "<br>" + html.escape(self.tr("Where they differ:")) + "<br>&nbsp;&nbsp;" \
                + "<br>&nbsp;&nbsp;".join(lines)
        technical = ""
        if self.file_collection is not None and self.arbitrator_collection is not None:
            from pdcp_studio.model.config_diff import diff_configurations

            name = (self.file_sources[0].name.split(" #")[0] if self.file_sources
                    else self.tr("the file"))
            diff = diff_configurations(self.file_collection, self.arbitrator_collection)
            records = diff.lines(name, ARBITRATOR)
            if records:
                said = count("CompareDialog", "The stored configurations of {0} and of the "
                             "arbitrator differ in %n place(s).", len(records))
            else:
                said = self.tr("The stored configurations of {0} and of the arbitrator are "
                               "the same, record by record.")
            text += "<br>" + html.escape(said.format(name))
            technical = "\n".join(records) or "no difference"
        return text, technical
