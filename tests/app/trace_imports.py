"""Wait for the window's background import of the trace docks (numpy, the trace store) to
end before a live test ends: a module imported on that thread while the next test's GUI
thread imports too crashed the interpreter now and then (seen in main as well)."""

from __future__ import annotations

import threading


def trace_imports_done() -> bool:
    return not any(t.name == "import trace docks" and t.is_alive()
                   for t in threading.enumerate())


def wait_for_trace_imports(qtbot) -> None:
    qtbot.wait(300)  # the window starts the import shortly after it is live
    qtbot.waitUntil(trace_imports_done, timeout=30000)
