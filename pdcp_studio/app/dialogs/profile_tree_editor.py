"""Edit a named profile tree (``pdcp-profile-tree/1``) with undo, and save it atomically.

Public API
    ``ProfileTreeEditor(tree=None, path=None, parent=None)`` — a QWidget; edits ``tree`` in
    place (pass a copy). Methods, each one undo step and refused with ``error`` when the tree
    forbids it: ``add_child(parent_profile, name, component=None) -> int | None`` (the new
    node's profile; the first free even component when none is given),
    ``rename(profile, name) -> bool``, ``renumber(profile, component) -> int | None`` (the
    new profile; its subtree moves along), ``remove(profile) -> bool``. Files:
    ``save(path=None) -> Path | None`` (atomic), ``load(path) -> bool``,
    ``set_tree(tree, path)``. State: ``tree``, ``path``, ``dirty``, ``undo_stack``,
    ``selected_profile()``, ``select(profile)``. Signals: ``treeChanged(ProfileTree)``,
    ``saved(str)``, ``error(str)``.
    ``ProfileTreeDialog(tree=None, path=None, parent=None, *, trees=None)`` — the editor in
    a window (``.editor``: the one shown); with ``trees``, one tab per named tree
    (``.editors``, ``.tabs``; the prosthetic tree and the thesis test tree are shipped);
    closing with unsaved edits asks ``confirm_discard()``.
    ``load_tree(path)`` / ``save_tree(tree, path)`` — the file format alone.

Each node shows its name, its 4-bit component, the 16-bit profile value of its path in hex
and, for odd components of a tree that names no vendor assigning them, "vendor-reserved"
(a tree that names its vendor shows that vendor instead). Names and components are edited in place;
add, remove, undo and redo sit on a toolbar. Every edit is one command on the editor's own
``QUndoStack`` and is tried on a copy of the tree first, so a refused edit (a duplicate
component, a fifth level) pushes nothing and is reported through ``error`` instead.
"""

from __future__ import annotations

import copy
import itertools
import json
from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtGui import QBrush, QColor, QFont, QUndoCommand, QUndoStack
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QFileDialog,
    QLabel,
    QMessageBox,
    QTabWidget,
    QToolBar,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.widgets.tree_items import children, set_current, top_level_items
from pdcp_studio.app.words.plural import count
from pdcp_studio.errors import ProfileError
from pdcp_studio.model import profile as prof
from pdcp_studio.model.profile_tree import ProfileNode, ProfileTree
from pdcp_studio.storage.atomic import atomic_write_text
from pdcp_studio.storage.profile_trees import read_tree_json

COL_NAME, COL_COMPONENT, COL_PROFILE, COL_NOTE = range(4)
VENDOR = "vendor-reserved"
PROFILE_ROLE = Qt.ItemDataRole.UserRole


def load_tree(path: str | Path) -> ProfileTree:
    """Read a ``pdcp-profile-tree/1`` file; ProfileError names the file and the bad node."""
    try:
        doc = read_tree_json(path)  # bounded; a FIFO or a device is refused
    except (OSError, ValueError) as err:
        raise ProfileError(f"{path}: cannot read a profile tree: {err}") from err
    return ProfileTree.from_json(doc, str(path))


def save_tree(tree: ProfileTree, path: str | Path) -> None:
    """Write the tree as JSON atomically: a crash leaves the old file or the new one."""
    atomic_write_text(path, json.dumps(tree.to_json(), indent=2, ensure_ascii=False) + "\n")


def default_save_path(tree: ProfileTree) -> Path:
    """Where a new tree is offered to be saved: the user profile folder, which the app merges
    into its profile names at start-up (``storage.profile_trees.load_profile_tree``)."""
    from pdcp_studio.storage.profile_trees import user_profiles_dir

    stem = "".join(c if c.isalnum() or c in "-_" else "-" for c in tree.name).strip("-")
    folder = user_profiles_dir()
    if folder is None:
        return Path(f"{stem or 'profiles'}.json")
    folder.mkdir(parents=True, exist_ok=True)
    return folder / f"{stem or 'profiles'}.json"


def free_component(siblings: list[ProfileNode]) -> int | None:
    """The first unused component, standard (even) ones before vendor-reserved (odd) ones."""
    used = {n.component for n in siblings}
    for comp in itertools.chain(range(2, 16, 2), range(1, 16, 2)):
        if comp not in used:
            return comp
    return None


class _Edit(QUndoCommand):
    """One edit: ``apply(tree)`` / ``revert(tree)`` return the profile to select afterwards."""

    def __init__(self, editor: ProfileTreeEditor, text: str,
                 apply: Callable[[ProfileTree], int | None],
                 revert: Callable[[ProfileTree], int | None]) -> None:
        super().__init__(text)
        self._editor, self._apply, self._revert = editor, apply, revert

    def redo(self) -> None:
        self._editor._changed(self._apply(self._editor.tree))

    def undo(self) -> None:
        self._editor._changed(self._revert(self._editor.tree))


