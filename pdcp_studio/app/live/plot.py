"""The live plot: the values of several output channels over a chosen time window.

Public API
    ``LivePlot(parent=None, window_s=10.0, fps=15)`` — a QWidget: a bar (signals menu, time
    window, hold, cursors, clear) over a ``PlotCanvas``. Slots: ``add_values(list[
    ChannelValue])`` (connect ``SessionBridge.channelValues``), ``add_value(ChannelValue)``.
    Methods: ``set_system(system)`` (names, units and the signals menu), ``set_link(link)`` /
    ``set_channel(ref)`` (follow the selection: replace the signal that follows it; None
    removes it), ``add_channel(ref)`` / ``remove_channel(ref)`` (signals kept until removed),
    ``set_window(seconds)``, ``set_cursors(a, b)`` (seconds before now, or None),
    ``set_hold(bool)``, ``clear()``, ``cursor_readout() -> str``. State: ``series`` (one
    ``Series`` per signal), ``ref`` and ``points`` (the first signal's, ``(t, raw value)``),
    ``paint_count``. Signal: ``channelChanged(ChannelRef | None)``.

Each signal has a lane of its own with its own value axis: the raw values the channel sends,
over the range its channel type gives (``model/value_axis.py``: unsigned 12-bit 0–4095,
signed, boolean on/off; a float over the values seen) and named by what the channel carries
(its one name, ``model/names.py``: descriptor, else profile name) with the type's form:
"Flexor EMG envelope (unsigned, 0–4095)"; a velocity or acceleration says so. The
prescaler's suggested factor is a hint in the lane's title only, never multiplied in
(reference §2, Decision: no computation depends on it). The title goes on with the part and
the parts it feeds, by their one names.
Ticks are 1-2-5 steps on both axes. Two vertical cursors (left click sets A, right click B,
drag moves the nearest) show Δt and each signal's values at A and B and their difference.

Painted by hand on a plain QWidget (QtCharts measured 40 % slower and 4× the memory, and
pyqtgraph would add a dependency for what is here a few hundred lines). A saturated bus
brings thousands of values a second: each lane is reduced to its minimum and maximum per
pixel column with numpy before drawing, so a repaint costs the same for 100 or 100,000
points; repaints are capped at ``fps``.
"""

from __future__ import annotations

import math
from array import array
from collections.abc import Callable, Iterable
from typing import Any, cast

import numpy as np
import shiboken6
from PySide6.QtCore import QPointF, QRectF, Qt, QTimer, Signal
from PySide6.QtGui import QColor, QMouseEvent, QPainter, QPaintEvent, QPen, QPolygonF
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QHBoxLayout,
    QLabel,
    QMenu,
    QPushButton,
    QSizePolicy,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.model.value_axis import ValueAxis, value_axis

DEFAULT_WINDOW_S = 10.0
WINDOWS_S = (1.0, 2.0, 5.0, 10.0, 30.0, 60.0)
#: Values kept per signal (older ones beyond the longest window are dropped too).
MAX_POINTS = 200_000
MAX_SIGNALS = 8
COLORS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b",
          "#e377c2")


def as_number(value: Any) -> float | None:
    """A plottable number from a channel value (int, float, bool or little-endian bytes)."""
    if isinstance(value, bool):
        return float(value)
    if isinstance(value, int | float):
        return float(value)
    if isinstance(value, bytes | bytearray | memoryview):
        raw = bytes(value)
        return float(int.from_bytes(raw, "little")) if raw else None
    return None


def nice_ticks(lo: float, hi: float, target: int = 5) -> list[float]:
    """Tick values in 1-2-5 steps covering ``lo … hi`` (about ``target`` of them)."""
    if not math.isfinite(lo) or not math.isfinite(hi) or hi <= lo:
        return [lo]
    raw = (hi - lo) / max(1, target)
    mag = 10 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 5, 10) if m * mag >= raw)
    first = math.ceil(lo / step) * step
    ticks, k = [], 0
    while first + k * step <= hi + step * 1e-9 and k < 100:
        ticks.append(round(first + k * step, 12))
        k += 1
    return ticks


