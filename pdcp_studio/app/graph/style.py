"""Colours, sizes and fonts of the bus graph, in one place so the look stays consistent.

Calm colours: roles tint the card header only; states use a few saturated accents
(green for a preview add, red for a preview remove or conflict, amber for warnings).
"""

from __future__ import annotations

from PySide6.QtCore import QT_TRANSLATE_NOOP
from PySide6.QtGui import QColor, QFont

# -- geometry (scene units = pixels at 100 % zoom) ---------------------------------------
CARD_WIDTH = 268.0
HEADER_HEIGHT = 40.0
ROW_HEIGHT = 22.0
FOOTER = 6.0
PORT_RADIUS = 5.5
CORNER = 7.0
LAYER_GAP = 110.0  # horizontal space between layers (room for the link curves)
CARD_GAP = 28.0  # vertical space between cards in a layer

# -- role colours (header tint, accent bar) -----------------------------------------------
ROLE_COLOURS = {
    "sensor": QColor("#3b82c4"),
    "control": QColor("#7a5cb8"),
    "terminal": QColor("#2f9a7a"),
}
ROLE_LABELS = {"sensor": QT_TRANSLATE_NOOP("Style", "Sensor"),
               "control": QT_TRANSLATE_NOOP("Style", "Control"),
               "terminal": QT_TRANSLATE_NOOP("Style", "Terminal device")}
MISSING_LABEL = QT_TRANSLATE_NOOP("Style", "Missing")

CARD_FILL = QColor("#ffffff")
CARD_BORDER = QColor("#b9c0ca")
CARD_BORDER_SELECTED = QColor("#2563eb")
MISSING_FILL = QColor("#eef0f2")
MISSING_TEXT = QColor("#8a929c")
TEXT = QColor("#1f2933")
TEXT_DIM = QColor("#66707b")
ROW_SELECTED = QColor("#dbe7fb")
SCENE_BACKGROUND = QColor("#f5f6f8")
GRID = QColor("#e8eaee")

PORT_FILL = QColor("#ffffff")
PORT_INPUT = QColor("#4b5563")
PORT_OUTPUT = QColor("#4b5563")
PORT_CONNECTED = QColor("#4b5563")

LINK = QColor("#6b7785")
LINK_SELECTED = QColor("#2563eb")
LINK_CONFLICT = QColor("#d97706")
LINK_LIVE = QColor("#0ea5e9")
LINK_MISSING = QColor("#a3abb5")
PREVIEW_ADD = QColor("#16a34a")
PREVIEW_REMOVE = QColor("#dc2626")
#: A staged change not yet written to the prosthesis (pending add; pending removal ghost).
PENDING = QColor("#9333ea")
PENDING_REMOVE = QColor("#c084fc")
DRAG_OK = QColor("#2563eb")
DRAG_BAD = QColor("#dc2626")

WARN = QColor("#d97706")
ERROR = QColor("#dc2626")

LINK_WIDTH = 2.0
LINK_WIDTH_SELECTED = 3.2
PREVIEW_WIDTH = 2.6


def title_font() -> QFont:
    f = QFont()
    f.setPointSizeF(10.0)
    f.setBold(True)
    return f


def small_font() -> QFont:
    f = QFont()
    f.setPointSizeF(8.0)
    return f


def row_font() -> QFont:
    f = QFont()
    f.setPointSizeF(8.6)
    return f


def mono_font() -> QFont:
    f = QFont("monospace")
    f.setStyleHint(QFont.StyleHint.Monospace)
    f.setPointSizeF(8.0)
    return f
