"""The system overview's findings and their words, computed apart from the form.

Pure work (the engine's checks, the plain words of each finding): the inspector runs it on
a worker for a live bus and shows only the result on the GUI thread.
"""

from __future__ import annotations

from typing import Any

from pdcp_studio.model.system import System

#: A finding's plain words (the list's text) and the engineer's detail (its tooltip).
Texts = list[tuple[str, str]]


def checked_findings(system: System, autoconfigure: bool) -> tuple[list[Any], Texts]:
    """Every finding of ``system`` and its words. The parts are named from the catalogue
    once, not once per finding (each lookup finds the user's folder again: 252 findings
    of a 254-device bus took ~60 ms)."""
    if not system.devices:
        return [], []  # (the window's first, empty system: nothing to import the checks for)
    from pdcp_studio.app.words.finding_text import finding_detail, plain_finding
    from pdcp_studio.app.words.part_names import one_naming
    from pdcp_studio.engine import check_system

    findings = check_system(system, autoconfigure=autoconfigure)
    if not findings:
        return [], []
    with one_naming(system) as naming:  # and the system's naming once, not per finding
        names = naming.parts()
        texts = [(plain_finding(f, system, autoconfigure, names), finding_detail(f))
                 for f in findings]
    return findings, texts
