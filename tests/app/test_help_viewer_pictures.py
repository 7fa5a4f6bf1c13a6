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

from pdcp_studio.app.dialogs import help_viewer

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
    from pdcp_studio.paths import resources_dir

    pictures = resources_dir() / "manual" / "images"
    for name in names:
        image = _image(viewer.browser, name)
        assert not image.isNull()
        # the manual's language's own picture where there is one (German has all three)
        own = pictures / (language if language != "en" else "") / Path(name).name
        assert viewer.browser.picture_path(name) == own
        shot = QImage(str(own))
        if language == "en":  # the English pictures are the documentation's screenshots
            assert QImage(str(ROOT / "docs" / "screenshots" / Path(name).name)).size() \
                == shot.size()
        # the picture itself (fitted to the page), not the placeholder
        assert image.width() == min(shot.width(), help_viewer.PICTURE_WIDTH)
        assert abs(image.height() - shot.height() * image.width() / shot.width()) <= 1
        assert image == _page_picture(shot)
    assert viewer.show_section("tasks")  # sections still found with pictures among them


def _page_picture(shot: QImage) -> QImage:
    """``shot`` as the manual shows it: fitted to the page, framed."""
    from PySide6.QtCore import Qt
    from PySide6.QtGui import QColor, QPainter

    if shot.width() > help_viewer.PICTURE_WIDTH:
        shot = shot.scaledToWidth(help_viewer.PICTURE_WIDTH,
                                  Qt.TransformationMode.SmoothTransformation)
    shot = shot.convertToFormat(QImage.Format.Format_RGB32)
    painter = QPainter(shot)
    painter.setPen(QColor("#9a9a9a"))
    painter.drawRect(shot.rect().adjusted(0, 0, -1, -1))
    painter.end()
    return shot


def test_the_german_manual_shows_german_pictures_and_the_english_one_english(qtbot):
    """The German pictures are pictures of the German app, not copies of the English ones:
    they differ, and where German has no picture of its own the English one is shown."""
    de = help_viewer.HelpViewer(language="de")
    en = help_viewer.HelpViewer(language="en")
    for viewer in (de, en):
        qtbot.addWidget(viewer)
    for name in _pictures(de.browser.document()):
        assert _image(de.browser, name) != _image(en.browser, name), name
        assert de.browser.picture_path(name).parent.name == "de"
        assert en.browser.picture_path(name).parent.name == "images"
    # a language without pictures of its own, and a picture German lacks: the English one
    from pdcp_studio.paths import resources_dir

    folder = resources_dir() / "manual"
    fr = help_viewer.ManualBrowser(folder, language="fr")
    qtbot.addWidget(fr)
    assert fr.picture_path("images/wizard-replace-4-plan.png") == \
        folder / "images" / "wizard-replace-4-plan.png"
    assert de.browser.picture_path("images/not-in-german.png") == \
        folder / "images" / "not-in-german.png"


def test_a_language_folder_is_used_only_for_the_pictures_it_has(tmp_path):
    (tmp_path / "images" / "de").mkdir(parents=True)
    (tmp_path / "images" / "a.png").write_bytes(b"")
    (tmp_path / "images" / "de" / "a.png").write_bytes(b"")
    assert help_viewer.localised(tmp_path / "images" / "a.png", "de") == \
        tmp_path / "images" / "de" / "a.png"
    assert help_viewer.localised(tmp_path / "images" / "b.png", "de") == \
        tmp_path / "images" / "b.png"
    assert help_viewer.localised(tmp_path / "images" / "a.png", "en") == \
        tmp_path / "images" / "a.png"
    assert help_viewer.localised(tmp_path / "images" / "a.png", "") == \
        tmp_path / "images" / "a.png"


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
    folder = ROOT / "resources" / "manual"
    for manual in sorted(folder.glob("*.md")):
        names = re.findall(r"\]\((images/[\w-]+\.png)\)", manual.read_text("utf-8"))
        own = [f"images/{manual.stem}/{Path(n).name}" for n in names
               if (folder / "images" / manual.stem / Path(n).name).is_file()]
        if manual.stem == "de":  # the German manual has its own pictures
            assert len(own) == len(names) == 3
        for name in names + own:
            rel = f"manual/{name}"
            assert any(fnmatch.fnmatch(rel, p) or fnmatch.fnmatch(rel, p.replace("**/", ""))
                       for p in patterns), rel
            assert (resources_dir() / rel).is_file(), rel
            # small: the wheel carries them
            assert (resources_dir() / rel).stat().st_size < 60_000, rel
