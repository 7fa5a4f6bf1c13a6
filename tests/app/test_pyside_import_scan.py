"""PySide6's per-import source scan replaced by a look at the module's namespace
(``app/pyside_import_scan.py``): no source file read, the same answer for Qt modules."""

from __future__ import annotations

import subprocess
import sys
import textwrap

SCRIPT = textwrap.dedent('''
    import linecache, sys
    sys.path.insert(0, sys.argv[1])
    from pdcp_studio.app.pyside_import_scan import spare_source_scan
    assert spare_source_scan(), "PySide6's import hook was not found"
    linecache.clearcache()
    import with_qt, without_qt
    from shibokensupport import feature
    print(feature.pyside_feature_dict["with_qt"], feature.pyside_feature_dict["without_qt"])
    print(sorted(name for name in linecache.cache if "with" in name))
    from PySide6.QtCore import QCoreApplication, QTimer
    app = QCoreApplication([])
    fired = []
    QTimer.singleShot(0, lambda: (fired.append(1), app.quit()))
    app.exec()
    print(fired)
''')


def test_modules_imported_after_qt_are_sorted_without_reading_their_source(tmp_path):
    (tmp_path / "with_qt.py").write_text("from PySide6.QtCore import QObject\n")
    (tmp_path / "without_qt.py").write_text("import json\nVALUE = json.dumps([1])\n")
    done = subprocess.run([sys.executable, "-c", SCRIPT, str(tmp_path)], capture_output=True,
                          text=True, timeout=120, env={"QT_QPA_PLATFORM": "offscreen",
                                                       "PATH": "/usr/bin:/bin",
                                                       "PYTHONPATH": ":".join(sys.path)})
    assert done.returncode == 0, done.stderr
    flags, read, fired = done.stdout.splitlines()
    assert flags == "0 -1"  # as PySide6's own scan answers: uses Qt / does not
    assert read == "[]", "a module's source was read into linecache"
    assert fired == "[1]"  # Qt works as before


def test_a_namespace_without_qt_is_not_taken_for_qt():
    import json
    import types

    from pdcp_studio.app.pyside_import_scan import uses_pyside

    assert not uses_pyside(json)
    odd = types.ModuleType("odd")

    class Raises:
        def __getattribute__(self, name):
            raise RuntimeError(name)

    odd.thing = Raises()
    assert not uses_pyside(odd)
