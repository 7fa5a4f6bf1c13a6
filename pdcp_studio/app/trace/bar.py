"""The trace's controls: filters, search and markers, and the row of actions (pause,
record, clear, open, save), in three short rows so the dock never widens the window.

``TraceBar`` makes the widgets and lays them out; the dock connects them. Their texts are
the dock's (translation context ``MonitorDock``).
"""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import QT_TRANSLATE_NOOP, Qt
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QProgressBar,
    QSizePolicy,
    QToolButton,
    QWidget,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.model import TIME_MODES
from pdcp_studio.app.trace.store import CHANNEL_DATA
from pdcp_studio.protocol.codes import FunctionCode

ANY = QT_TRANSLATE_NOOP("MonitorDock", "(any)")
_COMPACT = QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon


def _tool_button(text: str) -> QToolButton:
    """A compact text button (the dock's rows stay narrow)."""
    button = QToolButton()
    button.setText(text)
    button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextOnly)
    return button


def _combo(contents: int) -> QComboBox:
    box = QComboBox()
    box.setSizeAdjustPolicy(_COMPACT)
    box.setMinimumContentsLength(contents)
    return box


class NodeChoice:
    """The node filter's list: the nodes named by the system (``names``) and those heard."""

    def __init__(self, box: QComboBox) -> None:
        self._box = box
        self.names: dict[int, str] = {}
        self._heard: set[int] = set()
        self.fill()

    def fill(self) -> None:
        """List the nodes, keeping the one chosen; no signal is emitted."""
        box = self._box
        current = box.currentData() if box.count() else None
        box.blockSignals(True)
        try:
            box.clear()
            box.addItem(translate("MonitorDock", "Any node"), None)
            box.addItem(translate("MonitorDock", "Broadcast"), 0)
            for node in sorted((set(self.names) | self._heard) - {0}):
                name = self.names.get(node)
                box.addItem(translate("MonitorDock", "{name} (node {node})").format(
                    name=name, node=node) if name else translate(
                    "MonitorDock", "Node {node}").format(node=node), node)
            found = box.findData(current)
            box.setCurrentIndex(max(0, found))
        finally:
            box.blockSignals(False)

    def learn(self, system: Any) -> None:
        """Name the nodes of ``system``'s devices and output channels."""
        from pdcp_studio.app.words.part_names import names

        naming = names(system)  # the one names (``model/names.py``), looked up once
        for device in system.devices.values():
            if device.node_id is not None:
                self.names[device.node_id] = naming.part(device.key)
        for ref, ch in system.channels():
            if ch.is_output and ch.node_id is not None:
                self.names[ch.node_id] = naming.channel(ref)
        self.fill()

    def heard(self, nodes: set[int]) -> None:
        """Frames came from ``nodes``: list those not listed yet."""
        if not nodes <= self._heard | set(self.names) | {0}:
            self._heard |= nodes
            self.fill()

    def include(self, node: int) -> None:
        """List ``node`` (to be chosen) if it is not listed."""
        if self._box.findData(node) < 0:
            self._heard.add(node)
            self.fill()


