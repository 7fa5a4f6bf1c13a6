"""A smoke test of a whole installation's window: every dialog and dock opens, every plan
previews, the report is written, About answers — used on the frozen desktop build, where a
module left out of the bundle shows up only when its window opens.

``pdcp-studio gui --bus sim:transradial`` with ``PDCP_STUDIO_SMOKE_TEST=REPORT.json`` runs
:func:`exercise` once the window is ready, writes ``{"steps": {name: "ok" | why}, "ok": …}``
to REPORT.json and exits (1 when a step failed). The test suite runs the same function.
"""

from __future__ import annotations

import functools
import json
import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QApplication, QDockWidget, QWidget

SMOKE_ENV = "PDCP_STUDIO_SMOKE_TEST"


def _settle(ms: int = 50) -> None:
    deadline = QTimer()
    deadline.setSingleShot(True)
    deadline.start(ms)
    while deadline.isActive():
        QApplication.processEvents()


def _dialogs(window: Any) -> list[tuple[str, Callable[[], QWidget]]]:
    from pdcp_studio.app.dialogs.compare_dialog import CompareDialog
    from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog
    from pdcp_studio.app.dialogs.help_viewer import HelpViewer
    from pdcp_studio.app.dialogs.profile_tree_editor import ProfileTreeDialog
    from pdcp_studio.app.documents.recovery import RecoveryDialog

    out: list[tuple[str, Callable[[], QWidget]]] = [
        ("connect dialog", lambda: ConnectDialog(window)),
        ("compare dialog", lambda: CompareDialog(window.doc.system, bridge=window.live.bridge,
                                                 parent=window)),
        ("profile tree", lambda: ProfileTreeDialog(window.doc.tree.primary, None, window)),
        ("recovery dialog", lambda: RecoveryDialog([], window)),
        ("user manual", lambda: HelpViewer(window)),
    ]
    if window.live.bridge is not None:
        from pdcp_studio.app.dialogs.write_config_dialog import WriteConfigDialog

        out.append(("write configuration dialog", lambda: WriteConfigDialog.for_system(
            window.live.bridge, window.doc.system, window)))
    return out


def exercise(window: Any) -> dict[str, str]:
    """Open and close every dialog and dock of ``window``; name → "ok" or what failed."""
    from pdcp_studio.app.widgets.accessible_names import name_controls

    steps: dict[str, str] = {}

    def step(name: str, fn: Callable[[], object]) -> None:
        try:
            fn()
        except Exception as err:  # the report is what a smoke test is for
            steps[name] = f"{type(err).__name__}: {err}"
        else:
            steps[name] = "ok"

    for name, make in _dialogs(window):
        def open_close(make: Callable[[], QWidget] = make) -> None:
            dialog = make()
            dialog.show()
            _settle()
            if not dialog.isVisible():
                raise RuntimeError("did not show")
            unnamed = name_controls(dialog)
            if unnamed:
                raise RuntimeError(f"controls without an accessible name: {unnamed}")
            dialog.close()
            dialog.deleteLater()
        step(name, open_close)

    window.bus_docks.monitor_dock()  # the monitor exists even before a bus made it
    for dock in window.findChildren(QDockWidget):
        def show_dock(dock: QDockWidget = dock) -> None:
            dock.show()
            dock.raise_()
            _settle()
            if not dock.isVisible():
                raise RuntimeError("did not show")
        step(f"dock {dock.objectName()}", show_dock)

    for mode in window.plan_actions:
        step(f"plan {mode}", functools.partial(window.preview_plan, mode))
    step("plan discard", window.plan_panel.discard)

    def report() -> None:
        from pdcp_studio.app import report as report_mod

        out = Path(tempfile.mkdtemp(prefix="pdcp-smoke-")) / "report.pdf"
        report_mod.write_report(out, window.doc.system, window.doc.tree, window.graph_image())
        if out.stat().st_size < 1000:
            raise RuntimeError("the report is empty")
    step("fitting report", report)

    def about() -> None:
        from pdcp_studio.app.dialogs import help_viewer

        QTimer.singleShot(200, _close_modal)
        help_viewer.show_about(window)
    step("about", about)
    step("manual F1", lambda: window.act_manual.trigger())
    return steps


def _close_modal() -> None:
    front = QApplication.activeModalWidget()
    if front is not None:
        front.close()
    else:
        QTimer.singleShot(100, _close_modal)


def run(window: Any, report_path: str | os.PathLike[str]) -> int:
    """Exercise ``window``, write the report, return the exit status."""
    steps = exercise(window)
    ok = all(v == "ok" for v in steps.values())
    Path(report_path).write_text(json.dumps({"ok": ok, "steps": steps}, indent=2), "utf-8")
    return 0 if ok else 1