def bounded_ticks(ticks: list[float], bounds: tuple[float, float], step: float) -> list[float]:
    """``ticks`` with the type's least and greatest value added (0 and 4095 on a 12-bit
    axis, so its range reads on the axis however short the lane); a tick within a third of
    a step of either is left out, so no two labels overlap."""
    lo, hi = bounds
    inner = [t for t in ticks if lo + step / 3 < t < hi - step / 3]
    return [lo, *inner, hi]


def tick_text(value: float, step: float) -> str:
    """A tick label with as many decimals as the step needs."""
    decimals = max(0, -math.floor(math.log10(step))) if step > 0 else 0
    return f"{value:.{min(decimals, 6)}f}"


_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def factor_text(hint: str) -> str:
    """``×10⁻³`` for the thesis's suggested factor ``1e-3`` ("" for 1)."""
    if hint in ("", "1"):
        return ""
    mantissa, _e, exponent = hint.partition("e")
    if not exponent:
        return f"×{hint}"
    power = "10" if exponent in ("1", "+1") else "10" + exponent.lstrip("+").translate(
        _SUPERSCRIPT)
    return f"×{power}" if mantissa == "1" else f"×{mantissa}·{power}"


def channel_axis(ctype: int | None) -> tuple[str, str, bool]:
    """(quantity, hint, boolean) for an output channel's type value: the value axis's name
    from the control mode, the prescaler's suggested factor as a hint (``1e-3``; shown,
    never multiplied in), and whether it is on/off."""
    if ctype is None:
        return translate("LivePlot", "value"), "1", False
    from pdcp_studio.model.channel_type import ChannelType, ControlMode, DataType

    t = ChannelType(ctype)
    names = {ControlMode.POSITION: translate("LivePlot", "position"),
             ControlMode.VELOCITY: translate("LivePlot", "velocity"),
             ControlMode.ACCELERATION: translate("LivePlot", "acceleration"),
             ControlMode.OTHER: translate("LivePlot", "value")}
    return names[t.control_mode], t.prescaler_hint, t.data_type is DataType.BOOLEAN


def axis_words(what: str, axis: ValueAxis) -> str:
    """``Flexor EMG envelope (unsigned, 0–4095)``: the value axis's name, from what the
    channel carries and its type (a velocity or acceleration says so; no physical unit is
    known, so none is claimed)."""
    from pdcp_studio.model.channel_type import ControlMode, DataType

    mode = {ControlMode.POSITION: translate("LivePlot", "position"),
            ControlMode.VELOCITY: translate("LivePlot", "velocity"),
            ControlMode.ACCELERATION: translate("LivePlot", "acceleration")}.get(
                axis.mode) if axis.mode is not None else None
    if axis.boolean:
        return translate("LivePlot", "{what} (on/off)").format(
            what=what or translate("LivePlot", "value"))
    form = []
    if not what:  # nothing names it: the control mode is the quantity
        what = mode or translate("LivePlot", "value")
    elif axis.mode in (ControlMode.VELOCITY, ControlMode.ACCELERATION) and mode:
        form.append(mode)
    kind = {DataType.UNSIGNED: translate("LivePlot", "unsigned"),
            DataType.SIGNED: translate("LivePlot", "signed"),
            DataType.FLOAT: translate("LivePlot", "float")}.get(
                axis.data_type) if axis.data_type is not None else None
    if kind:
        form.append(kind)
    if axis.lo is not None and axis.hi is not None:
        form.append(f"{axis.lo:g}–{axis.hi:g}".replace("-", "−"))  # a minus, not a hyphen
    return f"{what} ({', '.join(form)})" if form else what


