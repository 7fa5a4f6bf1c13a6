"""The app in the user's language: Qt's translation system, following the system locale
unless ``--lang`` chooses.

Translations are Qt Linguist files, ``resources/i18n/pdcp_studio_<lang>.ts`` (committed;
``pyside6-lupdate`` refreshes them from the source, see ``packaging/README.md``). Qt loads
the compiled ``.qm``: ``packaging/build.sh`` compiles them into the frozen build; any other
install compiles a missing or outdated one at first start with PySide6's own ``lrelease``
into the user's cache folder. Qt's own strings (standard buttons, file dialogs) come from
Qt's ``qtbase_<lang>.qm``.
"""

from __future__ import annotations

import hashlib
import logging
import shutil
import subprocess
import sys
from pathlib import Path

from PySide6.QtCore import QCoreApplication, QLibraryInfo, QLocale, QTranslator

log = logging.getLogger(__name__)

CATALOG = "pdcp_studio"
#: Languages with a translation (besides English, the source).
LANGUAGES = ("de",)
#: The translators :func:`install` put in (Qt has one application per process).
_installed: list[QTranslator] = []


def language(requested: str | None = None) -> str:
    """The two-letter language to show: ``requested`` (``--lang``), else the system's."""
    name = requested or QLocale.system().name()
    return name.replace("-", "_").split("_")[0].lower() or "en"


def ts_path(lang: str) -> Path:
    from pdcp_studio.paths import resources_dir

    return resources_dir() / "i18n" / f"{CATALOG}_{lang}.ts"


def _lrelease() -> str | None:
    import PySide6

    here = Path(PySide6.__file__).parent
    for candidate in (here / "lrelease", here / "lrelease.exe",
                      here / "Qt" / "libexec" / "lrelease"):
        if candidate.is_file():
            return str(candidate)
    return shutil.which("pyside6-lrelease") or shutil.which("lrelease")


def compile_ts(ts: Path, qm: Path) -> bool:
    """``lrelease`` ``ts`` into ``qm``; False (logged) when it cannot."""
    tool = _lrelease()
    if tool is None:
        log.warning("no lrelease: %s stays untranslated", ts.name)
        return False
    qm.parent.mkdir(parents=True, exist_ok=True)
    done = subprocess.run([tool, "-silent", str(ts), "-qm", str(qm)], capture_output=True,
                          text=True, check=False)
    if done.returncode != 0 or not qm.is_file():
        log.warning("lrelease %s failed: %s", ts.name, done.stderr.strip())
        return False
    return True


def qm_path(lang: str) -> Path | None:
    """The compiled translation for ``lang``: the shipped one when it is current, else one
    compiled now into the user's cache folder; None when there is none."""
    ts = ts_path(lang)
    shipped = ts.with_suffix(".qm")
    if shipped.is_file() and (not ts.is_file() or shipped.stat().st_mtime >= ts.stat().st_mtime
                              or getattr(sys, "frozen", False)):
        return shipped
    if not ts.is_file():
        return None
    import platformdirs

    # Named by the translation's content: two installs (or checkouts) of different versions
    # never load each other's compiled file, whatever the files' times say.
    digest = hashlib.sha256(ts.read_bytes()).hexdigest()[:16]
    cached = (platformdirs.user_cache_path("pdcp-studio", appauthor=False)
              / f"{shipped.stem}-{digest}.qm")
    if cached.is_file():
        return cached
    return cached if compile_ts(ts, cached) else None


def install(app: QCoreApplication, requested: str | None = None) -> str:
    """Load the translations for the chosen language into ``app``; returns the language."""
    lang = language(requested)
    QLocale.setDefault(QLocale(lang))
    translators = []
    if lang != "en":
        qt_own = QTranslator(app)
        if qt_own.load(f"qtbase_{lang}",
                       QLibraryInfo.path(QLibraryInfo.LibraryPath.TranslationsPath)):
            translators.append(qt_own)
        qm = qm_path(lang)
        ours = QTranslator(app)
        if qm is not None and ours.load(str(qm)):
            translators.append(ours)
        elif lang in LANGUAGES:
            log.warning("the %s translation did not load", lang)
    for translator in translators:
        app.installTranslator(translator)
    _installed[:] = translators  # kept alive, and known to uninstall()
    return lang


def uninstall(app: QCoreApplication) -> None:
    """Back to English (tests switch languages in one process)."""
    for translator in _installed:
        app.removeTranslator(translator)
    _installed.clear()
    QLocale.setDefault(QLocale(QLocale.Language.English))


#: ``translate("Context", "text")``: Qt's translation outside a QObject (``self.tr`` inside).
translate = QCoreApplication.translate


def QT_TRANSLATE_NOOP(context: str, text: str) -> str:
    """Mark ``text`` for translation in ``context`` and give it back as it is, to be
    translated where it is shown. Qt's own does the same but is typed as returning
    ``object``; ``pyside6-lupdate`` finds this one by its name all the same."""
    return text
