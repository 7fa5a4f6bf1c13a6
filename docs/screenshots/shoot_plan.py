"""Retakes plan-preview.png: Autoconfigure's plan previewed on the transradial system file (its
four parts without links), before Apply. Under a real X server, from the repository root:

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_plan.py

The window is grabbed at 1600x1000 with the first step of the plan selected (its engineer's
detail in the pane beside the table).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
SYSTEM = HERE.parents[1] / "resources" / "systems" / "transradial.json"


def main() -> int:
    from shoot_window import fresh_window, run

    app, window = fresh_window()
    from PySide6.QtCore import QTimer

    window.open_path(SYSTEM)

    def preview() -> None:
        window.preview_plan("autoconfigure")
        table = window.plan_panel.actions_view
        table.selectRow(0)
        QTimer.singleShot(800, window.view.fit_all)  # the graph fitted above the plan dock
        QTimer.singleShot(1800, shoot)

    def shoot() -> None:
        app.processEvents()
        window.grab().save(str(HERE / "plan-preview.png"))
        print("saved", HERE / "plan-preview.png")
        app.quit()

    QTimer.singleShot(2500, preview)
    return run(app, window, 30_000, [])


if __name__ == "__main__":
    sys.exit(main())