class TraceBar:
    """The control widgets and the three rows that hold them (``rows``)."""

    def __init__(self) -> None:
        self.text_filter = QLineEdit()
        self.text_filter.setPlaceholderText(translate("MonitorDock", "Filter text, ID or data…"))
        self.text_filter.setClearButtonEnabled(True)
        self.function_filter = _combo(12)
        self.function_filter.addItem(translate("MonitorDock", str(ANY)), ANY)
        self.function_filter.addItems([CHANNEL_DATA, *sorted({c.title for c in FunctionCode})])
        self.node_filter = _combo(12)
        self.node_filter.setToolTip(translate("MonitorDock", "Show the frames of one node only"))
        self.nodes = NodeChoice(self.node_filter)
        self.find_edit = QLineEdit()
        self.find_edit.setPlaceholderText(translate("MonitorDock", "Find text or ID…"))
        self.find_edit.setClearButtonEnabled(True)
        self.find_prev = QToolButton()
        self.find_prev.setText("▲")
        self.find_prev.setToolTip(translate("MonitorDock", "Find the previous frame"))
        self.find_next = QToolButton()
        self.find_next.setText("▼")
        self.find_next.setToolTip(translate("MonitorDock", "Find the next frame"))

        self.pause_box = QCheckBox(translate("MonitorDock", "Pause"))
        self.pause_box.setToolTip(translate("MonitorDock", "Freeze the table; frames are still "
                                                           "recorded and counted"))
        self.autoscroll_box = QCheckBox(translate("MonitorDock", "Autoscroll"))
        self.autoscroll_box.setChecked(True)
        self.time_mode = _combo(12)
        for mode in TIME_MODES:
            self.time_mode.addItem(translate("TraceModel", str(mode)))
        self.time_mode.setToolTip(translate("MonitorDock", "How the Time column counts"))
        self.marker_button = _tool_button(translate("MonitorDock", "Add marker"))
        self.marker_button.setToolTip(translate("MonitorDock", "Mark the selected frame, or the "
                                                               "newest one"))
        self.marker_box = _combo(10)
        self.marker_box.setToolTip(translate("MonitorDock", "Go to a marker (times since a "
                                                            "marker count from it)"))
        from pdcp_studio.app.widgets.combo_popups import keep_whole

        keep_whole(self.marker_box)  # "Grip closes 3.89" whole, not cut
        self.marker_box.addItem(translate("MonitorDock", "No markers"))
        self.marker_box.setEnabled(False)
        self.count_label = QLabel(translate("MonitorDock", "0 frames"))
        # Long counts (and "recording to …") must not widen the dock, and so the window.
        self.count_label.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)
        self.count_label.setMinimumWidth(140)
        self.load_bar = QProgressBar()
        self.load_bar.setRange(0, 1000)
        self.load_bar.setMaximumWidth(160)
        self.load_bar.setTextVisible(True)
        self.load_bar.setVisible(False)
        self.record_button = _tool_button(translate("MonitorDock", "Record…"))
        self.record_button.setCheckable(True)
        self.record_button.setToolTip(translate("MonitorDock", "Write every live frame to a "
                                                               "capture file (the table keeps "
                                                               "only the newest ones)"))
        self.clear_button = _tool_button(translate("MonitorDock", "Clear"))
        self.save_button = _tool_button(translate("MonitorDock", "Save…"))
        self.open_button = _tool_button(translate("MonitorDock", "Open…"))
        self.open_button.setToolTip(translate("MonitorDock", "Show a capture file (python-can "
                                                             "log formats)"))
        self.live_button = _tool_button(translate("MonitorDock", "Back to live"))
        self.live_button.setToolTip(translate("MonitorDock", "Close the capture and show the "
                                                             "live frames again"))
        self.live_button.setVisible(False)
        self.stop_load_button = _tool_button(translate("MonitorDock", "Stop loading"))
        self.stop_load_button.setVisible(False)
        self.text_filter.setMinimumWidth(90)
        self.find_edit.setMinimumWidth(90)
        self.rows = self._lay_out()

    def _lay_out(self) -> tuple[QHBoxLayout, QHBoxLayout, QHBoxLayout]:
        """Filters; search, time and markers; the actions."""
        filters, finding, actions = QHBoxLayout(), QHBoxLayout(), QHBoxLayout()
        w: QWidget
        for w in (self.text_filter, self.function_filter, self.node_filter):
            filters.addWidget(w)
        filters.setStretch(0, 1)
        for w in (self.find_edit, self.find_prev, self.find_next, self.time_mode,
                  self.marker_button, self.marker_box):
            finding.addWidget(w)
        finding.setStretch(0, 1)
        for w in (self.pause_box, self.autoscroll_box, self.count_label, self.load_bar):
            actions.addWidget(w)
        actions.addStretch(1)
        for w in (self.stop_load_button, self.live_button, self.record_button,
                  self.clear_button, self.open_button, self.save_button):
            actions.addWidget(w)
        return filters, finding, actions

    def refresh_markers(self, texts: list[str]) -> None:
        """Show these markers (or "No markers") in the marker box."""
        box = self.marker_box
        box.clear()
        for text in texts:
            box.addItem(text)
        if not texts:
            box.addItem(translate("MonitorDock", "No markers"))
        box.setEnabled(bool(texts))
