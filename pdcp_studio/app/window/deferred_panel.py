"""A dock's panel made when the dock is first shown or the panel first asked for.

A dock that starts as a hidden tab (the fitting history behind the plan) would cost
start-up its imports and widgets for nothing on the first frame. The dock itself is made
with the window, so the saved layout, the tabs and the View menu are as before; only what
it holds waits.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Generic, TypeVar

from PySide6.QtWidgets import QDockWidget, QWidget

Panel = TypeVar("Panel", bound=QWidget)


class DeferredPanel(Generic[Panel]):
    """The panel ``make()`` builds, put in ``dock`` the first time the dock is shown or
    :meth:`panel` is called (whichever comes first; once); ``placed(panel)`` is called
    once it is in the dock (to name its controls, as the window's own were)."""

    def __init__(self, dock: QDockWidget, make: Callable[[], Panel],
                 placed: Callable[[Panel], object] | None = None) -> None:
        self._dock = dock
        self._make = make
        self._placed = placed
        self._panel: Panel | None = None
        dock.visibilityChanged.connect(self._visibility_changed)

    def _visibility_changed(self, visible: bool) -> None:
        if visible:
            self.panel()

    @property
    def made(self) -> Panel | None:
        """The panel if it has been made, else None (nothing is made by asking)."""
        return self._panel

    def panel(self) -> Panel:
        """The panel, made (and put in the dock) now if it was not yet."""
        if self._panel is None:
            self._panel = panel = self._make()
            self._dock.setWidget(panel)
            if self._placed is not None:
                self._placed(panel)
        return self._panel
