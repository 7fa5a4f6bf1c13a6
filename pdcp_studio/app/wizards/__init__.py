"""Guided tasks (issue 11): New fitting, Replace a part, Restore a configuration.

Each is a :class:`QWizard` with clear steps, Back and Next, that ends in the change road's
transaction (reference §5) on the main window's prosthesis. The decisions are pure
(:mod:`.logic`), the words in :mod:`.words`; the wizard and its page in :mod:`.task_wizard`,
the shared pages by what they do (:mod:`.connect_page`, :mod:`.scan_pages`,
:mod:`.change_pages`, :mod:`.result_pages`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from pdcp_studio.app.wizards.task_wizard import TaskWizard

#: The tasks by name (the Tasks menu's order).
TASKS = ("fitting", "replace", "restore")


def make_wizard(window: Any, task: str) -> TaskWizard:
    """The wizard for ``task`` (one of :data:`TASKS`) on ``window``, not shown yet."""
    if task == "fitting":
        from pdcp_studio.app.wizards.new_fitting import NewFittingWizard

        return NewFittingWizard(window)
    if task == "replace":
        from pdcp_studio.app.wizards.replace_part import ReplacePartWizard

        return ReplacePartWizard(window)
    if task == "restore":
        from pdcp_studio.app.wizards.restore_config import RestoreWizard

        return RestoreWizard(window)
    raise ValueError(f"no guided task {task!r} (one of {', '.join(TASKS)})")


def open_wizard(window: Any, task: str) -> TaskWizard:
    """Show the wizard for ``task`` beside the window (one at a time) and return it."""
    old: TaskWizard | None = getattr(window, "task_wizard", None)
    if old is not None and old.isVisible():
        if not old.writing:
            old.close()
        else:
            old.raise_()
            return old
    from pdcp_studio.app.wizards import words

    doc = getattr(window, "doc", None)
    hook = (lambda: doc.system) if doc is not None else None
    words.shown_system = hook
    wizard = make_wizard(window, task)
    window.task_wizard = wizard

    def forget(*_args: object) -> None:
        """The wizard is done: its window's system no longer names parts (nor is kept)."""
        if words.shown_system is hook:
            words.shown_system = None

    wizard.finished.connect(forget)
    wizard.show()
    return wizard
