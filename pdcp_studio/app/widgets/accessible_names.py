"""Accessible names for every control, from what the user sees next to it.

A screen reader says a control's accessible name; Qt leaves most of them empty. The name is
taken from the control's own text, its form label or buddy, a placeholder, its tooltip, a
table's column titles or the dock it sits in (:func:`accessible_name`), and
:func:`name_controls` gives one to every control under a widget that has none.
"""

from __future__ import annotations

from PySide6.QtCore import QModelIndex, Qt
from PySide6.QtWidgets import (
    QAbstractButton,
    QAbstractItemView,
    QAbstractSlider,
    QAbstractSpinBox,
    QComboBox,
    QDockWidget,
    QFormLayout,
    QGraphicsView,
    QHeaderView,
    QLabel,
    QLineEdit,
    QPlainTextEdit,
    QScrollBar,
    QTableView,
    QTextEdit,
    QTreeView,
    QWidget,
)

from pdcp_studio.app.i18n import translate

#: The controls that need an accessible name.
CONTROLS = (QAbstractButton, QLineEdit, QComboBox, QAbstractSpinBox, QAbstractSlider,
            QAbstractItemView, QTextEdit, QPlainTextEdit, QGraphicsView)


def plain_label(text: str) -> str:
    """A label's text as words: no &-mnemonic, no trailing ellipsis or colon."""
    return text.replace("&&", "\0").replace("&", "").replace("\0", "&").rstrip("…:. ").strip()


def _form_label(widget: QWidget) -> str:
    """The text of the label a form layout shows for ``widget``, if any."""
    parent = widget.parentWidget()
    layout = parent.layout() if parent is not None else None
    if isinstance(layout, QFormLayout):
        label = layout.labelForField(widget)
        if isinstance(label, QLabel):
            return plain_label(label.text())
    return ""


def _buddy_label(widget: QWidget) -> str:
    top = widget.window()
    for label in top.findChildren(QLabel):
        if label.buddy() is widget:
            return plain_label(label.text())
    return ""


def _qt_part_name(widget: QWidget) -> str:
    """Names for the buttons Qt adds itself (menu bar and toolbar overflow)."""
    names = {"qt_menubar_ext_button": translate("Desktop", "More menus"),
             "qt_toolbar_ext_button": translate("Desktop", "More tools"),
             "qt_tableview_cornerbutton": translate("Desktop", "Select all")}
    return names.get(widget.objectName(), "")


def _headers(view: QAbstractItemView) -> str:
    """A table's or tree's column titles, as a name for it."""
    model = view.model()
    if model is None or not isinstance(view, QTableView | QTreeView):
        return ""  # a list's model has no columns to name it by
    try:
        count = model.columnCount(QModelIndex())
    except TypeError:  # a list model seen through a table: no column titles
        return ""
    titles = [str(model.headerData(c, Qt.Orientation.Horizontal) or "")
              for c in range(min(count, 4))]
    return ", ".join(t for t in titles if t and not t.isdigit())


def _part_of_another_control(widget: QWidget) -> bool:
    """Scroll bars, headers, a combo box's list and line edit: named by their owner."""
    if isinstance(widget, QScrollBar | QHeaderView):
        return True
    parent = widget.parentWidget()
    while parent is not None:
        if isinstance(parent, QComboBox | QAbstractSpinBox):
            return True
        parent = parent.parentWidget()
    return False


def accessible_name(widget: QWidget) -> str:
    """The best name for ``widget`` from what the user sees next to it."""
    candidates: list[str] = [_qt_part_name(widget)]
    if isinstance(widget, QAbstractButton):
        candidates.append(plain_label(widget.text()))
    candidates += [_form_label(widget), _buddy_label(widget)]
    if isinstance(widget, QLineEdit):
        candidates.append(widget.placeholderText())
    candidates += [plain_label(widget.toolTip()), plain_label(widget.statusTip()),
                   plain_label(widget.whatsThis())]
    if isinstance(widget, QComboBox) and widget.count():
        candidates.append(widget.itemText(0))
    if isinstance(widget, QAbstractItemView):
        candidates.append(_headers(widget))
    dock = widget.parentWidget()
    while dock is not None and not isinstance(dock, QDockWidget):
        dock = dock.parentWidget()
    if dock is not None:
        candidates.append(plain_label(dock.windowTitle()))
    if isinstance(widget, QAbstractItemView | QTextEdit | QPlainTextEdit):
        candidates.append(plain_label(widget.window().windowTitle()))
    return next((c for c in candidates if c), "")


def name_controls(root: QWidget) -> list[QWidget]:
    """Give every control under ``root`` an accessible name (and a description from its
    tooltip) where it has none; returns the controls still without one."""
    unnamed: list[QWidget] = []
    for widget in [root, *root.findChildren(QWidget)]:
        if not isinstance(widget, CONTROLS) or _part_of_another_control(widget):
            continue
        if not widget.accessibleName():
            name = accessible_name(widget)
            if name:
                widget.setAccessibleName(name)
            else:
                unnamed.append(widget)
        if not widget.accessibleDescription():
            tip = widget.toolTip() or widget.statusTip()
            if tip and plain_label(tip) != widget.accessibleName():
                widget.setAccessibleDescription(tip)
    return unnamed
