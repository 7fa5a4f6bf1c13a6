"""Screenshots of the trace (with per-ID statistics and markers) and of the live plot.

Run from the repository root, under a real X server:

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_trace.py

It connects to the simulated prosthesis ``sim:transradial``, lets the bus run, marks two
frames in the bus monitor (times counted since the newest marker) and saves ``trace.png``;
then plots two outputs with cursors in the live plot and saves ``plot.png``; last it opens a
saved capture (``tests/data/captures/pcan-prosthesis-3.0.trc``) in the bus monitor, whose
banner says what it is, and saves ``trace-capture.png``. All are grabs of the whole main
window.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
#: A PCAN-View trace of a prosthesis session, kept with the tests.
CAPTURE = HERE.parents[1] / "tests" / "data" / "captures" / "pcan-prosthesis-3.0.trc"


def main() -> int:
    from PySide6.QtCore import Qt, QTimer
    from PySide6.QtWidgets import QApplication

    from pdcp_studio.app.trace.model import TIME_MARKER, TIME_START
    from pdcp_studio.app.window.main_window import MainWindow

    app = QApplication(sys.argv)
    window = MainWindow()
    window.quiet = True
    window.resize(1600, 1000)
    window.move(0, 0)
    window.show()

    def shoot(name: str) -> None:
        app.processEvents()
        window.grab().save(str(HERE / name))
        print("saved", HERE / name)

    def trace() -> None:
        dock = window._leaf_docks["monitor"]
        dock.show()
        dock.raise_()
        window.resizeDocks([dock], [600], Qt.Orientation.Vertical)
        dock.flush()
        m = dock.model
        rows = m.rowCount()
        dock.view.setCurrentIndex(m.index(max(0, rows - 60), 0))
        dock.add_marker(dock.tr("Grip opens"))
        dock.view.setCurrentIndex(m.index(max(0, rows - 25), 0))
        dock.add_marker(dock.tr("Grip closes"))
        dock.set_paused(True)
        dock.set_time_mode(TIME_MARKER)
        dock.view.scrollTo(m.index(max(0, rows - 35), 0), dock.view.ScrollHint.PositionAtTop)
        dock.splitter.setSizes([330, 170])
        QTimer.singleShot(600, lambda: (shoot("trace.png"), plot()))

    def plot() -> None:
        pdock = window._leaf_docks["plot"]
        plot_widget = pdock.widget()
        system = window.doc.system
        outputs = [lk.output for lk in system.links]
        window.doc.select(system.links[0])  # the plot follows the selection
        for ref in outputs[1:2]:
            plot_widget.add_channel(ref)
        pdock.show()
        pdock.raise_()
        window.resizeDocks([pdock], [520], Qt.Orientation.Vertical)
        QTimer.singleShot(5000, cursors)

    def cursors() -> None:
        plot_widget = window._leaf_docks["plot"].widget()
        plot_widget.set_hold(True)
        plot_widget.set_cursors(3.2, 1.1)
        QTimer.singleShot(500, lambda: (shoot("plot.png"), capture()))

    def capture() -> None:
        dock = window._leaf_docks["monitor"]
        dock.show()
        dock.raise_()
        window.resizeDocks([dock], [600], Qt.Orientation.Vertical)
        dock.set_time_mode(TIME_START)  # the capture has no markers
        dock.loaded.connect(lambda _path: QTimer.singleShot(
            800, lambda: (shoot("trace-capture.png"), app.quit())))
        dock.load_capture(CAPTURE)

    def ready() -> None:
        QTimer.singleShot(4000, trace)

    window.ready.connect(ready)
    window.connect_bus("sim:transradial")
    QTimer.singleShot(60_000, app.quit)
    app.exec()
    window.doc.mark_saved()
    window.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
