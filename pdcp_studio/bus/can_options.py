"""Which ``?NAME=VALUE`` options a python-can interface knows, read from its source.

python-can's bus classes take ``**kwargs`` and drop the names they do not know, so a typo in a
URL (``?recieve_own_messages=1``) would be accepted and silently ignored — a bus opened other
than the user asked. Contracts §2 makes an option the interface refuses bad input (exit 2).
What an interface knows is read from the installed python-can itself, without importing the
interface (importing some prints driver warnings or needs Windows): the parameter names of
every function in its module (or package) and every string it looks up — the names its code
reads from ``kwargs`` — plus what ``can.BusABC`` and ``can.util``'s bus configuration take.
An interface python-can does not list (a plug-in) is not checked.
"""

from __future__ import annotations

import ast
import difflib
import importlib.util
from functools import cache
from pathlib import Path

#: Options python-can itself reads for every interface (``can.util.load_config`` and
#: ``BusABC``), and the ones PDCP Studio's URLs add (``bitrate`` comes from ``@BITRATE``).
COMMON_OPTIONS = frozenset({
    "bitrate", "data_bitrate", "fd", "timing", "state", "can_filters", "port",
    "receive_own_messages", "auto_reset", "config_context", "single_handle",
})


def _names_in(source: str) -> set[str]:
    """Every parameter name and every identifier-like string constant in ``source``."""
    names: set[str] = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.arg):
            names.add(node.arg)
        elif isinstance(node, ast.Constant) and isinstance(node.value, str) \
                and node.value.isidentifier():
            names.add(node.value)
    return names


def _source_files(module: str) -> list[Path]:
    """The interface module's file, or every file of its package (``pcan/``, ``vector/``)."""
    spec = importlib.util.find_spec(module.rsplit(".", 1)[0])  # the parent never needs a driver
    if spec is None or not spec.submodule_search_locations:
        return []
    parent = Path(next(iter(spec.submodule_search_locations)))
    leaf = module.rsplit(".", 1)[1]
    if (parent / f"{leaf}.py").is_file():
        if parent.name == "interfaces":
            return [parent / f"{leaf}.py"]
        return sorted(parent.glob("*.py"))  # an interface package: its helpers read kwargs too
    return sorted((parent / leaf).glob("*.py"))


@cache
def known_options(interface: str) -> frozenset[str] | None:
    """The option names ``interface`` can read, or None when it cannot be told (a plug-in,
    or python-can's source is not on disk)."""
    try:
        from can.interfaces import BACKENDS
    except ImportError:  # pragma: no cover - python-can is a dependency
        return None
    if interface not in BACKENDS:
        return None
    module, _cls = BACKENDS[interface]
    try:
        files = _source_files(module)
        names: set[str] = set()
        for path in files:
            names |= _names_in(path.read_text(encoding="utf-8"))
    except (OSError, SyntaxError, ValueError, ImportError):
        return None
    if not names:
        return None
    return frozenset(names | COMMON_OPTIONS)


def unknown_option(interface: str, options: dict[str, object]) -> str | None:
    """Why an option of ``options`` is one ``interface`` does not know, or None."""
    known = known_options(interface)
    if known is None:
        return None
    for name in options:
        if name not in known:
            close = difflib.get_close_matches(name, sorted(known), n=1, cutoff=0.75)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            return f"the {interface} interface has no option {name!r}{hint}"
    return None
