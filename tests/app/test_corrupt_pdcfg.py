"""A corrupt stored configuration opened in the app names the file (issue 11 item 6):
File ▸ Open, the configuration window and Compare say which file and where it is bad."""

from __future__ import annotations

import pytest

from pdcp_studio.errors import ConfigFormatError

pytestmark = pytest.mark.gui


@pytest.fixture
def corrupt(tmp_path):
    path = tmp_path / "patient 7.pdcfg"
    path.write_bytes(b"garbage\x00\x01")
    return path


def test_file_open_names_the_corrupt_file(make_window, corrupt, qtbot):
    window = make_window()
    assert not window.open_path(corrupt)
    message = window.statusBar().currentMessage()
    assert str(corrupt) in message and "offset" in message
    assert message.count(str(corrupt)) == 1


def test_every_reader_of_a_pdcfg_in_the_app_names_it(corrupt):
    from pdcp_studio.app.dialogs import compare_dialog
    from pdcp_studio.app.documents import files
    from pdcp_studio.app.documents.config_document import ConfigDocument

    for read in (ConfigDocument.open, files.open_path, compare_dialog.load_file):
        with pytest.raises(ConfigFormatError) as caught:
            read(corrupt)
        assert str(caught.value).startswith(f"{corrupt}: offset ")
        assert caught.value.offset >= 0
