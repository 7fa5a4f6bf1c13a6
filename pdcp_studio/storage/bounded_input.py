"""Reading untrusted files within stated limits: bytes read, nesting depth, duplicate keys.

A file's size on disk says nothing for standard input (a pipe has no size), so a reader asks
for at most ``limit + 1`` bytes and refuses the file when it got more: what is counted is what
was read. A path must name a regular file (``storage/regular_file.py``): a FIFO or a device
is refused in words, never waited on; standard input is ``-``. JSON nested deeper than a
stated depth is refused before it is parsed (Python's parser would recurse), and an object
that gives a key twice is refused naming the key's JSON path
(``devices[2].channels[0].profile``) instead of letting the last one win silently. ``NaN``
and ``Infinity`` are not JSON and are refused too, as are numbers of more than 40 digits or
beyond a float's range.

Errors are :class:`InputError` (a ``ValueError``) with ``reason`` and ``path``; each loader
turns them into its own error type and adds the file's name.
"""

from __future__ import annotations

import errno
import itertools
import json
import math
import os
import re
import sys
from typing import Any, BinaryIO

from pdcp_studio.storage.regular_file import open_regular

#: Standard input, as a file argument.
STDIN = "-"

# A JSON string, possessive so it is matched in linear time; an unterminated one runs to the
# end (a second attempt from every later quote would make hostile input quadratic).
_STRINGS = re.compile(rb'"(?:[^"\\]++|\\.)*+(?:"|\\?\Z)', re.DOTALL)
_NOT_BRACKETS = bytes(c for c in range(256) if c not in b"[{]}")
_STEP = [0] * 256
for _c in b"[{":
    _STEP[_c] = 1
for _c in b"]}":
    _STEP[_c] = -1


class InputError(ValueError):
    """Input refused: ``reason`` says why, ``path`` the JSON path (empty when none applies)."""

    def __init__(self, reason: str, path: str = "") -> None:
        self.reason = reason
        self.path = path
        super().__init__(f"{path}: {reason}" if path else reason)


def read_prefix(source: str | os.PathLike[str] | BinaryIO, size: int) -> bytes:
    """The first ``size`` bytes at most of a file (``"-"``: standard input).

    A path that is not a regular file raises ``NotARegularFile`` (an OSError) at once.
    """
    if isinstance(source, (str, os.PathLike)):
        if os.fspath(source) == STDIN:
            stdin = getattr(sys.stdin, "buffer", None)
            if stdin is None:  # no console, or a host that replaced it
                raise OSError(errno.EBADF, "standard input is not available", STDIN)
            return read_prefix(stdin, size)
        with open_regular(source) as handle:
            return read_prefix(handle, size)
    return source.read(size)


def read_capped(source: str | os.PathLike[str] | BinaryIO, limit: int,
                what: str = "this kind of file") -> bytes:
    """At most ``limit`` bytes of a file (``"-"``: standard input), else InputError.

    Reads ``limit + 1`` bytes at most; OSError (``NotARegularFile`` too) passes through.
    """
    data = read_prefix(source, limit + 1)
    if len(data) > limit:
        raise InputError(f"larger than {limit:,} bytes (the limit for {what}); "
                         f"refused without reading further")
    return data


def nesting_depth(data: bytes) -> int:
    """The deepest nesting of arrays and objects in JSON text (strings are skipped)."""
    brackets = _STRINGS.sub(b"", data).translate(None, _NOT_BRACKETS)
    return max(itertools.accumulate(map(_STEP.__getitem__, brackets), initial=0))


class _Object(dict[str, Any]):
    """A parsed JSON object that remembers the first key it was given twice."""

    duplicate: str | None = None


def _pairs(pairs: list[tuple[str, Any]]) -> _Object:
    obj = _Object(pairs)
    if len(obj) != len(pairs):
        seen: set[str] = set()
        for key, _ in pairs:
            if key in seen:
                obj.duplicate = key
                break
            seen.add(key)
    return obj


def _not_json(name: str) -> Any:
    raise InputError(f"{name} is not a JSON number")


#: No number PDCP Studio reads has more digits (Python refuses more than 4,300 with an error
#: of its own, and big ones are slow to convert).
MAX_NUMBER_DIGITS = 40


def _int(text: str) -> int:
    if len(text) > MAX_NUMBER_DIGITS:
        raise InputError(f"a number of {len(text):,} digits is out of any range here")
    return int(text)


def _float(text: str) -> float:
    value = float(text)
    if len(text) > MAX_NUMBER_DIGITS or not math.isfinite(value):
        raise InputError(f"the number {text[:20]}{'…' if len(text) > 20 else ''} is out of "
                         "any range here")
    return value


def _key_path(base: str, key: str) -> str:
    name = key if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", key) else json.dumps(key)
    return f"{base}.{name}" if base else name


def _first_duplicate(doc: Any) -> str | None:
    """The JSON path of the first key given twice (document order), iteratively."""
    stack: list[tuple[str, Any]] = [("", doc)]
    while stack:
        path, value = stack.pop()
        if isinstance(value, _Object):
            if value.duplicate is not None:
                return _key_path(path, value.duplicate)
            stack.extend((_key_path(path, k), v) for k, v in reversed(value.items()))
        elif isinstance(value, list):
            stack.extend((f"{path}[{i}]", v) for i, v in reversed(list(enumerate(value))))
    return None


def loads_json(data: bytes | str, *, max_depth: int) -> Any:
    """Parse JSON text strictly: depth at most ``max_depth``, no key twice, no NaN/Infinity.

    InputError names the line and column of a syntax error, the path of a duplicate key.
    """
    raw = data.encode("utf-8", "surrogatepass") if isinstance(data, str) else data
    depth = nesting_depth(raw)
    if depth > max_depth:
        raise InputError(f"nested {depth} levels deep, more than the limit of {max_depth}; "
                         "refused without reading further")
    duplicates = []

    def hook(pairs: list[tuple[str, Any]]) -> _Object:
        obj = _pairs(pairs)
        if obj.duplicate is not None:
            duplicates.append(obj)
        return obj

    try:
        doc = json.loads(raw, object_pairs_hook=hook, parse_constant=_not_json,
                         parse_int=_int, parse_float=_float)
    except json.JSONDecodeError as err:
        raise InputError(f"not valid JSON: line {err.lineno} column {err.colno}: {err.msg}") \
            from None
    except UnicodeDecodeError as err:
        raise InputError(f"not valid JSON: not UTF-8 text ({err.reason} at byte {err.start})") \
            from None
    except RecursionError:  # pragma: no cover - the depth check comes first
        raise InputError(f"nested more than {max_depth} levels deep") from None
    if duplicates:
        path = _first_duplicate(doc) or duplicates[0].duplicate or ""
        raise InputError("this key is given twice in one object", path)
    return doc
