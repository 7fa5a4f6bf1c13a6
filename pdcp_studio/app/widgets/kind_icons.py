"""A part's kind as a small picture: the device catalogue's ``icon`` field (``sensor``,
``hand``, …) names an SVG under ``resources/icons/kinds/``. Qt's SVG icon engine draws it;
each picture is made once per size."""

from __future__ import annotations

from functools import cache

from PySide6.QtGui import QIcon, QImage

from pdcp_studio.model.catalog import CatalogEntry, default_catalog
from pdcp_studio.model.refs import DeviceKey


def _icon_path(name: str) -> str | None:
    from pdcp_studio.paths import resources_dir

    path = resources_dir() / "icons" / "kinds" / f"{name}.svg"
    return str(path) if name and path.is_file() else None


@cache
def kind_icon(name: str) -> QIcon:
    """The icon called ``name`` (an empty icon if none is shipped)."""
    path = _icon_path(name)
    return QIcon(path) if path else QIcon()


@cache
def kind_image(name: str, px: int) -> QImage:
    """``kind_icon(name)`` as a ``px``-pixel image (null if there is none). An image, not a
    pixmap: plain memory, safe to keep for the whole run (a cached pixmap drawn after the
    window that made it was gone crashed the graph's paint)."""
    path = _icon_path(name)
    if path is None:
        return QImage()
    image = QImage(px, px, QImage.Format.Format_ARGB32_Premultiplied)
    image.fill(0)
    from PySide6.QtGui import QPainter

    painter = QPainter(image)
    kind_icon(name).paint(painter, 0, 0, px, px)
    painter.end()
    return image


def entry_of(key: DeviceKey) -> CatalogEntry | None:
    return default_catalog().lookup(key.vid, key.pid)


def icon_for(key: DeviceKey) -> QIcon:
    """The icon of the part's kind, from the catalogue (empty if it has none)."""
    entry = entry_of(key)
    return kind_icon(entry.icon) if entry is not None and entry.icon else QIcon()


def product_line(key: DeviceKey) -> str:
    """``PDCP Studio simulator · EMG sensor``: the catalogue's vendor and product for a
    card's second line ("" for a product no catalogue knows)."""
    entry = entry_of(key)
    if entry is None:
        return ""
    return " · ".join(x for x in (entry.product, entry.vendor) if x)


def kind_renderer(name: str) -> object | None:
    """A new SVG renderer of the icon (vectors, for a vector export of the graph), or None.
    Made for each use: a renderer kept for the whole run crashed the graph's cached paint."""
    path = _icon_path(name)
    if path is None:
        return None
    from PySide6.QtSvg import QSvgRenderer

    renderer = QSvgRenderer(path)
    return renderer if renderer.isValid() else None
