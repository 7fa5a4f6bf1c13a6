"""The system overview of a live bus runs its checks on a worker (issue 11: the GUI thread
never blocked > 50 ms while scans run): a snapshot that changes the bus no longer runs
every check of the whole system on the GUI thread."""

from __future__ import annotations

import threading

import pytest

from pdcp_studio import engine
from pdcp_studio.app.docks.inspector import Inspector
from pdcp_studio.app.documents.document import Document
from tests.app.test_graph import big_system

pytestmark = pytest.mark.gui


def _overview(qtbot, session: object | None) -> tuple[Document, Inspector]:
    doc = Document(tree=None)
    system = big_system(40)
    system.clear_links()  # every terminal unconnected: findings to show
    doc.set_system(system, None, session=session)
    inspector = Inspector(doc)
    qtbot.addWidget(inspector)
    return doc, inspector


def _texts(inspector: Inspector) -> list[str]:
    lst = inspector.editors["findings"]
    return [lst.item(i).text() for i in range(lst.count())]


def test_a_live_change_is_checked_on_a_worker(qtbot, monkeypatch):
    doc, inspector = _overview(qtbot, session=object())
    expected = _texts(inspector)  # built at once when the system was set
    assert len(expected) > 10
    threads: list[threading.Thread] = []
    real = engine.check_system

    def recording(system, **kw):
        threads.append(threading.current_thread())
        return real(system, **kw)

    monkeypatch.setattr(engine, "check_system", recording)
    old_list = inspector.editors["findings"]
    doc.deviceChanged.emit(next(iter(doc.system.devices)))
    qtbot.waitUntil(lambda: inspector.editors.get("findings") is not old_list, timeout=5000)
    assert threads and all(t is not threading.main_thread() for t in threads)
    assert _texts(inspector) == expected


def test_offline_the_overview_is_checked_at_once(qtbot, monkeypatch):
    doc, _inspector = _overview(qtbot, session=None)
    threads: list[threading.Thread] = []
    real = engine.check_system
    monkeypatch.setattr(engine, "check_system",
                        lambda s, **kw: threads.append(threading.current_thread())
                        or real(s, **kw))
    doc.deviceChanged.emit(next(iter(doc.system.devices)))
    qtbot.waitUntil(lambda: bool(threads), timeout=5000)
    assert threads == [threading.main_thread()]


def test_checks_that_arrive_after_a_selection_are_dropped(qtbot, monkeypatch):
    doc, inspector = _overview(qtbot, session=object())
    release = threading.Event()
    started = threading.Event()
    real = engine.check_system

    def slow(system, **kw):
        started.set()
        release.wait(5)
        return real(system, **kw)

    monkeypatch.setattr(engine, "check_system", slow)
    doc.deviceChanged.emit(next(iter(doc.system.devices)))
    qtbot.waitUntil(started.is_set, timeout=5000)
    key = next(iter(doc.system.devices))
    doc.select(key)  # the user looks at a device meanwhile
    assert inspector.subject == key
    release.set()
    qtbot.wait(300)  # the late checks arrive and are not shown
    assert inspector.subject == key and "findings" not in inspector.editors


def test_the_words_are_those_of_each_finding_with_the_catalogue_asked_once(monkeypatch):
    from pdcp_studio.app.docks.inspector_checks import checked_findings
    from pdcp_studio.app.words import finding_text
    from pdcp_studio.model import catalog

    system = big_system(40)
    system.clear_links()
    expected_findings = engine.check_system(system, autoconfigure=False)
    expected = [(finding_text.plain_finding(f, system, False), finding_text.finding_detail(f))
                for f in expected_findings]
    asked: list[int] = []
    real = catalog.default_catalog
    monkeypatch.setattr(catalog, "default_catalog", lambda: asked.append(1) or real())
    from pdcp_studio.app.words import part_names

    monkeypatch.setattr(part_names, "default_catalog", catalog.default_catalog)
    findings, texts = checked_findings(system, False)
    assert findings == expected_findings and texts == expected
    assert len(findings) > 10 and len(asked) <= 1  # at most once (the names are remembered)
