"""The Edit, View and Plan menus' commands that act on the document and its views:
arrange the cards, go to a device, preview a plan (its dock grown to show it), edit the
profile trees."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import QDockWidget, QMainWindow

from pdcp_studio.app.docks.plan_panel import PlanPanel
from pdcp_studio.app.docks.tree_panel import DeviceTree
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.graph.view import GraphView

if TYPE_CHECKING:
    from pdcp_studio.app.docks.inspector import Inspector


class EditCommands:
    """Commands on ``doc`` and the views of ``host`` (the graph, the plan dock, the
    device tree and the inspector if it is made yet: ``inspector()``); ``device_finder``
    and ``profile_tree_dialog`` are the last ones opened."""

    def __init__(self, doc: Document, host: QMainWindow, scene: BusScene, view: GraphView,
                 plan_dock: QDockWidget, plan_panel: PlanPanel, tree: DeviceTree,
                 inspector: Callable[[], Inspector | None]) -> None:
        self.doc = doc
        self.host = host
        self.scene = scene
        self.view = view
        self.plan_dock = plan_dock
        self.plan_panel = plan_panel
        self.tree = tree
        self.inspector = inspector
        self.device_finder: Any = None
        self.profile_tree_dialog: Any = None

    def arrange(self) -> None:
        from pdcp_studio.app.documents import commands

        new = self.scene.relayout()
        moves = {k: (self.doc.positions[k], p) for k, p in new.items()
                 if k in self.doc.positions and self.doc.positions[k] != p}
        if moves:
            self.doc.undo_stack.push(commands.MoveDevicesCommand(self.doc, moves))
        self.view.fit_all()

    def preview_plan(self, mode: str) -> Any:
        self.plan_dock.show()
        self.plan_dock.raise_()
        plan = self.plan_panel.preview(mode)
        if plan is not None:
            # once the rows have their heights (never after the table is gone)
            QTimer.singleShot(0, self.plan_panel.actions_view, self.fit_plan_dock)
        return plan

    def fit_plan_dock(self, tries: int = 4, asked: int = 0) -> None:
        """Grow the plan dock so an ordinary plan's rows all show (never past half the
        window, never shrinking what the user made larger). The dock area's size includes
        its tab bar and the rows wrap anew at the new width, so it looks again until the
        rows fit."""
        view = self.plan_panel.actions_view
        view.resizeRowsToContents()
        missing = view.verticalHeader().length() - view.viewport().height()
        if missing <= 0 or self.plan_dock.isFloating() or not self.plan_dock.isVisible():
            return
        height = min(max(asked, self.plan_dock.height()) + missing + 2, self.host.height() // 2)
        if height > max(asked, self.plan_dock.height()):
            self.host.resizeDocks([self.plan_dock], [height], Qt.Orientation.Vertical)
            if tries > 1:
                QTimer.singleShot(30, view, lambda: self.fit_plan_dock(tries - 1, height))

    def show_profile_tree(self) -> None:
        from pdcp_studio.app.dialogs.profile_tree_editor import ProfileTreeDialog

        dialog = ProfileTreeDialog(parent=self.host, trees=self.doc.trees)  # edited in place
        primary = self.doc.tree.primary  # the tree naming most of this system
        tabs = dialog.tabs
        if tabs is not None:
            tabs.setCurrentIndex(self.doc.trees.index(primary)
                                 if primary in self.doc.trees else 0)
        dialog.treesChanged.connect(self.tree_changed)
        dialog.show()
        self.profile_tree_dialog = dialog

    def tree_changed(self, trees: Any) -> None:
        self.doc.set_trees(trees)
        self.scene.update()
        self.tree.rebuild()
        inspector = self.inspector()
        if inspector is not None:  # (one made later shows the selection with the new trees)
            inspector.show_object(self.doc.selection)

    def go_to_device(self, key: Any) -> None:
        """Select a device and centre its card in the graph."""
        self.doc.select(key)
        card = self.scene.cards.get(key)
        if card is not None:
            self.view.centerOn(card.sceneBoundingRect().center())

    def ask_go_to_device(self) -> None:
        from pdcp_studio.app.docks.device_finder import DeviceFinder

        self.device_finder = DeviceFinder(self.doc.system, self.go_to_device, self.host)
        self.device_finder.show()
        self.device_finder.field.setFocus()
