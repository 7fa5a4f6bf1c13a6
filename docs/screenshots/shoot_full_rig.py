"""Retakes full-rig.png: the full simulated rig (``sim:full``, 93 devices, every node ID in use)
fitted to the window once every card is built. Under a real X server:

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_full_rig.py

(``pdcp-studio gui --bus sim:full --screenshot`` grabs the window before the view has scrolled to
the middle of the grown graph, so the fit is asked for again here once the scene has settled.)
"""

from __future__ import annotations

from pathlib import Path

OUT = Path(__file__).resolve().parent / "full-rig.png"


def main() -> int:
    from shoot_window import fresh_window, run

    app, window = fresh_window()
    from PySide6.QtCore import QTimer

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
    return run(app, window, 90_000, failures)


if __name__ == "__main__":
    raise SystemExit(main())