class Series:
    """One signal: its values (raw), how to show them, and whether it follows the selection."""

    def __init__(self, ref: Any, label: str, quantity: str, hint: str, boolean: bool,
                 color: str, follows: bool) -> None:
        self.ref, self.label, self.quantity = ref, label, quantity
        self.hint, self.boolean, self.color, self.follows = hint, boolean, color, follows
        #: The range and form its channel type gives (``model/value_axis.py``).
        self.axis: ValueAxis = value_axis(None)
        #: What the channel carries, by its one name ("Flexor EMG envelope").
        self.what = ""
        #: The part and the parts it feeds ("EMG flexor site → Control unit").
        self.owner = ""
        self.ts = array("d")
        self.vs = array("d")

    @property
    def unit(self) -> str:
        """The value axis's name: what the values are and the form and range the channel
        type gives ("Flexor EMG envelope (unsigned, 0–4095)")."""
        return axis_words(self.what, self.axis)

    @property
    def hint_text(self) -> str:
        """``suggested ×10⁻³``: the prescaler's factor, a hint only ("" for none)."""
        factor = "" if self.boolean else factor_text(self.hint)
        return translate("LivePlot", "suggested {factor}").format(factor=factor) \
            if factor else ""

    @property
    def title(self) -> str:
        """The lane's title: what its values are (the axis's name), the part and what it
        feeds, and the hint."""
        text = f"{self.unit} — {self.owner or self.label}"
        return f"{text}, {self.hint_text}" if self.hint_text else text

    def value_range(self) -> tuple[float, float] | None:
        """The range the value axis spans: the type's (None: a float or an unknown type,
        scaled to the values seen)."""
        if self.boolean:
            return 0.0, 1.0
        if self.axis.lo is None or self.axis.hi is None:
            return None
        return self.axis.lo, self.axis.hi

    def trim(self, keep_s: float) -> None:
        if not self.ts:
            return
        cutoff = self.ts[-1] - keep_s
        drop = int(np.searchsorted(np.frombuffer(self.ts, dtype=np.float64), cutoff))
        drop = max(drop, len(self.ts) - MAX_POINTS)
        if drop > 4096 or (drop > 0 and drop * 4 > len(self.ts)):
            del self.ts[:drop]
            del self.vs[:drop]

    def value_at(self, t: float) -> float | None:
        """The raw value last sent at or before ``t`` (None before the first)."""
        if not self.ts:
            return None
        i = int(np.searchsorted(np.frombuffer(self.ts, dtype=np.float64), t, side="right")) - 1
        return None if i < 0 else self.vs[i]


_LANE_EDGE = QColor(128, 128, 128, 110)


def _polygon(xs: np.ndarray, ys: np.ndarray) -> QPolygonF:
    """A polygon of the points ``(xs[i], ys[i])``, written straight into Qt's array of
    ``QPointF`` (two doubles each): a QPointF per point made in Python cost ~2 ms a lane
    of 1,200 points, a fifth of a repaint; this ~0.01 ms."""
    n = len(xs)
    polygon = QPolygonF()
    polygon.resize(n)
    if n:
        memory: Any = cast(Any, shiboken6.VoidPtr)(polygon.data(), n * 16, True)  # writable
        points = np.frombuffer(memory, dtype=np.float64).reshape(n, 2)
        points[:, 0] = xs
        points[:, 1] = ys
    return polygon


# Grid lines and lane edges as one-pixel rectangles: translucent lines take the raster
# engine's slow path (a lane's edge 1.5 ms, each grid line 0.5 ms; as rectangles ~0.02 ms).
def _hline(p: QPainter, x0: float, x1: float, y: float, color: QColor) -> None:
    p.fillRect(QRectF(round(x0), round(y), round(x1) - round(x0) + 1, 1), color)


def _vline(p: QPainter, x: float, y0: float, y1: float, color: QColor) -> None:
    p.fillRect(QRectF(round(x), round(y0), 1, round(y1) - round(y0) + 1), color)


def _frame(p: QPainter, r: QRectF, color: QColor) -> None:
    """The outline ``QPainter.drawRect(r)`` draws with a one-pixel pen."""
    _hline(p, r.left(), r.right(), r.top(), color)
    _hline(p, r.left(), r.right(), r.bottom(), color)
    _vline(p, r.left(), r.top() + 1, r.bottom() - 1, color)
    _vline(p, r.right(), r.top() + 1, r.bottom() - 1, color)


