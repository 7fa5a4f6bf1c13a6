"""Screenshots of the Pending changes and Fitting history views, under a real X server.

Run from the repository root:

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_change_road.py

It connects to the simulated prosthesis, stages two edits (the Delete key on a link, a
channel's descriptor), captures ``pending-changes.png``, writes them with Ctrl+Shift+W (the
confirmation is given by this script), undoes the write with Ctrl+Z (a second transaction),
and captures ``history.png``. Keys go through ``xdotool``, captures through ImageMagick's
``import -window root``. The fitting history is a temporary file.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
os.environ.setdefault("PDCP_STUDIO_HISTORY", str(Path(tempfile.mkdtemp()) / "history.sqlite3"))
os.environ.setdefault("PDCP_STUDIO_OPERATOR", "J. Doe, CPO")


def main() -> int:
    from PySide6.QtCore import Qt, QTimer
    from PySide6.QtWidgets import QApplication

    from pdcp_studio.app.documents import commands
    from pdcp_studio.app.window.main_window import MainWindow
    from pdcp_studio.model.refs import ChannelRef, DeviceKey
    from pdcp_studio.model.system import Link

    app = QApplication(sys.argv)
    app.setApplicationName("PDCP Studio screenshots")
    window = MainWindow()
    window.resize(1600, 1000)
    window.move(0, 0)
    window.show()
    window.flow.confirm = lambda title, preview: print("\n".join(preview.lines())) or True
    control, hand = DeviceKey(2641, 513, 201), DeviceKey(2641, 769, 301)
    link = Link(ChannelRef(*control, 3), ChannelRef(*hand, 1))

    def key(*keys: str) -> None:
        wid = subprocess.run(["xdotool", "search", "--onlyvisible", "--name", "PDCP Studio"],
                             capture_output=True, text=True, check=True).stdout.split()[0]
        subprocess.run(["xdotool", "windowfocus", "--sync", wid], check=True)  # no WM here
        subprocess.run(["xdotool", "key", "--clearmodifiers", *keys], check=True)

    def shoot(name: str) -> None:
        app.processEvents()
        subprocess.run(["import", "-window", "root", str(HERE / name)], check=True)
        print("saved", HERE / name)

    def later(ms: int, fn) -> None:
        QTimer.singleShot(ms, fn)

    def stage() -> None:
        window.activateWindow()  # no window manager: Qt must give itself the focus
        window.doc.select(link)
        window.view.setFocus()
        app.processEvents()
        key("Delete")
        app.processEvents()
        window.doc.undo_stack.push(commands.SetChannelFieldCommand(
            window.doc, ChannelRef(*hand, 2), "descriptor", "Pinch motor"))
        window.pending_panel.patient.setText("Clinic ref 2026-117")
        window.pending_panel.patient.editingFinished.emit()
        window.pending_dock.show()
        window.pending_dock.raise_()
        window.inspector_dock.raise_()
        window.resizeDocks([window.pending_dock], [300], Qt.Orientation.Vertical)
        window.doc.select(None)
        later(1200, lambda: (shoot("pending-changes.png"), write()))

    def write() -> None:
        window.flow.finished.connect(after_write)
        key("ctrl+shift+w")

    steps = {"n": 0}

    def after_write(result) -> None:
        print(result.summary())
        steps["n"] += 1
        if steps["n"] == 1:
            later(1500, lambda: key("ctrl+z"))  # undo of a written change: a transaction
            return
        window.history_dock.show()
        window.history_dock.raise_()
        window.resizeDocks([window.history_dock], [380], Qt.Orientation.Vertical)
        window.resizeDocks([window.tree_dock], [230], Qt.Orientation.Horizontal)
        window.history_panel.loaded.connect(once_loaded)
        window.history_panel.refresh()

    def once_loaded() -> None:
        if steps["n"] == 2:
            steps["n"] += 1
            later(800, select)

    def select() -> None:
        ids = [e["id"] for e in window.history_panel.shown]
        window.history_panel.select_ids(*ids[:2])
        later(900, lambda: (shoot("history.png"), app.quit()))

    window.live.connected.connect(lambda _url: later(1500, stage))
    window.connect_bus("sim:transradial")
    QTimer.singleShot(60000, app.quit)  # never hang
    code = app.exec()
    window.live.disconnect_bus()
    return code


if __name__ == "__main__":
    raise SystemExit(main())
