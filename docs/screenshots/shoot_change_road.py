"""Screenshots of the change road: Pending changes, the Write confirmation, the Fitting
history, a restore's preview and the fitting report's pages, under a real X server.

Run from the repository root:

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_change_road.py

It connects to the simulated prosthesis, stages two edits (the Delete key on a link, the
hand's Power grip channel from position to velocity control), captures
``pending-changes.png``, writes them with Ctrl+Shift+W: the real confirmation opens, its
Technical detail is expanded and it is saved as ``confirm-change.png`` before this script
clicks Write. It undoes the write with Ctrl+Z (a second transaction, confirmed by the script)
and captures ``history.png`` with the first entry chosen (what it changed, in words); on that
entry (the one that changed the control mode) it presses **Restore on the prosthesis…** and
saves the preview as ``restore-preview.png`` (cancelled: nothing written). Last, the fitting
report of that entry is written by the app's own code path and its A4 pages become
``report-1.png``, ``report-2.png`` … (``pdftoppm -png -r 70``). Keys go through ``xdotool``,
window captures through ImageMagick's ``import -window root``, the dialogs are grabbed by Qt.
The fitting history is a temporary file.
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
    window.flow.confirm = None  # the first write: the real confirmation, photographed
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
        commands.push_channel_field(window.doc, ChannelRef(*hand, 1), "type", 0x9700)
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
        when_dialog(confirm_shot)

    def when_dialog(fn, tries: int = 150) -> None:
        """Call ``fn(dialog)`` once the confirmation is on screen (its preview runs on a
        worker)."""
        dialog = window.flow.dialog
        if dialog is not None and dialog.isVisible():
            later(700, lambda: fn(dialog))
        elif tries:
            later(200, lambda: when_dialog(fn, tries - 1))
        else:
            print("no confirmation appeared")
            app.exit(1)

    def grab(widget, name: str) -> None:
        app.processEvents()
        widget.grab().save(str(HERE / name))
        print("saved", HERE / name)

    def confirm_shot(dialog) -> None:
        dialog.detail_button.setChecked(True)
        later(500, lambda: (grab(dialog, "confirm-change.png"), dialog.write_button.click()))

    steps = {"n": 0}

    def after_write(result) -> None:
        print(result.summary())
        steps["n"] += 1
        if steps["n"] == 1:
            window.flow.confirm = lambda title, preview: True  # the undo: no picture
            later(1500, lambda: key("ctrl+z"))  # undo of a written change: a transaction
            return
        window.history_dock.show()
        window.history_dock.raise_()
        window.resizeDocks([window.history_dock], [380], Qt.Orientation.Vertical)
        window.resizeDocks([window.tree_dock, window.inspector_dock], [230, 260],
                           Qt.Orientation.Horizontal)
        window.history_panel.loaded.connect(once_loaded)
        window.history_panel.refresh()

    def once_loaded() -> None:
        if steps["n"] == 2:
            steps["n"] += 1
            later(800, select)

    def select() -> None:
        ids = [e["id"] for e in window.history_panel.shown]
        window.history_panel.select_ids(min(ids))  # the write: its effect in words
        later(900, lambda: (shoot("history.png"), restore(min(ids))))

    def restore(first: int) -> None:
        window.history_panel.select_ids(first)
        window.flow.confirm = None
        app.processEvents()
        if not window.history_panel.restore_selected():
            print("Restore did not start")
            app.exit(1)
            return
        when_dialog(lambda dialog: (grab(dialog, "restore-preview.png"), dialog.reject(),
                                    later(800, lambda: report(first))))

    def report(first: int) -> None:
        entry = next(e for e in window.history_panel.shown if e["id"] == first)
        pdf = Path(tempfile.mkdtemp()) / "fitting.pdf"
        if not window.write_fitting_report(pdf, entry=entry):
            app.exit(1)
            return
        for old in HERE.glob("report-*.png"):
            old.unlink()
        subprocess.run(["pdftoppm", "-png", "-r", "70", str(pdf), str(HERE / "report")],
                       check=True)
        for page in sorted(HERE.glob("report-*.png")):  # report-1.png, not report-01.png
            number = int(page.stem.split("-")[1])
            page.rename(HERE / f"report-{number}.png")
            print("saved", HERE / f"report-{number}.png")
        app.quit()

    window.live.connected.connect(lambda _url: later(1500, stage))
    window.connect_bus("sim:transradial")
    QTimer.singleShot(90000, lambda: app.exit(2))  # never hang
    code = app.exec()
    window.live.disconnect_bus()
    return code


if __name__ == "__main__":
    raise SystemExit(main())
