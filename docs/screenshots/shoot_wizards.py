"""Screenshots of every step of the three guided tasks, under a real X server.

Run from the repository root:

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_wizards.py

It connects to the simulated prosthesis ``sim:transradial``, clears its links without a
record (so New fitting has links to propose), then walks New fitting, Replace a part (the
hand unplugged and the spare hand plugged in through the Simulator panel) and Restore a
configuration (the original hand back, the first fitting's stored configuration restored
from the history; then the fitting's first write, made before anything was stored, which
warns that it clears the stored configuration; then a configuration file chosen, in
``~/Fittings`` like the fitting report), and
saves ``wizard-<task>-<step>.png`` beside this script (with ``--lang de``: the German build,
into a temporary folder, to look at, or into ``--out DIR``): the wizard's window, and for
the plug step the whole screen with the Simulator panel. The fitting history is a temporary
file. The German manual's pictures are made from a German run:

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_wizards.py \
        --lang de --out /tmp/wizards-de
    QT_QPA_PLATFORM=offscreen python docs/screenshots/manual_pictures.py --lang de /tmp/wizards-de
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Callable, Generator
from pathlib import Path

HERE = Path(__file__).resolve().parent
TMP = Path(tempfile.mkdtemp())
# The report step shows where the report went: a plain folder of a prosthetist's, not a
# temporary one. /home/jdoe is made for the run (and removed after it) where it can be;
# elsewhere a temporary folder stands in for the home folder.
PLAIN_HOME = Path("/home/jdoe")
MARK = ".made-by-shoot_wizards"  # a folder left by a run that was stopped is ours to reuse
MADE_HOME = False
try:
    if PLAIN_HOME.is_dir() and (PLAIN_HOME / MARK).exists():
        shutil.rmtree(PLAIN_HOME)
    PLAIN_HOME.mkdir()
    (PLAIN_HOME / MARK).touch()
    MADE_HOME = True
except OSError:
    PLAIN_HOME = TMP / "home"
    PLAIN_HOME.mkdir()
os.environ["HOME"] = str(PLAIN_HOME)
os.environ.setdefault("PDCP_STUDIO_HISTORY", str(TMP / "history.sqlite3"))
os.environ.setdefault("PDCP_STUDIO_OPERATOR", "J. Doe, CPO")

Script = Generator[Callable[[], bool], None, None]


def main() -> int:
    from PySide6.QtCore import QSettings, QTimer
    from PySide6.QtWidgets import QApplication

    from pdcp_studio.app.window.main_window import MainWindow
    from pdcp_studio.app.wizards import open_wizard
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.model.refs import DeviceKey

    QSettings.setDefaultFormat(QSettings.Format.IniFormat)  # nothing from the user's settings
    QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, str(TMP))
    app = QApplication(sys.argv)
    app.setApplicationName("PDCP Studio screenshots")
    lang = sys.argv[sys.argv.index("--lang") + 1] if "--lang" in sys.argv else ""
    out = HERE if not lang else Path(tempfile.mkdtemp())  # other languages: to look at
    if "--out" in sys.argv:
        out = Path(sys.argv[sys.argv.index("--out") + 1])
        out.mkdir(parents=True, exist_ok=True)
    if lang:
        from pdcp_studio.app import i18n

        i18n.install(app, lang)
    window = MainWindow()
    window.resize(1600, 1000)
    window.move(0, 0)
    window.show()
    hand, spare = DeviceKey(2641, 769, 301), DeviceKey(2641, 769, 302)
    # the size of the wizard for its long pages (German runs longer: shown whole, too)
    big = (900, 700) if lang in ("", "en") else (960, 800)
    failures: list[str] = []

    def shoot(wizard, name: str, screen: bool = False) -> None:
        app.processEvents()
        path = out / f"wizard-{name}.png"
        if screen:
            subprocess.run(["import", "-window", "root", str(path)], check=True)
        else:
            wizard.grab().save(str(path))
        print("saved", path)

    def ready(wizard, page) -> Callable[[], bool]:
        return lambda: wizard.currentPage() is page and page.isComplete()

    def chosen(page, action: str) -> Callable[[], bool]:
        """Choose the history entry of ``action``, again after the page refills its list
        (the history is read again in the background when the page opens)."""
        def check() -> bool:
            ids = [e["id"] for e in page.history if e["action"] == action]
            return bool(ids) and page.choose_entry(ids[0]) and page.isComplete()
        return check

    def opened(task: str):
        wizard = open_wizard(window, task)
        wizard.move(280, 120)
        return wizard

    def present(key) -> bool:
        """On the bus now (a replaced part that nothing links to leaves the graph)."""
        device = window.doc.system.devices.get(key)
        return device is not None and device.present

    def script() -> Script:
        yield lambda: window.is_ready and window.doc.config is not None
        session = window.live.bridge.session
        links = sorted(session.system().links)
        session.transact(Change.links_to(links, [], "clear for the screenshots"), record=False)
        window.live.refresh()
        yield lambda: not window.doc.system.links

        # New fitting
        w = opened("fitting")
        yield ready(w, w.connect_page)
        shoot(w, "fitting-1-connect")
        steps = [(w.scan_page, "fitting-2-scan"), (w.checks_page, "fitting-3-checks"),
                 (w.plan_page, "fitting-4-autoconfigure"), (w.write_page, "fitting-5-write")]
        for page, name in steps:
            w.next()
            yield ready(w, page)
            if page is w.plan_page:
                w.resize(*big)
            shoot(w, name)
        w.next()  # the commit: the transaction runs
        yield ready(w, w.store_page)
        shoot(w, "fitting-6-store")
        w.next()
        yield ready(w, w.report_page)
        (PLAIN_HOME / "Fittings").mkdir(exist_ok=True)
        w.report_page.save_report(PLAIN_HOME / "Fittings" / "P-0042 fitting.pdf")
        shoot(w, "fitting-7-report")
        w.close()

        # Replace a part
        w = opened("replace")
        yield lambda: (w.missing_page.view.toPlainText() and not w.missing_page.busy.isVisible()
                       and not w.missing_page.isComplete())
        shoot(w, "replace-0-nothing-missing")
        w.missing_page.show_simulator()
        panel = window._leaf_docks["sim"].widget()
        panel.select(hand)
        panel.unplug_selected()
        yield ready(w, w.missing_page)
        shoot(w, "replace-1-missing")
        w.next()
        yield lambda: w.plug_page.busy.isVisible() and w.plug_page.view.toPlainText()
        panel.select(spare)
        shoot(w, "replace-2-plug", screen=True)
        panel.plug_selected()
        yield ready(w, w.plug_page)
        shoot(w, "replace-3-seen")
        w.next()
        yield ready(w, w.plan_page)
        w.resize(*big)
        shoot(w, "replace-4-plan")
        w.next()
        yield ready(w, w.write_page)
        shoot(w, "replace-5-write")
        w.next()
        yield ready(w, w.verify_page)
        shoot(w, "replace-6-verify")
        w.next()
        yield ready(w, w.report_page)
        shoot(w, "replace-7-report")
        w.close()

        # Restore a configuration: the original hand is back from repair.
        panel.select(spare)
        panel.unplug_selected()
        yield lambda: not present(spare)
        panel.select(hand)
        panel.plug_selected()
        yield lambda: present(hand)
        w = opened("restore")
        page = w.source_page
        yield lambda: len(page.history) >= 2
        yield chosen(page, "new fitting: store configuration")
        shoot(w, "restore-1-choose")
        w.next()
        yield ready(w, w.diff_page)
        w.resize(*big)
        shoot(w, "restore-2-difference")
        w.next()
        yield ready(w, w.write_page)
        shoot(w, "restore-3-write")
        w.next()
        yield ready(w, w.verify_page)
        shoot(w, "restore-4-verify")
        w.close()

        # The fitting's first write was made before anything was stored: restoring it
        # would clear the stored configuration, so the page warns and waits for a tick.
        w = opened("restore")
        page = w.source_page
        yield lambda: len(page.history) >= 3
        yield chosen(page, "new fitting: connect")
        w.next()
        yield lambda: w.currentPage() is w.diff_page and w.diff_page.clears
        w.resize(*big)
        shoot(w, "restore-5-clears-warning")
        w.close()

        # Restore from a configuration file: the file chosen, its stored links counted.
        w = opened("restore")
        page = w.source_page
        yield lambda: len(page.history) >= 2
        stored = PLAIN_HOME / "Fittings" / "P-0042 hand and hook.pdcfg"
        shutil.copy(HERE.parents[1] / "resources" / "configs" / "transradial-hand-and-hook.pdcfg",
                    stored)
        page.load_file(stored)
        yield lambda: page.isComplete()
        shoot(w, "restore-6-from-file")
        w.close()

    steps = script()
    waiting: list[Callable[[], bool]] = []
    ticks = [0]

    def tick() -> None:
        ticks[0] += 1
        if ticks[0] > 600:  # 60 s without progress
            failures.append(f"stuck after {waiting}")
            app.quit()
            return
        try:
            if waiting and not waiting[0]():
                return
            waiting[:] = [next(steps)]
            ticks[0] = 0
        except StopIteration:
            app.quit()
        except Exception as err:  # a failed step ends the run with its message
            failures.append(repr(err))
            app.quit()

    timer = QTimer()
    timer.timeout.connect(tick)
    timer.start(100)
    QTimer.singleShot(0, lambda: window.connect_bus("sim:transradial"))
    app.exec()
    window.live.disconnect_bus()
    if MADE_HOME:
        shutil.rmtree(PLAIN_HOME, ignore_errors=True)
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
