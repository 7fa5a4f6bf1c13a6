"""The manual shows its pictures (issue 11): each guided task's key step as a picture,
loaded from beside the manual (package data, so an installed wheel has them too), and a
plain placeholder where an installation lacks one."""

from __future__ import annotations

import fnmatch
import re
import tomllib
from pathlib import Path

import pytest
from PySide6.QtCore import QUrl
from PySide6.QtGui import QImage, QTextDocument

from pdcp_studio.app import help_viewer

pytestmark = pytest.mark.gui

ROOT = Path(__file__).resolve().parents[2]


def _pictures(doc: QTextDocument) -> list[str]:
    """The picture names the document shows, in order."""
    names = []
    block = doc.begin()
    while block.isValid():
        it = block.begin()
        while not it.atEnd():
            fmt = it.fragment().charFormat()
            if fmt.isImageFormat():
                names.append(fmt.toImageFormat().name())
            it += 1
        block = block.next()
    return names


def _image(browser, name: str) -> QImage:
    res = browser.document().resource(QTextDocument.ResourceType.ImageResource.value, QUrl(name))
    assert isinstance(res, QImage), (name, type(res))
    return res


@pytest.mark.parametrize("language", ["en", "de"])
def test_every_picture_in_the_manual_is_shown(qtbot, language):
    viewer = help_viewer.HelpViewer(language=language)
    qtbot.addWidget(viewer)
    names = _pictures(viewer.browser.document())
    assert names == ["images/wizard-fitting-4-autoconfigure.png",
                     "images/wizard-replace-4-plan.png",
                     "images/wizard-restore-2-difference.png"]
    for name in names:
        image = _image(viewer.browser, name)
        assert not image.isNull()
        shot = QImage(str(ROOT / "docs" / "screenshots" / Path(name).name))
        # the screenshot itself (fitted to the page), not the placeholder
        assert image.width() == min(shot.width(), help_viewer.PICTURE_WIDTH)
        assert abs(image.height() - shot.height() * image.width() / shot.width()) <= 1
    assert viewer.show_section("tasks")  # sections still found with pictures among them


def test_a_picture_the_installation_lacks_shows_a_placeholder(qtbot, tmp_path):
    browser = help_viewer.ManualBrowser(tmp_path)
    qtbot.addWidget(browser)
    browser.setMarkdown("Before\n\n![A step](images/not-there.png)\n\nAfter\n")
    assert _pictures(browser.document()) == ["images/not-there.png"]
    image = _image(browser, "images/not-there.png")
    assert not image.isNull()
    assert image.size() == help_viewer.missing_picture("x").size()
    assert image.pixelColor(image.width() // 2, 2).name() == "#eeeeee"


def test_the_manuals_pictures_are_package_data():
    """What ``pip install`` ships: every picture a manual names matches the resources'
    package-data patterns and is in the resources the app reads."""
    from pdcp_studio.paths import resources_dir

    config = tomllib.loads((ROOT / "pyproject.toml").read_text("utf-8"))
    patterns = config["tool"]["setuptools"]["package-data"]["pdcp_studio.resources"]
    for manual in sorted((ROOT / "resources" / "manual").glob("*.md")):
        for name in re.findall(r"\]\((images/[\w-]+\.png)\)", manual.read_text("utf-8")):
            rel = f"manual/{name}"
            assert any(fnmatch.fnmatch(rel, p) or fnmatch.fnmatch(rel, p.replace("**/", ""))
                       for p in patterns), rel
            assert (resources_dir() / rel).is_file(), rel
            # small: the wheel carries them
            assert (resources_dir() / rel).stat().st_size < 60_000, rel
