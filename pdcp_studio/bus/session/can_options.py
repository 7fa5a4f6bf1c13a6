"""Which ``?NAME=VALUE`` options a python-can interface knows, read from its source.

python-can's bus classes take ``**kwargs`` and drop the names they do not know, so a typo in a
URL (``?recieve_own_messages=1``) would be accepted and silently ignored — a bus opened other
than the user asked. Contracts §2 makes an option the interface refuses bad input (exit 2).
What an interface knows is read from the installed python-can itself, without importing the
interface (importing some prints driver warnings or needs Windows): the parameter names of
every function in its module (or package) and every string it looks up — the names its code
reads from ``kwargs`` — plus what ``can.BusABC`` and ``can.util``'s bus configuration take.
An interface python-can does not list (a plug-in) is not checked.

What an option's value must be is read the same way: the annotation (or, without one, the
default's type) of the parameter in the bus class's ``__init__``. An ``int``, ``float`` or
``bool`` parameter given a word (``?tty_baudrate=abc``) would fail deep inside the driver as
"cannot open adapter"; it is bad input, said before opening. Values are compared after the
URL's conversion (``can.util.cast_from_string``, as python-can's own configuration does).
Rates (baud rates, bitrates) must be above 0; sizes, timeouts and intervals 0 or more.
"""

from __future__ import annotations

import ast
import difflib
import importlib.util
import math
import re
from functools import cache
from pathlib import Path

#: Options python-can itself reads for every interface (``can.util.load_config`` and
#: ``BusABC``), and the ones PDCP Studio's URLs add (``bitrate`` comes from ``@BITRATE``).
COMMON_OPTIONS = frozenset({
    "bitrate", "data_bitrate", "fd", "timing", "state", "can_filters", "port",
    "receive_own_messages", "auto_reset", "config_context", "single_handle",
})
#: The types of the common options that are plain values (``can.util.load_config``).
COMMON_TYPES = {
    "bitrate": frozenset({"int"}), "data_bitrate": frozenset({"int"}),
    "fd": frozenset({"bool"}), "port": frozenset({"int"}),
    "receive_own_messages": frozenset({"bool"}), "auto_reset": frozenset({"bool"}),
    "single_handle": frozenset({"bool"}),
}
_PLAIN = frozenset({"int", "float", "bool"})
_IGNORED = frozenset({"None", "Optional", "Union", "typing"})
_RATE = re.compile(r"(baud|bit)_?rate|_rate$", re.IGNORECASE)
_AT_LEAST_0 = re.compile(r"size|timeout|interval|sleep", re.IGNORECASE)


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


def _annotation_names(node: ast.expr) -> set[str]:
    """The type names an annotation mentions (``Optional[int]`` → {"int"}), a quoted one
    read too; ``None``, ``Optional`` and ``Union`` are left out."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        try:
            node = ast.parse(node.value, mode="eval").body
        except SyntaxError:
            return {"?"}
    names: set[str] = set()
    for part in ast.walk(node):
        if isinstance(part, ast.Name):
            names.add(part.id)
        elif isinstance(part, ast.Attribute):
            names.add(part.attr)
    return names - _IGNORED


def _default_names(node: ast.expr | None) -> set[str]:
    """The type of a parameter's default when it has no annotation (None: unknown)."""
    if isinstance(node, ast.Constant) and node.value is not None:
        return {type(node.value).__name__}
    return {"?"}


def _init_types(tree: ast.AST, cls: str) -> dict[str, set[str]]:
    """Each ``__init__`` parameter of class ``cls`` in ``tree`` → the type names it takes."""
    types: dict[str, set[str]] = {}
    for node in ast.walk(tree):
        if not (isinstance(node, ast.ClassDef) and node.name == cls):
            continue
        for fn in node.body:
            if not (isinstance(fn, ast.FunctionDef) and fn.name == "__init__"):
                continue
            a = fn.args
            positional = a.posonlyargs + a.args
            defaults = [None] * (len(positional) - len(a.defaults)) + list(a.defaults)
            pairs = (list(zip(positional, defaults, strict=True))
                     + list(zip(a.kwonlyargs, a.kw_defaults, strict=True)))
            for arg, default in pairs:
                found = (_annotation_names(arg.annotation) if arg.annotation is not None
                         else _default_names(default))
                types.setdefault(arg.arg, set()).update(found or {"?"})
    return types


@cache
def option_types(interface: str) -> dict[str, frozenset[str]] | None:
    """The options of ``interface`` whose value is a plain ``int``, ``float`` or ``bool``
    (every definition of its bus class read: a union), or None when it cannot be told."""
    try:
        from can.interfaces import BACKENDS
    except ImportError:  # pragma: no cover - python-can is a dependency
        return None
    if interface not in BACKENDS:
        return None
    module, cls = BACKENDS[interface]
    merged: dict[str, set[str]] = {}
    try:
        for path in _source_files(module):
            for name, found in _init_types(ast.parse(path.read_text(encoding="utf-8")),
                                           cls).items():
                merged.setdefault(name, set()).update(found)
    except (OSError, SyntaxError, ValueError, ImportError):
        return None
    out = {name: frozenset(found) for name, found in merged.items() if found <= _PLAIN}
    for name, common in COMMON_TYPES.items():
        out.setdefault(name, common)
    return out


def _what(name: str, types: frozenset[str]) -> str:
    """What an option takes, in words."""
    if types == {"bool"}:
        return "true or false"
    whole = "float" not in types
    noun = "a whole number" if whole else "a number"
    if _RATE.search(name):
        return f"{noun} above 0"
    if _AT_LEAST_0.search(name):
        return f"{noun} of 0 or more"
    return noun


def _fits(name: str, types: frozenset[str], value: object) -> bool:
    if isinstance(value, bool):
        return "bool" in types
    if "bool" in types and value in (0, 1) and isinstance(value, int):
        return True  # python-can reads 1 / 0 as true / false
    if isinstance(value, int):
        number: float = value
        ok = bool(types & {"int", "float"})
    elif isinstance(value, float):
        number = value
        ok = "float" in types and math.isfinite(value)
    else:
        return False
    if not ok:
        return False
    if _RATE.search(name):
        return number > 0
    if _AT_LEAST_0.search(name):
        return number >= 0
    return True


def _shown(value: object) -> str:
    return str(value).lower() if isinstance(value, bool) else str(value)


def bad_value(interface: str, options: dict[str, object]) -> str | None:
    """Why a value of ``options`` is not one ``interface``'s parameter takes, or None."""
    types = option_types(interface)
    if types is None:
        return None
    for name, value in options.items():
        wanted = types.get(name)
        if wanted and not _fits(name, wanted, value):
            return (f"the {interface} interface's option {name!r} takes "
                    f"{_what(name, wanted)}, not {_shown(value)!r}")
    return None


def refused_option(interface: str, options: dict[str, object]) -> str | None:
    """Why ``interface`` refuses an option of ``options`` (its name, then its value), or
    None."""
    return unknown_option(interface, options) or bad_value(interface, options)


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