class PlotCanvas(QWidget):
    """Lanes of signals over a shared time axis, with two cursors (see the module doc)."""

    cursorsChanged = Signal()

    def __init__(self, plot: LivePlot) -> None:
        super().__init__(plot)
        self.plot = plot
        self.setMinimumSize(240, 120)
        self.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Expanding)
        self._drag: str | None = None

    # -- geometry ----------------------------------------------------------------------
    def _area(self) -> QRectF:
        m = self.fontMetrics()
        left = m.horizontalAdvance("-00000.00") + 10
        return QRectF(left, 4, max(1, self.width() - left - 10),
                      max(1, self.height() - m.height() * 2 - 10))

    def time_of_x(self, x: float) -> float:
        area = self._area()
        end, window = self.plot.t_end(), self.plot.window_s
        return end - window + (x - area.left()) / area.width() * window

    def x_of_time(self, t: float) -> float:
        area = self._area()
        end, window = self.plot.t_end(), self.plot.window_s
        return area.left() + (t - (end - window)) / window * area.width()

    # -- cursors -----------------------------------------------------------------------
    def mousePressEvent(self, event: QMouseEvent) -> None:
        t = self.time_of_x(event.position().x())
        p = self.plot
        if event.button() == Qt.MouseButton.RightButton:
            which = "b"
        elif p.cursor_a is not None and p.cursor_b is not None:
            da = abs(self.x_of_time(p.cursor_a) - event.position().x())
            db = abs(self.x_of_time(p.cursor_b) - event.position().x())
            which = "a" if da <= db else "b"
        else:
            which = "a" if p.cursor_a is None or p.cursor_b is not None else "b"
        self._drag = which
        p.set_hold(True)  # cursors on a moving trace would run away
        p._set_cursor(which, t)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        if self._drag is not None:
            self.plot._set_cursor(self._drag, self.time_of_x(event.position().x()))

    def mouseReleaseEvent(self, _event: QMouseEvent) -> None:
        self._drag = None

    # -- painting ----------------------------------------------------------------------
    def paintEvent(self, _event: QPaintEvent) -> None:
        plot = self.plot
        plot._painted()
        p = QPainter(self)
        try:
            self._paint(p)
        finally:
            p.end()

    def _paint(self, p: QPainter) -> None:
        plot = self.plot
        pal = self.palette()
        p.fillRect(self.rect(), pal.base())
        m = p.fontMetrics()
        text_pen = QPen(pal.text().color())
        grid = QColor(128, 128, 128, 60)
        area = self._area()
        series = plot.series
        end, window = plot.t_end(), plot.window_s
        start = end - window
        p.setPen(text_pen)
        if not series:
            p.drawText(area, Qt.AlignmentFlag.AlignCenter, translate(
                "LivePlot", "Choose signals to plot: select a link or channel on the bus, or "
                "use Signals."))
            return
        # time axis, shared by the lanes: ticks in seconds before now
        step_t = nice_ticks(-window, 0.0, max(2, int(area.width() // 90)))
        t_step = step_t[1] - step_t[0] if len(step_t) > 1 else window
        for rel in step_t:
            x = area.left() + (rel + window) / window * area.width()
            _vline(p, x, area.top(), area.bottom(), grid)
            p.setPen(text_pen)
            label = tick_text(rel, t_step) + (" s" if rel == step_t[-1] else "")
            p.drawText(QRectF(x - 40, area.bottom() + 2, 80, m.height()),
                       Qt.AlignmentFlag.AlignHCenter, label)
        p.drawText(QRectF(area.left(), area.bottom() + 2 + m.height(), area.width(),
                          m.height()), Qt.AlignmentFlag.AlignHCenter,
                   translate("LivePlot", "time before now (s)") if not plot.hold else
                   translate("LivePlot", "time before the hold (s)"))
        lane_h = area.height() / len(series)
        for i, s in enumerate(series):
            lane = QRectF(area.left(), area.top() + i * lane_h, area.width(), lane_h)
            self._paint_lane(p, s, lane, start, end, text_pen, grid)
        for name, t in (("A", plot.cursor_a), ("B", plot.cursor_b)):
            if t is None or not start <= t <= end:
                continue
            x = self.x_of_time(t)
            p.setPen(QPen(QColor(0, 0, 0) if name == "A" else QColor(90, 90, 90), 1,
                          Qt.PenStyle.DashLine))
            p.drawLine(QPointF(x, area.top()), QPointF(x, area.bottom()))
            # the letter at the foot of the line: the lanes' titles are at their tops
            p.drawText(QRectF(x + 3, area.bottom() - m.height() - 2, 20, m.height()),
                       Qt.AlignmentFlag.AlignLeft, name)

    def _paint_lane(self, p: QPainter, s: Series, lane: QRectF, start: float, end: float,
                    text_pen: QPen, grid: QColor) -> None:
        m = p.fontMetrics()
        _frame(p, lane, _LANE_EDGE)
        all_ts = np.frombuffer(s.ts, dtype=np.float64)  # views: no copy of 200,000 values
        first = int(np.searchsorted(all_ts, start, side="left"))
        first = max(0, first - 1)  # the line comes in from the left edge
        ts = all_ts[first:].copy()  # the window only (the arrays stay resizable)
        vs = np.frombuffer(s.vs, dtype=np.float64)[first:].copy()  # raw values
        del all_ts
        bounds = s.value_range()
        if s.boolean:
            lo, hi = -0.2, 1.2
        elif bounds is not None:  # the type's range, a little room at each end
            lo, hi = bounds
            if len(vs):  # a value outside it (a type changed under way) still shows
                lo, hi = min(lo, float(vs.min())), max(hi, float(vs.max()))
            pad = (hi - lo) * 0.04
            lo, hi = lo - pad, hi + pad
        elif len(vs):
            lo, hi = float(vs.min()), float(vs.max())
            if hi - lo < 1e-9:
                lo, hi = lo - 1.0, hi + 1.0
            pad = (hi - lo) * 0.08
            lo, hi = lo - pad, hi + pad
        else:
            lo, hi = 0.0, 1.0
        top = lane.top() + m.height() + 2
        body = QRectF(lane.left(), top, lane.width(), max(4.0, lane.bottom() - top - 2))
        ticks = [0.0, 1.0] if s.boolean else nice_ticks(
            lo, hi, max(2, int(body.height() // (m.height() * 2))))
        step = ticks[1] - ticks[0] if len(ticks) > 1 else 1.0
        if bounds is not None and not s.boolean:
            ticks = bounded_ticks(ticks, bounds, step)
        for v in ticks:
            y = body.bottom() - (v - lo) / (hi - lo) * body.height()
            _hline(p, body.left(), body.right(), y, grid)
            p.setPen(text_pen)
            text = (translate("LivePlot", "on") if v else translate("LivePlot", "off")) \
                if s.boolean else tick_text(v, step)
            p.drawText(QRectF(0, y - m.height() / 2, body.left() - 4, m.height()),
                       Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter, text)
        color = QColor(s.color)
        p.setPen(color)
        p.drawText(QRectF(lane.left() + 4, lane.top() + 1, lane.width() - 8, m.height()),
                   Qt.AlignmentFlag.AlignLeft, m.elidedText(
                       s.title, Qt.TextElideMode.ElideRight,
                       int(lane.width() - 8)))
        if not len(ts):
            return
        sx = body.width() / (end - start)
        sy = body.height() / (hi - lo)
        xs = (ts - start) * sx
        cols = np.floor(xs).astype(np.int64)
        if len(xs) > 2 * body.width():  # min and max per pixel column
            starts = np.concatenate(([0], np.flatnonzero(np.diff(cols)) + 1))
            lows = np.minimum.reduceat(vs, starts)
            highs = np.maximum.reduceat(vs, starts)
            xs = np.repeat(cols[starts].astype(np.float64), 2)
            vs = np.empty(2 * len(starts))
            vs[0::2], vs[1::2] = lows, highs
        polygon = _polygon(body.left() + xs, body.bottom() - (vs - lo) * sy)
        p.save()
        p.setClipRect(body)
        # Antialiased lines cost ~10× more to draw: only for a sparse trace.
        p.setRenderHint(QPainter.RenderHint.Antialiasing, polygon.size() < 400)
        p.setPen(QPen(color, 1.5 if polygon.size() < 400 else 1.0))
        if polygon.size() == 1:
            p.drawEllipse(polygon.at(0), 2.0, 2.0)
        else:
            p.drawPolyline(polygon)
        p.restore()


class LivePlot(QWidget):
    """Several output channels' values over a rolling window (see the module doc)."""

    channelChanged = Signal(object)

    def __init__(self, parent: QWidget | None = None, window_s: float = DEFAULT_WINDOW_S,
                 fps: int = 15) -> None:
        super().__init__(parent)
        self.window_s = float(window_s)
        self.series: list[Series] = []
        self.system: Any = None
        #: ``profile_name(code) -> str``: what a profile carries, by the profile tree's
        #: names (the window sets the document's); a channel without a descriptor is named so.
        self.profile_name: Callable[[int], str] | None = None
        self.hold = False
        self._hold_at: float | None = None
        self.cursor_a: float | None = None
        self.cursor_b: float | None = None
        self.paint_count = 0
        self._min_interval_ms = max(1, 1000 // max(1, fps))
        self._later = QTimer(self)
        self._later.setSingleShot(True)
        self._later.timeout.connect(self._request_repaint)
        self._dirty = False
        self._last_paint_ms = -1e9
        from PySide6.QtCore import QElapsedTimer

        self._clock = QElapsedTimer()
        self._clock.start()

        self.canvas = PlotCanvas(self)
        self.signals_button = QToolButton()
        self.signals_button.setText(self.tr("Signals"))
        self.signals_button.setToolTip(self.tr("Choose the output channels to plot"))
        self.signals_button.setPopupMode(QToolButton.ToolButtonPopupMode.InstantPopup)
        self.signals_menu = QMenu(self.signals_button)
        self.signals_menu.aboutToShow.connect(self._fill_signals_menu)
        self.signals_button.setMenu(self.signals_menu)
        self.window_box = QComboBox()
        for seconds in WINDOWS_S:
            self.window_box.addItem(self.tr("Last {n} s").format(n=f"{seconds:g}"), seconds)
        self.window_box.setToolTip(self.tr("How much time the plot shows"))
        self.window_box.currentIndexChanged.connect(
            lambda i: self.set_window(float(self.window_box.itemData(i))))
        self.hold_box = QCheckBox(self.tr("Hold"))
        self.hold_box.setToolTip(self.tr("Freeze the plot to read it; values keep being "
                                         "recorded"))
        self.hold_box.toggled.connect(self.set_hold)
        self.cursor_button = QPushButton(self.tr("Clear cursors"))
        self.cursor_button.setToolTip(self.tr("Click the plot to set cursor A, right-click "
                                              "for cursor B; drag to move them"))
        self.cursor_button.clicked.connect(lambda: self.set_cursors(None, None))
        self.clear_button = QPushButton(self.tr("Clear"))
        self.clear_button.clicked.connect(self.clear)
        self.readout = QLabel()
        self.readout.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.readout.setWordWrap(True)
        bar = QHBoxLayout()
        for w in (self.signals_button, self.window_box, self.hold_box, self.cursor_button,
                  self.clear_button):
            bar.addWidget(w)
        bar.addStretch(1)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(2, 2, 2, 2)
        layout.addLayout(bar)
        layout.addWidget(self.canvas, 1)
        layout.addWidget(self.readout)
        self._sync_window_box()
        self._update_readout()

    # -- what to show ------------------------------------------------------------------
    @property
    def ref(self) -> Any:
        """The first signal's output channel (None: nothing plotted)."""
        return self.series[0].ref if self.series else None

    @property
    def label(self) -> str:
        return self.series[0].label if self.series else ""

    @property
    def points(self) -> list[tuple[float, float]]:
        """The first signal's values as ``(timestamp, raw value)``."""
        if not self.series:
            return []
        s = self.series[0]
        return list(zip(s.ts, s.vs, strict=True))

    def set_system(self, system: Any) -> None:
        """Learn names and channel types (titles, units, the Signals menu)."""
        self.system = system
        for s in self.series:
            s.label = self.name_of(s.ref) if not s.label or "/" in s.label else s.label
            self._describe(s)
        self.canvas.update()

    def _describe(self, s: Series) -> None:
        """``s``'s value axis (range and form from its channel type), what it carries and
        whose it is, by the one names (``model/names.py``)."""
        ctype = self._type_of(s.ref)
        s.quantity, s.hint, s.boolean = channel_axis(ctype)
        s.axis = value_axis(ctype)
        s.what, s.owner = self._what(s.ref), self._owner(s.ref)

    def _profile_words(self, ref: Any) -> str:
        ch = None if self.system is None else self.system.channel(ref)
        if ch is None or self.profile_name is None or not ch.profile:
            return ""
        name = self.profile_name(ch.profile)
        return "" if name.startswith("0x") else name

    def _what(self, ref: Any) -> str:
        """What the channel carries: its descriptor, else its profile's name ("" when only
        its number would say it)."""
        if self.system is None or ref is None:
            return ""
        from pdcp_studio.app.words.part_names import names, tr
        from pdcp_studio.model.names import CHANNEL_NUMBER

        what = names(self.system).channel_only(ref, self._profile_words(ref))
        return "" if what == tr(CHANNEL_NUMBER).format(n=ref.index) else what

    def _owner(self, ref: Any) -> str:
        """``EMG flexor site → Control unit``: the part and the parts it feeds."""
        if self.system is None or ref is None:
            return ""
        from pdcp_studio.app.words.part_names import part_name

        fed = sorted({part_name(self.system, r.device)
                      for r in self.system.inputs_fed_by(ref)})
        owner = part_name(self.system, ref.device)
        return f"{owner} → {', '.join(fed)}" if fed else owner

    def _type_of(self, ref: Any) -> int | None:
        ch = None if self.system is None or ref is None else self.system.channel(ref)
        return None if ch is None else ch.type

    def name_of(self, ref: Any) -> str:
        """A readable name: the channel's one name (``model/names.py``) and the parts it
        feeds ("EMG flexor site, Flexor EMG envelope → Control unit")."""
        system = self.system
        if system is None:
            return str(ref)
        from pdcp_studio.app.words.part_names import channel_name, part_name

        name = channel_name(system, ref, self._profile_words(ref))
        fed = sorted({part_name(system, r.device) for r in system.inputs_fed_by(ref)})
        if fed:
            name += " → " + ", ".join(fed)
        return name

    def set_link(self, link: Any, label: str = "") -> None:
        """Follow a selected link: plot the values its output channel sends."""
        self.set_channel(None if link is None else link.output, label)

    def set_channel(self, ref: Any, label: str = "") -> None:
        """Follow a selection: the signal that follows it becomes ``ref`` (None: removed).
        Signals added with ``add_channel`` stay."""
        old = self.ref
        self.series = [s for s in self.series if not s.follows or s.ref == ref]
        if ref is not None and not any(s.ref == ref for s in self.series):
            self._add(ref, label, follows=True, first=True)
        if self.ref != old or ref is None:
            self.channelChanged.emit(self.ref)
        self._update_readout()
        self.canvas.update()

    def add_channel(self, ref: Any, label: str = "") -> None:
        """Plot ``ref`` too, until ``remove_channel`` (at most ``MAX_SIGNALS``)."""
        for s in self.series:
            if s.ref == ref:
                s.follows = False
                return
        self._add(ref, label, follows=False)
        self.channelChanged.emit(self.ref)
        self.canvas.update()

    def remove_channel(self, ref: Any) -> None:
        self.series = [s for s in self.series if s.ref != ref]
        self.channelChanged.emit(self.ref)
        self._update_readout()
        self.canvas.update()

    def _add(self, ref: Any, label: str, *, follows: bool, first: bool = False) -> None:
        used = {s.color for s in self.series}
        color = next((c for c in COLORS if c not in used), COLORS[len(self.series) % 8])
        quantity, hint, boolean = channel_axis(self._type_of(ref))
        title = label if label and self.system is None else self.name_of(ref)
        s = Series(ref, title, quantity, hint, boolean, color, follows)
        self._describe(s)
        if first:
            self.series.insert(0, s)
        else:
            self.series.append(s)
        del self.series[MAX_SIGNALS:]

    def _fill_signals_menu(self) -> None:
        menu = self.signals_menu
        menu.clear()
        shown = {s.ref for s in self.series}
        outputs = [] if self.system is None else [
            ref for ref, ch in self.system.channels() if ch.is_output]
        if not outputs:
            menu.addAction(self.tr("No output channels known yet")).setEnabled(False)
        for ref in outputs:
            action = menu.addAction(self.name_of(ref))
            action.setCheckable(True)
            action.setChecked(ref in shown)
            action.toggled.connect(lambda on, r=ref: self.add_channel(r) if on
                                   else self.remove_channel(r))

    def set_window(self, seconds: float) -> None:
        """Show the last ``seconds`` (at least 0.1 s)."""
        self.window_s = max(0.1, float(seconds))
        for s in self.series:
            s.trim(max(self.window_s, WINDOWS_S[-1]))
        self._sync_window_box()
        self.canvas.update()

    def _sync_window_box(self) -> None:
        i = self.window_box.findData(self.window_s)
        if i >= 0 and i != self.window_box.currentIndex():
            self.window_box.blockSignals(True)
            self.window_box.setCurrentIndex(i)
            self.window_box.blockSignals(False)

    def set_hold(self, hold: bool) -> None:
        """Freeze the time axis at now (values keep being recorded)."""
        if self.hold_box.isChecked() != hold:
            self.hold_box.setChecked(hold)
            return
        self.hold = hold
        self._hold_at = self._newest() if hold else None
        self.canvas.update()

    def set_cursors(self, a: float | None, b: float | None) -> None:
        """Place the cursors ``a`` and ``b`` seconds before the end of the plot (None:
        remove)."""
        end = self.t_end()
        self.cursor_a = None if a is None else end - a
        self.cursor_b = None if b is None else end - b
        self._update_readout()
        self.canvas.update()

    def _set_cursor(self, which: str, t: float) -> None:
        if which == "a":
            self.cursor_a = t
        else:
            self.cursor_b = t
        self._update_readout()
        self.canvas.update()

    def clear(self) -> None:
        """Drop the values; new ones start afresh."""
        for s in self.series:
            s.ts, s.vs = array("d"), array("d")
        self.cursor_a = self.cursor_b = None
        self._update_readout()
        self.canvas.update()

    def _newest(self) -> float:
        return max((s.ts[-1] for s in self.series if s.ts), default=0.0)

    def t_end(self) -> float:
        """The time at the right edge: now (the newest value), or when held."""
        return self._hold_at if self.hold and self._hold_at is not None else self._newest()

    def cursor_readout(self) -> str:
        """Δt between the cursors and each signal's values at them, as text."""
        a, b = self.cursor_a, self.cursor_b
        if a is None and b is None:
            return ""
        end = self.t_end()
        parts = []
        if a is not None:
            parts.append(f"A {a - end:+.3f} s")
        if b is not None:
            parts.append(f"B {b - end:+.3f} s")
        if a is not None and b is not None:
            dt = b - a
            parts.append(f"Δt {dt:.4f} s" + (f" ({1 / abs(dt):.2f} Hz)" if dt else ""))
        lines = ["   ".join(parts)]
        for s in self.series:
            va = None if a is None else s.value_at(a)
            vb = None if b is None else s.value_at(b)
            text = f"{s.label}: "
            text += "  ".join(f"{n} {v:.4g}" for n, v in (("A", va), ("B", vb)) if v is not None)
            if va is not None and vb is not None:
                text += f"  Δ {vb - va:+.4g}"
            lines.append(text + f"  ({s.unit})")
        return "\n".join(lines)

    def _update_readout(self) -> None:
        text = self.cursor_readout()
        self.readout.setText(text)
        self.readout.setVisible(bool(text))

    # -- feeding -----------------------------------------------------------------------
    def add_values(self, values: Iterable[Any]) -> None:
        """Take the values of the plotted channels from a batch of ``ChannelValue``."""
        if not self.series:
            return
        by_ref = {s.ref: s for s in self.series}
        added = False
        for v in values:
            s = by_ref.get(v.ref)
            if s is None:
                continue
            y = as_number(v.value)
            if y is not None:
                s.ts.append(float(v.timestamp))
                s.vs.append(y)
                added = True
        if added:
            keep = max(self.window_s, WINDOWS_S[-1])
            for s in self.series:
                s.trim(keep)
            if not self.hold:
                self._schedule()

    def add_value(self, value: Any) -> None:
        """One ``ChannelValue`` (``add_values`` for a batch)."""
        self.add_values((value,))

    def _schedule(self) -> None:
        """Repaint at most once per ``1/fps`` s: now, or when the interval is over."""
        if self._dirty or self._later.isActive():
            return
        wait = self._min_interval_ms - (self._clock.elapsed() - self._last_paint_ms)
        if wait <= 0:
            self._request_repaint()
        else:
            self._later.start(int(wait) + 1)

    def _request_repaint(self) -> None:
        self._dirty = True
        self.canvas.update()
        if self.readout.isVisible():
            self._update_readout()

    def _painted(self) -> None:
        self._dirty = False
        self._last_paint_ms = self._clock.elapsed()
        self.paint_count += 1

    def y_range(self) -> tuple[float, float]:
        """The first signal's raw value range (0…1 when empty); the axis spans
        :meth:`axis_range`."""
        if not self.series or not self.series[0].vs:
            return 0.0, 1.0
        vs = np.array(self.series[0].vs)
        return float(vs.min()), float(vs.max())

    def axis_range(self) -> tuple[float, float] | None:
        """The range the first signal's value axis spans by its channel type (before the
        little room at each end); None for a float or an unknown type (its values')."""
        return self.series[0].value_range() if self.series else None
