"""A part's kind as a small picture: the device catalogue's ``icon`` field (``sensor``,
``hand``, …) names an SVG under ``resources/icons/kinds/``. Qt's SVG icon engine draws it;
each picture is made once per size."""

from __future__ import annotations

from functools import cache

from PySide6.QtGui import QIcon, QPixmap

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
def kind_pixmap(name: str, px: int) -> QPixmap:
    """``kind_icon(name)`` as a ``px``-pixel picture (null if there is none)."""
    icon = kind_icon(name)
    return icon.pixmap(px, px) if not icon.isNull() else QPixmap()


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


@cache
def kind_renderer(name: str) -> object | None:
    """An SVG renderer of the icon (vectors, for a vector export of the graph), or None."""
    path = _icon_path(name)
    if path is None:
        return None
    from PySide6.QtSvg import QSvgRenderer

    renderer = QSvgRenderer(path)
    return renderer if renderer.isValid() else None
