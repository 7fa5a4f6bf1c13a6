"""The start-up yardstick of ``benchmarks/gui.py``: a bare PySide6 window that imports the
parts the live app cannot do without (python-can and networkx), shown, then a line.

It prints the app's start-up probe line (``PDCP_STUDIO_STARTUP_PROBE``) once the window is
shown and its first events are handled, with the ends of the phases both have (imported,
built, shown: ``<phase>_s=<wall>/<cpu>/<gui cpu>``), then exits, so ``gui.py`` times both the same way.
"""

from __future__ import annotations

import sys
import time

STARTED = time.perf_counter()


def main() -> int:
    ends: list[str] = []

    def end(phase: str) -> None:
        ends.append(f"{phase}_s={time.perf_counter() - STARTED:.3f}/{time.process_time():.3f}"
                    f"/{time.thread_time():.3f}")

    import can  # noqa: F401
    import networkx  # noqa: F401
    from PySide6.QtCore import QTimer
    from PySide6.QtWidgets import QApplication, QLabel, QMainWindow

    app = QApplication(sys.argv[:1])
    end("imported")  # (and the application made, as the app's phase is)
    window = QMainWindow()
    window.setCentralWidget(QLabel("bare"))
    window.resize(1400, 860)
    end("built")

    def probe() -> None:
        app.processEvents()
        print(f"startup_s={time.perf_counter() - STARTED:.3f} devices=0 live=True "
              f"cpu_s={time.process_time():.3f} gui_cpu_s={time.thread_time():.3f} "
              + " ".join(ends), flush=True)
        window.close()
        app.quit()

    window.show()
    end("shown")
    QTimer.singleShot(0, probe)
    return app.exec()


if __name__ == "__main__":
    sys.exit(main())
