"""Linux desktop integration files: the menu entry names file types that the shared-mime-info
file defines, the app's desktop file name matches it, and install-desktop.sh installs all
three (entry, types, icon) for a user."""

from __future__ import annotations

import configparser
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGING = ROOT / "packaging"
MIME_NS = "{http://www.freedesktop.org/standards/shared-mime-info}"


def _entry() -> configparser.SectionProxy:
    parser = configparser.ConfigParser(interpolation=None)
    parser.optionxform = str  # keys are case-sensitive
    parser.read(PACKAGING / "pdcp-studio.desktop", encoding="utf-8")
    return parser["Desktop Entry"]


def test_desktop_entry_names_only_defined_types_and_the_app_matches_it():
    entry = _entry()
    assert entry["Exec"].startswith("pdcp-studio gui %f")
    assert entry["Icon"] == "pdcp-studio" and entry["StartupWMClass"] == "pdcp-studio"
    named = {t for t in entry["MimeType"].split(";") if t}
    defined = {m.get("type") for m in ET.parse(PACKAGING / "pdcp-studio-mime.xml").getroot()
               .iter(f"{MIME_NS}mime-type")}
    assert named and named <= defined
    source = (ROOT / "pdcp_studio" / "app" / "application.py").read_text()
    assert 'setDesktopFileName("pdcp-studio")' in source


def test_mime_types_match_the_file_kinds():
    root = ET.parse(PACKAGING / "pdcp-studio-mime.xml").getroot()
    globs = {m.get("type"): [g.get("pattern") for g in m.iter(f"{MIME_NS}glob")]
             for m in root.iter(f"{MIME_NS}mime-type")}
    assert globs["application/x-pdcp-configuration"] == ["*.pdcfg"]
    assert "*.pdcpsys.json" in globs["application/x-pdcp-system+json"]


@pytest.mark.skipif(shutil.which("update-mime-database") is None,
                    reason="shared-mime-info is not installed here")
def test_install_desktop_installs_entry_types_and_icon(tmp_path):
    env = {**os.environ, "XDG_DATA_HOME": str(tmp_path), "PDCP_STUDIO": "/opt/pdcp/pdcp-studio"}
    done = subprocess.run([str(PACKAGING / "install-desktop.sh")], env=env,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    entry = (tmp_path / "applications" / "pdcp-studio.desktop").read_text()
    assert "Exec=/opt/pdcp/pdcp-studio gui %f" in entry
    assert (tmp_path / "icons/hicolor/scalable/apps/pdcp-studio.svg").is_file()
    assert (tmp_path / "mime/application/x-pdcp-configuration.xml").is_file()
    globs = (tmp_path / "mime" / "globs2").read_text()
    assert "application/x-pdcp-configuration:*.pdcfg" in globs
