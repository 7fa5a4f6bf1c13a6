"""The inspector on the transradial system file, shown at a prosthetist's width (shared by the
inspector's wording tests)."""

from __future__ import annotations

from pdcp_studio.app.docks.inspector import Inspector
from pdcp_studio.app.documents.document import Document
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.paths import systems_dir
from pdcp_studio.storage import system_file

HAND = DeviceKey(2641, 769, 301)


def transradial_inspector(qtbot) -> tuple[Document, Inspector]:
    doc = Document(system_file.load_path(systems_dir() / "transradial.json"))
    inspector = Inspector(doc)
    qtbot.addWidget(inspector)
    inspector.resize(380, 900)
    inspector.show()
    return doc, inspector