class ProfileTreeEditor(QWidget):
    """A profile-tree editor widget with its own undo stack.

    ``ProfileTreeEditor(tree=None, path=None, parent=None)``: edits ``tree`` in place (a copy
    of the caller's is wise); ``path`` is where Save writes. Signals: ``treeChanged(tree)``
    after every edit, undo or load; ``saved(path)``; ``error(message)`` for refused edits
    and failed file operations. Programmatic edits: ``add_child``, ``rename``, ``renumber``,
    ``remove`` (each one undo step); ``save``/``load``.
    """

    treeChanged = Signal(object)
    saved = Signal(str)
    error = Signal(str)

    def __init__(self, tree: ProfileTree | None = None, path: str | Path | None = None,
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.tree = tree if tree is not None else ProfileTree("profiles")
        self.path = Path(path) if path else None
        self.undo_stack = QUndoStack(self)
        self.view = QTreeWidget()
        self.view.setHeaderLabels([self.tr("Name"), self.tr("Component"), self.tr("Profile"), ""])
        self.view.setColumnWidth(COL_NAME, 220)
        self.view.setEditTriggers(QTreeWidget.EditTrigger.DoubleClicked
                                  | QTreeWidget.EditTrigger.EditKeyPressed)
        self.view.itemChanged.connect(self._item_edited)
        self.status = QLabel()
        self.toolbar = QToolBar()
        self._actions()
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.toolbar)
        layout.addWidget(self.view)
        layout.addWidget(self.status)
        self.error.connect(self.status.setText)
        self._refresh()

    def _actions(self) -> None:
        tb = self.toolbar
        tb.addAction(
            self.tr("Add root"), lambda: self._start_edit(self.add_child(prof.NULL_PROFILE))
        )
        tb.addAction(self.tr("Add child"), lambda: self._start_edit(self.add_child(
            self.selected_profile() or prof.NULL_PROFILE)))
        tb.addAction(self.tr("Remove"), lambda: self.selected_profile() and self.remove(
            self.selected_profile() or 0))
        tb.addSeparator()
        undo = self.undo_stack.createUndoAction(self, self.tr("Undo"))
        undo.setShortcut("Ctrl+Z")
        redo = self.undo_stack.createRedoAction(self, self.tr("Redo"))
        redo.setShortcut("Ctrl+Shift+Z")
        tb.addAction(undo)
        tb.addAction(redo)
        tb.addSeparator()
        tb.addAction(self.tr("Open…"), self._ask_open)
        tb.addAction(self.tr("Save"), lambda: self._ask_save(self.path))
        tb.addAction(self.tr("Save as…"), lambda: self._ask_save(None))

    # -- state ----------------------------------------------------------------------
    @property
    def dirty(self) -> bool:
        """True when there are edits since the last save or load."""
        return not self.undo_stack.isClean()

    def set_tree(self, tree: ProfileTree, path: str | Path | None = None) -> None:
        """Edit another tree; the undo history starts afresh."""
        self.tree = tree
        self.path = Path(path) if path else None
        self.undo_stack.clear()
        self._changed(None)

    def selected_profile(self) -> int | None:
        """The profile value of the selected node, or None."""
        item = self.view.currentItem()
        return None if item is None else int(item.data(COL_NAME, PROFILE_ROLE))

    def select(self, profile: int | None) -> None:
        """Select the node of ``profile`` (None or unknown: clear the selection)."""
        set_current(self.view, self._item(profile) if profile else None)

    def _item(self, profile: int) -> QTreeWidgetItem | None:
        for item in self._items():
            if item.data(COL_NAME, PROFILE_ROLE) == profile:
                return item
        return None

    def _items(self) -> list[QTreeWidgetItem]:
        out: list[QTreeWidgetItem] = []
        stack = top_level_items(self.view)
        while stack:
            item = stack.pop()
            out.append(item)
            stack.extend(children(item))
        return out

    # -- edits ----------------------------------------------------------------------
    def _push(self, text: str, apply: Callable[[ProfileTree], int | None],
              revert: Callable[[ProfileTree], int | None]) -> bool:
        try:
            apply(copy.deepcopy(self.tree))  # refuse before anything changes
        except (ProfileError, ValueError) as err:
            self.error.emit(f"{text}: {err}")
            return False
        self.undo_stack.push(_Edit(self, text, apply, revert))
        return True

    def add_child(self, parent_profile: int = prof.NULL_PROFILE, name: str = "New profile",
                  component: int | None = None) -> int | None:
        """Add a node under ``parent_profile`` (null: a root); returns its profile or None."""
        try:
            siblings = self.tree.children_of(parent_profile)
        except ProfileError as err:
            self.error.emit(self.tr("Add: {err}").format(err=err))
            return None
        comp = component if component is not None else free_component(siblings)
        if comp is None:
            self.error.emit(
                self.tr("Add: {v0} has no free component").format(
                    v0=self.tree.name_of(parent_profile)
                )
            )
            return None
        new: list[int] = []

        def apply(t: ProfileTree) -> int:
            new[:] = [t.add(parent_profile, name, comp)]
            return new[0]

        def revert(t: ProfileTree) -> int:
            t.remove(new[0])
            return parent_profile

        return new[0] if self._push(f"Add {name!r}", apply, revert) else None

    def rename(self, profile: int, name: str) -> bool:
        """Rename the node of ``profile``; False if refused or unchanged."""
        node = self.tree.node(profile)
        if node is None or node.name == name.strip():
            return False  # a no-op edit pushes nothing
        old = node.name

        def apply(t: ProfileTree) -> int:
            t.rename(profile, name)
            return profile

        def revert(t: ProfileTree) -> int:
            t.rename(profile, old)
            return profile

        return self._push(f"Rename {old!r} to {name.strip()!r}", apply, revert)

    def renumber(self, profile: int, component: int) -> int | None:
        """Give a node another component (its subtree follows); returns the new profile."""
        node = self.tree.node(profile)
        if node is None or node.component == component:
            return None
        old = node.component
        moved: list[int] = []

        def apply(t: ProfileTree) -> int:
            moved[:] = [t.renumber(profile, component)]
            return moved[0]

        def revert(t: ProfileTree) -> int:
            return t.renumber(moved[0], old)

        text = f"Renumber {node.name!r} 0x{old:X} → 0x{component:X}"
        return moved[0] if self._push(text, apply, revert) else None

    def remove(self, profile: int) -> bool:
        """Remove the node of ``profile`` and its subtree (one undo step)."""
        node = self.tree.node(profile)
        if node is None:
            return False
        parent = prof.parent(profile)
        removed: list[ProfileNode] = []

        def apply(t: ProfileTree) -> int:
            removed[:] = [t.remove(profile)]
            return parent

        def revert(t: ProfileTree) -> int:
            siblings = t.children_of(parent)
            siblings.append(removed[0])
            siblings.sort(key=lambda n: n.component)
            return profile

        return self._push(f"Remove {node.name!r}", apply, revert)

    # -- view -----------------------------------------------------------------------
    def _changed(self, select: int | None) -> None:
        self._refresh(select)
        self.treeChanged.emit(self.tree)

    def _refresh(self, select: int | None = None) -> None:
        expanded = {int(i.data(COL_NAME, PROFILE_ROLE)) for i in self._items() if i.isExpanded()}
        self.view.blockSignals(True)
        try:
            self.view.clear()
            items: dict[int, QTreeWidgetItem] = {}
            for value, node in self.tree.walk():
                parent = items.get(prof.parent(value))
                item = QTreeWidgetItem(parent) if parent else QTreeWidgetItem(self.view)
                self._fill(item, value, node)
                items[value] = item
            for value, item in items.items():
                item.setExpanded(value in expanded or not expanded)
        finally:
            self.view.blockSignals(False)
        if select:
            self.select(select)
        title = self.tree.name + (" •" if self.dirty else "")
        self.status.setText(
            self.tr("{title} — {n_items}").format(
                title=title, n_items=count("ProfileTreeEditor", "%n node(s)", len(items)))
            + (f" — {self.path}" if self.path else "")
        )

    def _fill(self, item: QTreeWidgetItem, value: int, node: ProfileNode) -> None:
        item.setData(COL_NAME, PROFILE_ROLE, value)
        item.setText(COL_NAME, node.name)
        item.setText(COL_COMPONENT, f"0x{node.component:X}")
        item.setText(COL_PROFILE, prof.fmt(value))
        item.setToolTip(COL_NAME, node.description or self.tree.name_of(value))
        item.setFlags(item.flags() | Qt.ItemFlag.ItemIsEditable)
        mono = QFont("monospace")
        item.setFont(COL_PROFILE, mono)
        if self.tree.is_vendor_reserved(node):
            item.setText(COL_NOTE, VENDOR)
            item.setForeground(COL_NOTE, QBrush(QColor("#a05a00")))
            item.setForeground(COL_COMPONENT, QBrush(QColor("#a05a00")))
        elif node.vendor_reserved:  # assigned by the vendor the tree names
            item.setToolTip(COL_COMPONENT, self.tr("Assigned by {vendor}").format(
                vendor=self.tree.vendor))

    def _item_edited(self, item: QTreeWidgetItem, column: int) -> None:
        """An in-place edit: applied on the next event-loop turn, because applying it
        rebuilds the tree and must not delete the item while it is still emitting."""
        profile = int(item.data(COL_NAME, PROFILE_ROLE))
        text = item.text(column).strip()
        QTimer.singleShot(0, self, lambda: self._apply_edit(profile, column, text))

    def _apply_edit(self, profile: int, column: int, text: str) -> None:
        ok = False
        if column == COL_NAME:
            if text:
                ok = self.rename(profile, text)
            else:
                self.error.emit(self.tr("Rename: a profile node needs a name"))
        elif column == COL_COMPONENT:
            try:
                comp = int(text, 16)  # "5", "0x5", "A"
            except ValueError:
                self.error.emit(
                    self.tr("Renumber: {text!r} is not a hex digit 1…F").format(text=text)
                )
            else:
                ok = self.renumber(profile, comp) is not None
        if not ok:
            self._refresh(profile)  # show the model's value again

    def _start_edit(self, profile: int | None) -> None:
        item = self._item(profile) if profile else None
        if item is not None:
            self.view.setCurrentItem(item)
            self.view.editItem(item, COL_NAME)

    # -- files ----------------------------------------------------------------------
    def save(self, path: str | Path | None = None) -> Path | None:
        """Save to ``path`` (or the current path) atomically; marks the stack clean."""
        target = Path(path) if path else self.path
        if target is None:
            self.error.emit(self.tr("Save: no file name given"))
            return None
        try:
            save_tree(self.tree, target)
        except OSError as err:
            self.error.emit(
                self.tr("Save {target}: {v1}").format(target=target, v1=err.strerror or err)
            )
            return None
        self.path = target
        self.undo_stack.setClean()
        self._refresh(self.selected_profile())
        self.saved.emit(str(target))
        return target

    def load(self, path: str | Path) -> bool:
        """Edit the tree in ``path``; False (and ``error``) if it cannot be read."""
        try:
            tree = load_tree(path)
        except ProfileError as err:
            self.error.emit(str(err))
            return False
        self.set_tree(tree, path)
        return True

    def _ask_open(self) -> None:
        path, _ = QFileDialog.getOpenFileName(
            self,
            self.tr("Open profile tree"),
            str(self.path or ""),
            self.tr("Profile trees (*.json)"),
        )
        if path:
            self.load(path)

    def _ask_save(self, path: Path | None) -> None:
        if path is None:
            name, _ = QFileDialog.getSaveFileName(self, self.tr("Save profile tree"),
                                                  str(self.path or default_save_path(self.tree)),
                                                  self.tr("Profile trees (*.json)"))
            path = Path(name) if name else None
        if path is not None:
            self.save(path)


