"""Frozen dataclasses whose equality, hash and repr are shared instead of generated per class.

Python 3.11's ``dataclass`` writes and compiles ``__eq__``, ``__hash__`` and ``__repr__`` anew
for every class (an ``exec`` each). For the protocol's 23 messages and the bus's events that
was half of importing them, and the app imports them while it opens the simulated prosthesis
(issue 11). A class declared ``@dataclass(frozen=True, eq=False, repr=False)`` that derives
from :class:`Record` behaves exactly as ``@dataclass(frozen=True)`` would: equal to an instance
of the same class whose compared fields are equal, hashed by the same fields, shown as
``Name(field=value, …)``; ``fields``, ``replace`` and ``asdict`` work as on any dataclass.
A mutable one (``@dataclass(eq=False, repr=False)`` deriving from :class:`MutableRecord`)
behaves as ``@dataclass``: compared and shown the same way, and unhashable.
"""

from __future__ import annotations

import reprlib
from dataclasses import fields

#: Per class: (compared field names, hashed field names, shown field names), as dataclass
#: chooses them (``compare``, ``hash`` and ``repr`` of each field).
_NAMES: dict[type, tuple[tuple[str, ...], tuple[str, ...], tuple[str, ...]]] = {}


def _names(cls: type) -> tuple[tuple[str, ...], tuple[str, ...], tuple[str, ...]]:
    names = _NAMES.get(cls)
    if names is None:
        flds = fields(cls)
        names = _NAMES[cls] = (
            tuple(f.name for f in flds if f.compare),
            tuple(f.name for f in flds if (f.compare if f.hash is None else f.hash)),
            tuple(f.name for f in flds if f.repr),
        )
    return names


class Record:
    """The methods ``dataclass(frozen=True)`` would generate for each class, written once."""

    __slots__ = ()

    def __eq__(self, other: object) -> bool:
        if other.__class__ is self.__class__:
            compared = _names(self.__class__)[0]
            return (tuple(getattr(self, n) for n in compared)
                    == tuple(getattr(other, n) for n in compared))
        return NotImplemented

    def __hash__(self) -> int:
        return hash(tuple(getattr(self, n) for n in _names(self.__class__)[1]))

    @reprlib.recursive_repr()
    def __repr__(self) -> str:
        shown = ", ".join(f"{n}={getattr(self, n)!r}" for n in _names(self.__class__)[2])
        return f"{self.__class__.__qualname__}({shown})"



class MutableRecord(Record):
    """What ``dataclass()`` generates for a mutable class: equality and repr; no hash."""

    __slots__ = ()
    __hash__ = None  # type: ignore[assignment]
