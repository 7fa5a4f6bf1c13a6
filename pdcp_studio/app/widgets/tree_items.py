"""A QTreeWidget's items walked, and its current item chosen, in one typed place.

PySide's stubs say ``topLevelItem(i)`` and ``child(i)`` may give None (an index out of
range, which a walk by count never asks for) and that ``setCurrentItem`` takes no None
(Qt's "no current item"); the panels say what they mean through these instead."""

from __future__ import annotations

from PySide6.QtCore import QModelIndex
from PySide6.QtWidgets import QTreeWidget, QTreeWidgetItem


def children(item: QTreeWidgetItem) -> list[QTreeWidgetItem]:
    """``item``'s children, in order."""
    found = (item.child(i) for i in range(item.childCount()))
    return [child for child in found if child is not None]


def top_level_items(tree: QTreeWidget) -> list[QTreeWidgetItem]:
    """The tree's top-level items, in order (the children of its invisible root)."""
    return children(tree.invisibleRootItem())


def set_current(tree: QTreeWidget, item: QTreeWidgetItem | None) -> None:
    """Make ``item`` the current item; None: no current item and no selection, as Qt's
    ``setCurrentItem(nullptr)`` (an invalid index made current)."""
    if item is None:
        tree.setCurrentIndex(QModelIndex())
    else:
        tree.setCurrentItem(item)
