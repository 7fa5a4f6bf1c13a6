"""Retakes full-rig.png: the full simulated rig (``sim:full``, 93 devices, every node ID in use)
fitted to the window once every card is built. Under a real X server:

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_full_rig.py

(``pdcp-studio gui --bus sim:full --screenshot`` grabs the window before the view has scrolled to
the middle of the grown graph, so the fit is asked for again here once the scene has settled.)
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

OUT = Path(__file__).resolve().parent / "full-rig.png"


def main() -> int:
    os.environ.pop("QT_QPA_PLATFORM", None)
    os.environ["HOME"] = tempfile.mkdtemp()  # fresh settings: no recent files, no layouts
    from PySide6.QtCore import QTimer
    from PySide6.QtWidgets import QApplication

    app = QApplication(sys.argv)
    app.setOrganizationName("PDCP Studio")
    app.setApplicationName("PDCP Studio")
    from pdcp_studio.app.main_window import MainWindow

    window = MainWindow()
    window.quiet = True
    window.resize(1600, 1000)
    window.move(0, 0)
    window.show()
    failures: list[str] = []

    def settle() -> None:
        window.view.settle()
        QTimer.singleShot(1000, shoot)

    def shoot() -> None:
        window.view.fit_all()
        app.processEvents()
        window.grab().save(str(OUT))
        print(OUT)
        app.quit()

    window.ready.connect(lambda: QTimer.singleShot(3000, settle))
    window.connect_bus("sim:full")
    QTimer.singleShot(90_000, lambda: (failures.append("timed out"), app.quit()))
    app.exec()
    window.live.disconnect_bus()
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
