"""Markers in the trace: a frame marked by name, and times counted from the newest marker
(or the one jumped to)."""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.bar import TraceBar
from pdcp_studio.app.trace.model import TraceModel, TraceView


class Marker(NamedTuple):
    index: int  # type: ignore[assignment]  # the absolute frame index
    time: float
    name: str


class Markers:
    """The markers of what the table shows, listed in the bar's marker box.

    ``select_row(row)`` shows a table row (the dock's, which also stops autoscrolling)."""

    def __init__(self, model: TraceModel, view: TraceView, bar: TraceBar,
                 select_row: Callable[[int], None]) -> None:
        self._model, self._view, self._bar, self._select_row = model, view, bar, select_row
        self.items: list[Marker] = []

    def add(self, name: str = "") -> Marker | None:
        """Mark the selected frame, or the newest frame shown; times since a marker count
        from the newest marker until another is chosen."""
        current = self._view.currentIndex()
        m = self._model
        if current.isValid():
            index = m.absolute(current.row())
        elif m.rowCount():
            index = m.absolute(m.rowCount() - 1)
        else:
            return None
        marker = Marker(index, m.store.timestamp(index), name or translate(
            "MonitorDock", "Marker {n}").format(n=len(self.items) + 1))
        self.items.append(marker)
        m.markers[index] = marker.name
        m.set_marker_time(marker.time)
        row = m.row_of(index)
        if row is not None:
            m.dataChanged.emit(m.index(row, 0), m.index(row, m.columnCount() - 1))
        self.refresh()
        self._bar.marker_box.setCurrentIndex(len(self.items) - 1)
        return marker

    def jump(self, i: int) -> None:
        """Select the marked frame (or the first shown after it) and count from it."""
        if not 0 <= i < len(self.items):
            return
        marker = self.items[i]
        self._model.set_marker_time(marker.time)
        row = self._model.row_of(marker.index, nearest=True)
        if row is not None:
            self._select_row(row)

    def clear(self) -> None:
        self.items.clear()
        self.refresh()

    def refresh(self) -> None:
        """List the markers with their times since the table's first frame."""
        t0 = self._model.t0 or 0.0
        self._bar.refresh_markers([f"{marker.name}  {marker.time - t0:.3f} s"
                                   for marker in self.items])
