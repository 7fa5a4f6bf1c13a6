"""Exporting the graph (PNG, SVG, PDF) and the fitting report (PDF) from the main window.

Output that leaves the app, as opposed to saving the document (:mod:`.files`). An export
shows the graph, not the user's pointer: the selection and hover highlights are taken off
while it is drawn and put back after.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
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
    """The graph as an image or a file (PNG, SVG, PDF), and the dialogs that ask where;
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

    @contextmanager
    def _unhighlighted(self) -> Iterator[None]:
        """The graph without selection or hover highlights for a while (an export); the
        document's selection is untouched (the scene's signals are held meanwhile)."""
        scene = self.scene
        was_blocked = scene.blockSignals(True)
        selected = scene.selectedItems()
        rows = {card: card.selected_ref for card in scene.cards.values()
                if card.selected_ref is not None}
        hovered = [item for item in scene.items() if getattr(item, "_hover", False)]
        try:
            for item in selected:
                item.setSelected(False)
            for card in rows:
                card.selected_ref = None
                card.refresh()
            for item in hovered:
                item.set_hover(False)  # type: ignore[attr-defined]
            yield
        finally:
            for item in hovered:
                item.set_hover(True)  # type: ignore[attr-defined]
            for card, ref in rows.items():
                card.selected_ref = ref
                card.refresh()
            for item in selected:
                item.setSelected(True)
            scene.blockSignals(was_blocked)

    def graph_image(self, scale: float = 2.0) -> QImage:
        """The whole graph rendered off screen (for PNG export and the report)."""
        rect = self.export_rect()
        image = QImage(max(1, round(rect.width() * scale)), max(1, round(rect.height() * scale)),
                       QImage.Format.Format_ARGB32)
        image.fill(self.scene.backgroundBrush().color())
        painter = QPainter(image)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        with self._unhighlighted(), self.scene.full_detail():  # rows, whatever the zoom
            self.scene.render(painter, QRectF(0, 0, image.width(), image.height()), rect,
                              Qt.AspectRatioMode.IgnoreAspectRatio)
        painter.end()
        return image

    @contextmanager
    def _vectors(self) -> Iterator[None]:
        """Cards keep a pixmap cache for the screen; a vector file wants their vectors."""
        cached = [(item, item.cacheMode()) for item in self.scene.items()
                  if item.cacheMode() != QGraphicsItem.CacheMode.NoCache]
        for item, _mode in cached:
            item.setCacheMode(QGraphicsItem.CacheMode.NoCache)
        try:
            with self._unhighlighted(), self.scene.full_detail():  # vectors and rows
                yield
        finally:
            for item, mode in cached:
                item.setCacheMode(mode)

    def export_pdf(self, path: Path) -> None:
        """The graph as a one-page vector PDF, the page the graph's own shape (in points)."""
        from PySide6.QtCore import QBuffer, QByteArray, QIODevice, QMarginsF, QSizeF
        from PySide6.QtGui import QPageLayout, QPageSize, QPdfWriter

        from pdcp_studio.storage.atomic import atomic_write_bytes

        rect = self.export_rect()
        data = QByteArray()
        buffer = QBuffer(data)
        buffer.open(QIODevice.OpenModeFlag.WriteOnly)
        writer = QPdfWriter(buffer)  # rendered in memory, then written atomically
        writer.setTitle(self.doc.title)
        writer.setCreator("PDCP Studio")
        writer.setResolution(72)  # a scene unit is a point
        size = QPageSize(QSizeF(rect.width(), rect.height()), QPageSize.Unit.Point,
                         "graph", QPageSize.SizeMatchPolicy.ExactMatch)
        writer.setPageLayout(QPageLayout(size, QPageLayout.Orientation.Portrait,
                                         QMarginsF(0, 0, 0, 0)))
        painter = QPainter()
        if not painter.begin(writer):
            raise OSError(f"{path}: the PDF writer did not start")
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        with self._vectors():
            self.scene.render(painter, QRectF(0, 0, rect.width(), rect.height()), rect,
                              Qt.AspectRatioMode.KeepAspectRatio)
        painter.end()
        buffer.close()
        if data.isEmpty():
            raise OSError(f"{path}: the PDF writer produced nothing")
        atomic_write_bytes(path, bytes(data.data()))

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
            painter = QPainter(gen)
            with self._vectors():  # vectors and rows, whatever the zoom
                self.scene.render(painter, page, rect, Qt.AspectRatioMode.IgnoreAspectRatio)
            painter.end()
            buffer.close()
            if data.isEmpty():
                raise OSError(f"{path}: the SVG renderer produced nothing")
            atomic_write_bytes(path, bytes(data.data()))
        elif path.suffix.lower() == ".pdf":
            self.export_pdf(path)
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
