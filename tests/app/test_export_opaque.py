"""An exported SVG looks the same in every renderer: the cards paint no translucent fill.

ImageMagick's own SVG renderer (``MSVG``, its default without an rsvg delegate) ignores
``fill-opacity``: a translucent header tint came out as solid role colour (the subtitle
unreadable) and the soft shadow as a black bar. The cards now paint the equivalent opaque
colours, so the screen is unchanged and Qt, rsvg and ImageMagick agree.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from PySide6.QtCore import QPointF
from PySide6.QtGui import QColor, QImage, QPainter

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"


def _translucent(svg: Path) -> list[str]:
    """Every fill in ``svg`` drawn with an alpha below 1 (attribute, style or rgba)."""
    found = []
    for el in ET.parse(svg).iter():
        attrs = dict(el.attrib)
        for part in attrs.pop("style", "").split(";"):
            if ":" in part:
                name, value = part.split(":", 1)
                attrs[name.strip()] = value.strip()
        for name in ("fill-opacity", "opacity"):
            if name in attrs and float(attrs[name]) < 0.999:
                found.append(f"{el.tag} {name}={attrs[name]}")
        fill = attrs.get("fill", "")
        match = re.match(r"rgba\([^,]+,[^,]+,[^,]+,\s*([\d.]+)\)", fill)
        if match and float(match.group(1)) < 0.999:
            found.append(f"{el.tag} fill={fill}")
    return found


def _composed(base: QColor, tint: QColor) -> QColor:
    """``tint`` painted translucent over ``base`` by Qt (the look before the change)."""
    image = QImage(4, 4, QImage.Format.Format_RGB32)
    image.fill(base)
    p = QPainter(image)
    p.fillRect(0, 0, 4, 4, tint)
    p.end()
    return image.pixelColor(2, 2)


def _near(a: QColor, b: QColor, levels: int) -> bool:
    return max(abs(a.red() - b.red()), abs(a.green() - b.green()),
               abs(a.blue() - b.blue())) <= levels


def _points(window):
    """Scene points of each card: (header clear of text, shadow under the card, expected
    header colour, expected shadow colour)."""
    from pdcp_studio.app.graph import style

    background = window.scene.backgroundBrush().color()
    shadow = _composed(background, QColor(0, 0, 0, 22))
    out = []
    for card in window.scene.cards.values():
        tint = QColor(style.ROLE_COLOURS[card.role])
        tint.setAlpha(30)
        header = _composed(style.CARD_FILL, tint)
        x = card.pos().x() + card.width / 2
        out.append((card, QPointF(card.pos().x() + card.width - 30, card.pos().y() + 8),
                    QPointF(x, card.pos().y() + card.height + 1.5), header, shadow))
    return out


def _pixel(image: QImage, rect, point: QPointF, scale: float) -> QColor:
    x = int((point.x() - rect.left()) * scale)
    y = int((point.y() - rect.top()) * scale)
    return image.pixelColor(x, y)


@pytest.fixture
def exported(make_window, tmp_path):
    window = make_window(TRANSRADIAL, size=(1600, 1000))
    # A staged parameter on the hand (its header and a row washed violet), a row selected.
    card = next(c for c in window.scene.cards.values() if c.rows)
    card.pending_rows = {0, card.rows[0].index}
    svg = tmp_path / "graph.svg"
    window.export_graph(svg)
    return window, svg


def test_the_exported_svg_has_no_translucent_fill(exported):
    _window, svg = exported
    text = svg.read_text(encoding="utf-8")
    assert "Power grip" in text and "#9333ea" in text  # rows (the channels' one names) and the pending wash's border
    assert _translucent(svg) == []


def test_the_translucent_check_finds_a_translucent_fill(tmp_path):
    """The checker above is not blind: Qt's generator marks alpha as fill-opacity."""
    from PySide6.QtCore import QRectF
    from PySide6.QtSvg import QSvgGenerator

    path = tmp_path / "tinted.svg"
    gen = QSvgGenerator()
    gen.setFileName(str(path))
    gen.setViewBox(QRectF(0, 0, 10, 10))
    p = QPainter(gen)
    p.fillRect(QRectF(0, 0, 10, 10), QColor(0, 0, 0, 22))
    p.end()
    assert _translucent(path)


@pytest.mark.parametrize("zoom", [2.0, 3.0])  # the card's picture; its vectors
def test_the_screen_looks_as_the_translucent_painting_did(make_window, qtbot, zoom):
    """The card on screen: header = the role tint laid over the card, shadow = black at
    22/255 over the background — as when they were painted translucent (a few levels)."""
    window = make_window(TRANSRADIAL, size=(1600, 1000))
    view = window.view
    view.set_zoom(zoom)
    for card, header, shadow, want_header, want_shadow in _points(window):
        view.centerOn(card)
        window.scene.render_pending()
        assert card.vector == (zoom > 2.0)
        image = view.viewport().grab().toImage()
        h = view.mapFromScene(header)
        s = view.mapFromScene(shadow)
        assert _near(image.pixelColor(h.x(), h.y()), want_header, 3), card.device.name
        assert _near(image.pixelColor(s.x(), s.y()), want_shadow, 3), card.device.name


def _is_the_renderer(tool: str, binary: str) -> bool:
    """A ``convert`` that is not ImageMagick (a stand-in some images ship) is no renderer."""
    if tool != "imagemagick":
        return True
    try:
        said = subprocess.run([binary, "-version"], capture_output=True, text=True, timeout=30)
    except OSError:
        return False
    return "ImageMagick" in said.stdout


def _render(tool: str, svg: Path, out: Path) -> QImage:
    if tool == "imagemagick":
        cmd = [shutil.which("convert") or "convert", f"MSVG:{svg}", str(out)]
    else:
        cmd = [shutil.which("rsvg-convert") or "rsvg-convert", str(svg), "-o", str(out)]
    subprocess.run(cmd, check=True, timeout=120, capture_output=True)
    image = QImage(str(out))
    assert not image.isNull()
    return image


@pytest.mark.parametrize("tool,binary", [("imagemagick", "convert"), ("rsvg", "rsvg-convert")])
def test_other_renderers_draw_the_svg_as_the_png_export(exported, tmp_path, tool, binary):
    if shutil.which(binary) is None or not _is_the_renderer(tool, binary):
        pytest.skip(f"{binary} is not installed (only this renderer's check is skipped)")
    window, svg = exported
    rect = window.export_rect()
    rendered = _render(tool, svg, tmp_path / f"{tool}.png")
    scale = rendered.width() / rect.width()
    png = window.graph_image(scale)
    checked = 0
    for card, header, shadow, want_header, want_shadow in _points(window):
        assert _near(_pixel(png, rect, header, scale), want_header, 3), card.device.name
        assert _near(_pixel(png, rect, shadow, scale), want_shadow, 4), card.device.name
        got = _pixel(rendered, rect, header, scale)
        assert _near(got, _pixel(png, rect, header, scale), 6), (tool, card.device.name,
                                                                  got.name())
        got = _pixel(rendered, rect, shadow, scale)
        assert _near(got, _pixel(png, rect, shadow, scale), 8), (tool, card.device.name,
                                                                  got.name())
        checked += 1
    assert checked == len(window.scene.cards) >= 3
