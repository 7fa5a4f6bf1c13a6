"""Retakes bus-events-hot-swap.png: the thesis's test 4 hot-swap on ``sim:thesis-test4`` (joystick
A pulled, joystick B plugged in while the prosthesis runs), the Bus events list saying which link
the prosthesis made, why and how similar, and the new joystick's card where the old one was (the
missing one below it). Under a real X server (the whole screen is taken with ImageMagick's
``import``):

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_hot_swap.py
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

OUT = Path(__file__).resolve().parent / "bus-events-hot-swap.png"


def main() -> int:
    os.environ.pop("QT_QPA_PLATFORM", None)
    os.environ["HOME"] = tempfile.mkdtemp()  # fresh settings: no recent files, no layouts
    os.environ.setdefault("PDCP_STUDIO_OPERATOR", "Screenshot")
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

    def swap() -> None:
        bridge = window.live.bridge
        if bridge is None:
            failures.append("not connected")
            app.quit()
            return
        window._leaf_docks["events"].raise_()
        window._leaf_docks["sim"].raise_()
        panel = window._leaf_docks["sim"].widget()
        panel.script_combo.setCurrentIndex(panel.script_combo.findText("hot-swap"))
        bridge.scriptFinished.connect(lambda _result: QTimer.singleShot(2500, shoot))
        bridge.run_script("hot-swap")

    def shoot() -> None:
        window.view.fit_all()
        app.processEvents()
        subprocess.run(["import", "-window", "root", str(OUT)], check=True)
        print(OUT)
        app.quit()

    window.ready.connect(lambda: QTimer.singleShot(1500, swap))
    window.connect_bus("sim:thesis-test4")
    QTimer.singleShot(60_000, lambda: (failures.append("timed out"), app.quit()))
    app.exec()
    window.live.disconnect_bus()
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
