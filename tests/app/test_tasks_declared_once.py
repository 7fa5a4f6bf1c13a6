"""The guided tasks are declared once: the action table's rows give the Tasks menu and the
start page's buttons, and they are the wizards' tasks, in their order."""

from __future__ import annotations

from pdcp_studio.app import wizards
from pdcp_studio.app.window import actions


def test_the_action_table_names_exactly_the_wizards_tasks_in_order():
    assert tuple(task.id for task in actions.TASKS) == wizards.TASKS


def test_the_tasks_menu_and_the_start_page_are_built_from_the_same_rows(make_window):
    window = make_window()
    assert list(window.task_actions) == list(wizards.TASKS)
    window.start_page.show()
    view = window.start_view
    assert view is not None and list(view.task_buttons) == list(wizards.TASKS)
    for task in actions.TASKS:
        menu_text = window.task_actions[task.id].text().replace("&", "")
        assert menu_text.rstrip("…") in task.menu_text.replace("&", "")
        assert view.task_buttons[task.id].text() == task.title
