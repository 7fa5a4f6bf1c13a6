"""A broken user catalogue file is skipped but said (issue 11): the good files still load;
the problem names the file and why; the app shows it and ``pdcp-studio doctor`` lists it."""

from __future__ import annotations

import json

import pytest

from pdcp_studio.model import catalog


@pytest.fixture
def user_catalogs(tmp_path, monkeypatch):
    from pdcp_studio import paths

    folder = tmp_path / "catalogs"
    folder.mkdir()
    monkeypatch.setattr(paths, "user_catalogs_dir", lambda: folder)
    catalog.reload_default_catalog()
    yield folder
    catalog.reload_default_catalog()


def test_a_broken_file_is_skipped_and_named_with_why(user_catalogs, caplog):
    (user_catalogs / "good.json").write_text(json.dumps({
        "format": "pdcp-catalog/1", "vendor": "Acme",
        "products": [{"vid": 77, "pid": 1, "product": "Acme wrist"}]}), encoding="utf-8")
    (user_catalogs / "broken.json").write_text('{"format": "pdcp-catalog/1", "products": [',
                                               encoding="utf-8")
    with caplog.at_level("WARNING"):
        assert catalog.default_catalog().lookup(77, 1).product == "Acme wrist"
        assert catalog.default_catalog().lookup(2641, 769) is not None  # the shipped one
    problems = catalog.default_catalog_problems()
    assert len(problems) == 1
    assert str(user_catalogs / "broken.json") in problems[0] and "not JSON" in problems[0]
    assert any("broken.json" in r.getMessage() for r in caplog.records)


def test_doctor_lists_the_skipped_file(user_catalogs, capsys):
    import argparse

    from pdcp_studio.cli import doctor

    (user_catalogs / "broken.json").write_text("[]", encoding="utf-8")
    doc = doctor.report()
    assert len(doc["catalog_problems"]) == 1 and "broken.json" in doc["catalog_problems"][0]
    doctor.run(argparse.Namespace(json=False))
    out = capsys.readouterr().out
    assert "device catalogue skipped:" in out and "broken.json" in out
    assert "not a device catalogue" in out