class ProfileTreeDialog(QDialog):
    """The editor in a non-modal window; ``editor`` exposes the widget and its signals.

    With ``trees`` each named tree gets a tab of its own (``editors``, in order) and
    ``editor`` is the one on show; ``treesChanged(list)`` follows any edit."""

    treesChanged = Signal(list)

    def __init__(self, tree: ProfileTree | None = None, path: str | Path | None = None,
                 parent: QWidget | None = None, *,
                 trees: list[ProfileTree] | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(self.tr("Profile trees") if trees else self.tr("Profile tree"))
        self.resize(620, 520)
        layout = QVBoxLayout(self)
        self.tabs: QTabWidget | None = None
        if trees:
            self.trees = trees
            self.tabs = QTabWidget()
            self.editors = []
            for t in trees:
                ed = ProfileTreeEditor(t, None, self)
                ed.treeChanged.connect(lambda _t: self.treesChanged.emit(self.trees))
                self.tabs.addTab(ed, t.name)
                index = self.tabs.count() - 1
                self.tabs.setTabToolTip(index, t.description or t.name)
                self.editors.append(ed)
            layout.addWidget(self.tabs)
        else:
            self.editors = [ProfileTreeEditor(tree, path, self)]
            self.trees = [self.editors[0].tree]
            layout.addWidget(self.editors[0])
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Close)
        buttons.rejected.connect(self.reject)
        layout.addWidget(buttons)

    @property
    def editor(self) -> ProfileTreeEditor:
        """The editor on show (the only one without ``trees``)."""
        if self.tabs is not None:
            widget = self.tabs.currentWidget()
            if isinstance(widget, ProfileTreeEditor):
                return widget
        return self.editors[0]

    def reject(self) -> None:
        if any(ed.dirty for ed in self.editors) and not self.confirm_discard():
            return
        super().reject()

    def confirm_discard(self) -> bool:
        """Ask before unsaved edits are dropped (patch in tests: it is modal)."""
        answer = QMessageBox.question(self, self.tr("Unsaved profile tree"),
                                      self.tr("Discard the unsaved changes to the profile tree?"))
        return answer == QMessageBox.StandardButton.Yes
