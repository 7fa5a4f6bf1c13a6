"""The trace dock with an opened capture on disk: shown, searched to its end, and its
temporary files removed when the live frames come back or another capture is opened."""

from __future__ import annotations

import gc
import os

import pytest

from pdcp_studio.app.trace.disk import RECENT_TEXTS, FileFrameStore, FileTexts
from pdcp_studio.app.trace.dock import MonitorDock
from pdcp_studio.bus.events import FrameSeen

from .test_trace_disk import _write_log

pytestmark = pytest.mark.gui


def test_an_opened_capture_lives_in_temporary_files_until_closed(qtbot, tmp_path):
    first, second = tmp_path / "first.log", tmp_path / "second.log"
    _write_log(first, 20_000)
    _write_log(second, 3000)
    dock = MonitorDock()
    qtbot.addWidget(dock)
    dock.resize(1200, 500)
    dock.show()
    with qtbot.waitSignal(dock.loaded, timeout=60_000):
        dock.load_capture(first)
    store = dock.capture_store
    assert isinstance(store, FileFrameStore) and os.path.exists(store.path)
    assert dock.model.rowCount() == 20_000
    with qtbot.waitSignal(dock.found, timeout=10_000) as found:
        dock.find_frame("de ad be ef")  # the last frame
    assert found.args == [19_999]
    assert dock.model.row_texts(19_999)[1] == "0x123"
    with qtbot.waitSignal(dock.loaded, timeout=60_000):
        dock.load_capture(second)
    assert not os.path.exists(store.folder)  # the first capture's files went with it
    store = dock.capture_store
    assert dock.model.rowCount() == 3000 and os.path.exists(store.path)
    dock.show_live()
    assert not os.path.exists(store.folder) and dock.model.store is dock.live_store


def test_the_live_frames_texts_are_on_disk_and_go_with_the_dock(qtbot):
    dock = MonitorDock()
    texts = dock.live_store.tables.texts
    assert isinstance(texts, FileTexts) and os.path.isdir(texts.folder)
    dock.add_frames([FrameSeen(1000 + i / 8000, 7, bytes([3, 1, i & 0xFF]),
                               f"{i / 8000:11.6f}  P0  #7→BA Get Device Parameter  value {i}")
                     for i in range(RECENT_TEXTS + 10)])  # more distinct texts than it keeps
    dock.flush()
    assert len(texts) > RECENT_TEXTS and len(texts._recent) <= RECENT_TEXTS + 1
    assert dock.model.row_texts(0)[5].endswith("value 0")  # an old text, read back
    folder = texts.folder
    dock.deleteLater()
    del dock, texts
    qtbot.wait(10)
    gc.collect()
    assert not os.path.exists(folder)
