"""Where a guided task's window goes: beside the Simulator panel it points to, never over it.

The pages of Replace a part (and the New fitting on a simulated prosthesis) tell the user to
press Unplug or Plug in in the Simulator panel while the wizard waits; a wizard opened over
that panel hides the very buttons it names. :func:`spot` is the pure choice (a rectangle on
the screen that does not meet the panel's), :func:`keep_clear` moves a wizard there.
"""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import QPoint, QRect, QSize
from PySide6.QtWidgets import QDockWidget, QWidget

#: Room left for a window manager's title bar and borders when the frame is not known yet.
FRAME_ALLOWANCE = QSize(8, 32)
GAP = 4


def _fit(region: QRect, size: QSize, minimum: QSize, hug_right: bool,
         top: int) -> QRect | None:
    """``size`` (shrunk to ``minimum`` at most) inside ``region``, against the side that
    faces the panel, its top at ``top`` where it can be."""
    w, h = min(size.width(), region.width()), min(size.height(), region.height())
    if w < minimum.width() or h < minimum.height():
        return None
    x = region.right() - w + 1 if hug_right else region.left()
    y = max(region.top(), min(top, region.bottom() - h + 1))
    return QRect(x, y, w, h)


def spot(size: QSize, avoid: QRect, screen: QRect, minimum: QSize | None = None
         ) -> QRect | None:
    """A frame rectangle for a window of ``size`` on ``screen`` that does not meet ``avoid``:
    left of it, else right of it, else below or above; a side where the whole window fits
    first, else the roomiest that fits it shrunk to ``minimum``. None: no room anywhere."""
    minimum = minimum or size
    left = QRect(screen.left(), screen.top(), avoid.left() - GAP - screen.left(),
                 screen.height())
    right = QRect(avoid.right() + 1 + GAP, screen.top(),
                  screen.right() - avoid.right() - GAP, screen.height())
    below = QRect(screen.left(), avoid.bottom() + 1 + GAP, screen.width(),
                  screen.bottom() - avoid.bottom() - GAP)
    above = QRect(screen.left(), screen.top(), screen.width(),
                  avoid.top() - GAP - screen.top())
    sides = ((left, True, avoid.top()), (right, False, avoid.top()),
             (below, False, below.top()), (above, False, above.top()))
    whole = [r for region, hug, top in sides if region.isValid()
             and (r := _fit(region, size, size, hug, top)) is not None]
    if whole:
        return whole[0]
    shrunk = [r for region, hug, top in sides if region.isValid()
              and (r := _fit(region, size, minimum, hug, top)) is not None]
    return max(shrunk, key=lambda r: r.width() * r.height()) if shrunk else None


def panel_rect(dock: QDockWidget) -> QRect | None:
    """Where the panel shows on the screen: the dock's own rectangle, or, while it waits as
    a tab behind another dock, that dock's (raising it shows it there)."""
    window: Any = dock.parentWidget()
    tabbed = list(window.tabifiedDockWidgets(dock)) if hasattr(
        window, "tabifiedDockWidgets") else []
    shown = dock if dock.isVisible() else next((d for d in tabbed if d.isVisible()), None)
    if shown is None:
        return None
    return QRect(shown.mapToGlobal(QPoint(0, 0)), shown.size())


def keep_clear(wizard: QWidget, dock: QDockWidget | None) -> bool:
    """Move (and if need be narrow) ``wizard`` so that its frame leaves ``dock``'s panel
    free; False when there is no panel or no room (the wizard stays where it is)."""
    if dock is None:
        return False
    avoid = panel_rect(dock)
    screen = wizard.screen() or dock.screen()
    if avoid is None or screen is None:
        return False
    frame = wizard.frameGeometry().size()
    extra = frame - wizard.size()
    if extra.width() <= 0 and extra.height() <= 0:
        extra = FRAME_ALLOWANCE
    outer = wizard.size() + extra
    least = wizard.minimumSizeHint().expandedTo(wizard.minimumSize()) + extra
    place = spot(outer, avoid, screen.availableGeometry(), least)
    if place is None:
        return False
    inner = place.size() - extra
    if inner != wizard.size():
        wizard.resize(inner)
    wizard.move(place.topLeft())
    return True
