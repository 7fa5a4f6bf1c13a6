"""The trace's two tables: the frames, and the per-identifier statistics under them."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtGui import QFontDatabase
from PySide6.QtWidgets import QHeaderView, QTableView

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.model import StatsModel, TraceModel, TraceView

#: Widths of the frame table's columns but the last (which stretches).
FRAME_COLUMNS = (92, 84, 70, 150, 170)  # the ID's: an extended one's 10 characters
#: A foreign capture's Kind and DLC columns (in place of Node and Function).
PLAIN_COLUMNS = {2: 120, 3: 44}
#: The widest text of each statistics column but the last.
STATS_SAMPLES = ("0x00000000", "BA→#00 ", "000,000", "0000.000", "0000.000", "00 00 00 00 ")


def frame_table(model: TraceModel) -> TraceView:
    """One frame a row, in the fixed-width font; one row selected at a time."""
    view = TraceView()
    view.setModel(model)
    view.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
    view.verticalHeader().setVisible(False)
    view.verticalHeader().setDefaultSectionSize(18)
    view.verticalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Fixed)
    view.setSelectionBehavior(QTableView.SelectionBehavior.SelectRows)
    view.setSelectionMode(QTableView.SelectionMode.SingleSelection)
    view.setWordWrap(False)
    header = view.horizontalHeader()
    header.setStretchLastSection(True)
    for col, width in enumerate(FRAME_COLUMNS):
        header.resizeSection(col, width)
    header.setSectionResizeMode(QHeaderView.ResizeMode.Interactive)
    return view


def show_plain(view: QTableView, plain: bool) -> None:
    """The frame table's columns for plain CAN (Kind, DLC; no meaning) or for PDCP."""
    header = view.horizontalHeader()
    for col, width in PLAIN_COLUMNS.items():
        header.resizeSection(col, width if plain else FRAME_COLUMNS[col])
    view.setColumnHidden(5, plain)


def stats_table(model: StatsModel) -> TraceView:
    """One identifier a row, each column as wide as its widest text or its title."""
    view = TraceView()
    view.setModel(model)
    view.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
    view.verticalHeader().setVisible(False)
    view.verticalHeader().setDefaultSectionSize(18)
    view.setWordWrap(False)
    view.setSelectionBehavior(QTableView.SelectionBehavior.SelectRows)
    view.horizontalHeader().setStretchLastSection(True)
    metrics = view.fontMetrics()
    for col, sample in enumerate(STATS_SAMPLES):
        head = str(model.headerData(col, Qt.Orientation.Horizontal))
        view.horizontalHeader().resizeSection(
            col, max(metrics.horizontalAdvance(sample),
                     view.horizontalHeader().fontMetrics().horizontalAdvance(head)) + 14)
    view.setToolTip(translate("MonitorDock", "Per identifier: frames counted, mean period, "
                                             "last period, last data and what it means. "
                                             "Double-click to show only that identifier."))
    return view
