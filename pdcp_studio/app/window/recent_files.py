"""Recently opened files: kept in the app's settings, offered in File → Open Recent.

Only files that still exist are offered; the newest comes first; at most ``LIMIT``.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import QSettings
from PySide6.QtWidgets import QMenu, QWidget

from pdcp_studio.model.safe_text import shown

KEY = "recentFiles"
LIMIT = 10


class RecentFiles:
    """The list itself (``QSettings`` ``recentFiles``)."""

    def __init__(self, settings: QSettings | None = None) -> None:
        self.settings = settings if settings is not None else QSettings()

    def _stored(self) -> list[str]:
        value = self.settings.value(KEY, [])
        if isinstance(value, str):  # QSettings gives a lone entry back as a string
            return [value]
        return [str(v) for v in value] if isinstance(value, list | tuple) else []

    def paths(self) -> list[Path]:
        """The recent files that still exist, newest first."""
        return [Path(p) for p in self._stored() if Path(p).is_file()]

    def add(self, path: str | Path) -> None:
        entry = str(Path(path).resolve())
        kept = [p for p in self._stored() if p != entry]
        self.settings.setValue(KEY, [entry, *kept][:LIMIT])

    def clear(self) -> None:
        self.settings.setValue(KEY, [])


class RecentMenu(QMenu):
    """File → Open Recent: rebuilt each time it opens; ``open_fn(path)`` opens one."""

    def __init__(self, recent: RecentFiles, open_fn: Callable[[Path], object],
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setTitle(self.tr("Open &Recent"))
        self.setObjectName("RecentMenu")
        self.recent = recent
        self.open_fn = open_fn
        self.aboutToShow.connect(self.rebuild)
        self.rebuild()

    def rebuild(self) -> None:
        self.clear()
        paths = self.recent.paths()
        for n, path in enumerate(paths, 1):
            name = shown(path.name)
            label = f"&{n} {name}" if n < 10 else name
            action = self.addAction(label)
            action.setToolTip(shown(str(path)))
            action.setStatusTip(shown(str(path)))
            action.triggered.connect(lambda _c=False, p=path: self.open_fn(p))
        if not paths:
            none = self.addAction(self.tr("No recent files"))
            none.setEnabled(False)
        self.addSeparator()
        clear = self.addAction(self.tr("&Clear the list"))
        clear.setEnabled(bool(paths))
        clear.triggered.connect(self._clear)

    def _clear(self) -> None:
        self.recent.clear()
        self.rebuild()
