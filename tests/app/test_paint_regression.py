"""PySide6 6.12.0 on CPython 3.11 aborts ("Fatal Python error: none_dealloc") after a few
thousand calls of a Python-overridden ``QGraphicsItem.paint()``; 6.11.3 runs it clean
(issue 2, pyproject's pin). Render 1,000 Python-painted items 30 times — 30,000 paints —
in a child process, so an abort fails this test instead of killing the test run."""

from __future__ import annotations

import subprocess
import sys
import textwrap

ITEMS = 1000
RENDERS = 30

CHILD = textwrap.dedent(f"""
    import os
    os.environ["QT_QPA_PLATFORM"] = "offscreen"
    from PySide6.QtCore import QRectF
    from PySide6.QtGui import QColor, QImage, QPainter
    from PySide6.QtWidgets import QApplication, QGraphicsItem, QGraphicsScene

    app = QApplication([])
    painted = 0

    class Item(QGraphicsItem):
        def boundingRect(self):
            return QRectF(0, 0, 20, 12)

        def paint(self, painter, option, widget=None):
            global painted
            painted += 1
            painter.setBrush(QColor(40, 90, 200))
            painter.drawRoundedRect(QRectF(0, 0, 20, 12), 3, 3)
            painter.drawText(QRectF(0, 0, 20, 12), 0, "x")

    scene = QGraphicsScene()
    for i in range({ITEMS}):
        item = Item()
        item.setPos((i % 40) * 24, (i // 40) * 16)
        scene.addItem(item)
    image = QImage(1000, 420, QImage.Format.Format_ARGB32)
    for _ in range({RENDERS}):
        image.fill(0xFFFFFFFF)
        p = QPainter(image)
        scene.render(p)
        p.end()
    print("painted", painted)
""")


def test_python_painted_items_survive_30000_paints():
    r = subprocess.run([sys.executable, "-c", CHILD], capture_output=True, text=True, timeout=110)
    assert r.returncode == 0, f"child died ({r.returncode}): {r.stderr[-2000:]}"
    painted = int(r.stdout.split()[-1])
    assert painted >= ITEMS * RENDERS == 30_000
