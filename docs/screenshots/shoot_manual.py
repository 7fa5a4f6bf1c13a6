"""Retakes manual-images.png: the user manual (F1) open at *Guided tasks*, with the picture of
a new fitting's Autoconfigure step, in front of the main window on the simulated prosthesis.
Under a real X server (the whole screen is taken with ImageMagick's ``import``):

    xvfb-run -a -s "-screen 0 1600x1000x24" python docs/screenshots/shoot_manual.py

With ``--lang de``: the app in German, its manual with the German pictures, into
manual-images-de.png.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

OUT = Path(__file__).resolve().parent / "manual-images.png"


def main() -> int:
    os.environ.pop("QT_QPA_PLATFORM", None)
    os.environ["HOME"] = tempfile.mkdtemp()  # fresh settings: no recent files, no layouts
    os.environ.setdefault("PDCP_STUDIO_OPERATOR", "Screenshot")
    from PySide6.QtCore import QTimer
    from PySide6.QtWidgets import QApplication

    app = QApplication(sys.argv)
    app.setOrganizationName("PDCP Studio")
    app.setApplicationName("PDCP Studio")
    out = OUT
    if "--lang" in sys.argv:
        from pdcp_studio.app import i18n

        lang = sys.argv[sys.argv.index("--lang") + 1]
        i18n.install(app, lang)
        out = OUT.with_name(f"{OUT.stem}-{lang}.png")
    from pdcp_studio.app.dialogs import help_viewer
    from pdcp_studio.app.window.main_window import MainWindow

    window = MainWindow()
    window.quiet = True
    window.resize(1600, 1000)
    window.move(0, 0)
    window.show()
    window.connect_bus("sim:transradial")

    def open_manual() -> None:
        viewer = help_viewer.open_manual(window, "tasks")
        viewer.resize(900, 960)
        viewer.move(680, 20)
        browser = viewer.browser
        doc = browser.document()
        block = doc.begin()
        while block.isValid():  # the first picture, with the paragraph before it
            it = block.begin()
            if not it.atEnd() and it.fragment().charFormat().isImageFormat():
                top = doc.documentLayout().blockBoundingRect(block).top()
                browser.verticalScrollBar().setValue(int(top) - 260)
                break
            block = block.next()
        QTimer.singleShot(1500, shoot)

    def shoot() -> None:
        subprocess.run(["import", "-window", "root", str(out)], check=True)
        print(out)
        app.quit()

    QTimer.singleShot(4000, open_manual)
    return app.exec()


if __name__ == "__main__":
    raise SystemExit(main())
