"""PySide6 without its source scan of every module imported after it.

Importing PySide6 replaces ``builtins.__import__``: after every import it asks whether the new
module "uses PySide" (for its opt-in ``from __feature__ import snake_case, true_property``) by
reading the module's whole source with ``inspect.getsource`` and searching it for "PySide6".
For an app that imports networkx, python-can, numpy and its own packages after Qt, that reads
~300 source files into ``linecache`` at start-up: measured on this project's 2-core machine,
``import PySide6.QtWidgets; import networkx, can, numpy`` peaks at 100 MB RSS against 77 MB
with the check below (the same imports before PySide6: 77 MB), and costs CPU time at start-up.

The check below answers the same question from what the module holds once it has run — an
object or submodule of PySide6 or shiboken6 in its namespace — without reading a file.
PDCP Studio selects no ``__feature__``, so the answer only sorts modules for PySide6's
bookkeeping; a module that imports Qt inside its functions is counted as not using it, which
with no feature selected anywhere changes nothing. Where PySide6 lacks the hook (another
version), nothing is changed.
"""

from __future__ import annotations

import types

_QT_PACKAGES = ("PySide6", "shiboken6")


def uses_pyside(module: types.ModuleType) -> bool:
    """Whether ``module``'s namespace holds something of PySide6 (read from memory only)."""
    try:
        values = list(vars(module).values())
    except TypeError:
        return False
    for value in values:
        try:
            name = value.__name__ if type(value) is types.ModuleType \
                else getattr(value, "__module__", None)
        except Exception:  # an object whose attribute access fails: not Qt's
            continue
        if type(name) is str and name.startswith(_QT_PACKAGES):
            return True
    return False


def spare_source_scan() -> bool:
    """Import PySide6 and replace its per-import source scan by :func:`uses_pyside`; True
    when the hook was found and replaced (call once, before the app's own imports)."""
    import PySide6.QtCore  # noqa: F401  - installs the import hook

    try:
        from shibokensupport import feature
    except ImportError:
        return False
    if not callable(getattr(feature, "_mod_uses_pyside", None)):
        return False
    feature._mod_uses_pyside = uses_pyside
    return True
