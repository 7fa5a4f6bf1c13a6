"""The window every screenshot script starts from: fresh settings (no recent files, no
remembered layouts), a real X server's window at 1600x1000 in the screen's corner, and the
run until the script quits, with its failures printed and the exit status."""

from __future__ import annotations

import os
import sys
import tempfile
from typing import Any

SIZE = (1600, 1000)


def fresh_window(operator: str | None = None) -> tuple[Any, Any]:
    """(QApplication, MainWindow) shown, with a HOME of its own for the settings."""
    os.environ.pop("QT_QPA_PLATFORM", None)
    os.environ["HOME"] = tempfile.mkdtemp()  # fresh settings: no recent files, no layouts
    if operator:
        os.environ.setdefault("PDCP_STUDIO_OPERATOR", operator)
    from PySide6.QtWidgets import QApplication

    app = QApplication(sys.argv)
    app.setOrganizationName("PDCP Studio")
    app.setApplicationName("PDCP Studio")
    from pdcp_studio.app.window.main_window import MainWindow

    window = MainWindow()
    window.quiet = True
    window.resize(*SIZE)
    window.move(0, 0)
    window.show()
    return app, window


def run(app: Any, window: Any, timeout_ms: int, failures: list[str]) -> int:
    """Run until the script quits (or ``timeout_ms`` passes: a failure), then close the
    window quietly; 1 if anything failed."""
    from PySide6.QtCore import QTimer

    QTimer.singleShot(timeout_ms, lambda: (failures.append("timed out"), app.quit()))
    app.exec()
    window.live.disconnect_bus()
    window.doc.mark_saved()
    window.close()
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0
