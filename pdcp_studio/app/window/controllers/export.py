"""Exporting the graph (PNG, SVG) and the fitting report (PDF) from the main window.

Output that leaves the app, as opposed to saving the document (:mod:`.files`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QImage, QPainter
from PySide6.QtWidgets import QFileDialog, QGraphicsItem, QWidget

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.window.controllers.files import last_dir
from pdcp_studio.app.window.status import StatusLine

_CTX = "WindowExport"


def _t(text: str) -> str:
    return translate(_CTX, text)


class GraphExport:
    """The graph as an image or a file (PNG, SVG), and the dialogs that ask where;
    ``write_report(path)`` writes the fitting report."""

    def __init__(self, scene: BusScene, doc: Document, status: StatusLine, parent: QWidget,
                 write_report: Callable[[str], object]) -> None:
        self.scene = scene
        self.doc = doc
        self.status = status
        self.parent = parent
        self._write_report = write_report

    def export_rect(self) -> QRectF:
        """The part of the scene an export shows: every item and a 20-unit margin, grown to
        whole units so the file's size holds all of it (no clipping at right or bottom)."""
        from pdcp_studio.app.graph.items import PICTURE_PAD

        self.scene.finish_building()  # a large bus still being built: all of it
        rect = self.scene.itemsBoundingRect()
        for card in self.scene.cards.values():  # with or without its picture drawn yet
            rect |= card.mapRectToScene(QRectF(-PICTURE_PAD, -PICTURE_PAD,
                                               card.width + 2 * PICTURE_PAD,
                                               card.height + 2 * PICTURE_PAD))
        rect = rect.adjusted(-20, -20, 20, 20)
        left, top = math.floor(rect.left()), math.floor(rect.top())
        return QRectF(left, top, math.ceil(rect.right()) - left,
                      math.ceil(rect.bottom()) - top)

    def graph_image(self, scale: float = 2.0) -> QImage:
        """The whole graph rendered off screen (for PNG export and the report)."""
        rect = self.export_rect()
        image = QImage(max(1, round(rect.width() * scale)), max(1, round(rect.height() * scale)),
                       QImage.Format.Format_ARGB32)
        image.fill(self.scene.backgroundBrush().color())
        painter = QPainter(image)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        with self.scene.full_detail():  # the cards' rows, whatever the view's zoom
            self.scene.render(painter, QRectF(0, 0, image.width(), image.height()), rect,
                              Qt.AspectRatioMode.IgnoreAspectRatio)
        painter.end()
        return image

    def export_graph(self, path: str | Path) -> None:
        path = Path(path)
        rect = self.export_rect()
        if path.suffix.lower() == ".svg":
            from PySide6.QtCore import QBuffer, QByteArray, QIODevice
            from PySide6.QtSvg import QSvgGenerator

            from pdcp_studio.storage.atomic import atomic_write_bytes

            data = QByteArray()
            buffer = QBuffer(data)
            buffer.open(QIODevice.OpenModeFlag.WriteOnly)
            gen = QSvgGenerator()
            gen.setOutputDevice(buffer)  # rendered in memory, then written atomically
            # The file's own coordinates start at 0,0 (a viewBox at the scene's negative
            # origin shifted the drawing and cut off its right and bottom): the scene's
            # rectangle is mapped onto the whole page.
            page = QRectF(0, 0, rect.width(), rect.height())
            gen.setSize(page.size().toSize())
            gen.setViewBox(page)
            gen.setTitle(self.doc.title)
            # Cards keep a pixmap cache for the screen; a vector file wants their vectors.
            cached = [(item, item.cacheMode()) for item in self.scene.items()
                      if item.cacheMode() != QGraphicsItem.CacheMode.NoCache]
            for item, _mode in cached:
                item.setCacheMode(QGraphicsItem.CacheMode.NoCache)
            try:
                painter = QPainter(gen)
                with self.scene.full_detail():  # vectors and rows, whatever the zoom
                    self.scene.render(painter, page, rect,
                                      Qt.AspectRatioMode.IgnoreAspectRatio)
                painter.end()
            finally:
                for item, mode in cached:
                    item.setCacheMode(mode)
            buffer.close()
            if data.isEmpty():
                raise OSError(f"{path}: the SVG renderer produced nothing")
            atomic_write_bytes(path, bytes(data.data()))
        elif not self.graph_image().save(str(path)):
            raise OSError(f"{path}: could not write the image")

    def ask_export(self, kind: str) -> None:
        path, _ = QFileDialog.getSaveFileName(self.parent, _t("Export graph"),
                                              str(Path(last_dir()) / f"bus.{kind}"),
                                              f"{kind.upper()} (*.{kind})")
        if path:
            try:
                self.export_graph(path)
                self.status.say(_t("Exported {path}").format(path=path))
            except OSError as err:
                self.status.error(_t("Cannot export"), str(err))

    def ask_report(self) -> None:
        path, _ = QFileDialog.getSaveFileName(self.parent, _t("Fitting report"),
                                              str(Path(last_dir()) / "fitting.pdf"),
                                              _t("PDF (*.pdf)"))
        if path:
            self._write_report(path)  # patient, prosthetist, this session's changes
