"""Retakes bus-events-hot-swap.png: the thesis's test 4 hot-swap on ``sim:thesis-test4`` (joystick
A pulled, joystick B plugged in while the prosthesis runs), the Bus events list saying which link
the prosthesis made, why and how similar, and the new joystick's card where the old one was (the
missing one below it). Under a real X server (the whole screen is taken with ImageMagick's
``import``):

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_hot_swap.py
"""

from __future__ import annotations

import subprocess
from pathlib import Path

OUT = Path(__file__).resolve().parent / "bus-events-hot-swap.png"


def main() -> int:
    from shoot_window import fresh_window, run

    app, window = fresh_window(operator="Screenshot")
    from PySide6.QtCore import QTimer

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
    return run(app, window, 60_000, failures)


if __name__ == "__main__":
    raise SystemExit(main())
