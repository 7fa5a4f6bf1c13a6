"""One name per part in every panel and wizard: the graph, the tree, the Simulator panel,
Checks, the plan, the status bar, the events and the guided tasks all ask here, and here asks
the one naming of ``model/names.py`` (the CLI's too) with Qt's translate (context ``Names``).

A part is called by its own name (the role a system file gives it), else by what it tells
the bus (its descriptor), else by its product from the device catalogue; its serial number
is added, in plain words, only where two parts would otherwise read the same. The numbers
(VID/PID/serial) stay in tooltips and the inspector's detail (:func:`numbers`).
"""

from __future__ import annotations

import re
import threading
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.model import names as model_names
from pdcp_studio.model.catalog import default_catalog
from pdcp_studio.model.names import Names
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Device, System

if TYPE_CHECKING:
    from PySide6.QtCore import QModelIndex, QPersistentModelIndex
    from PySide6.QtWidgets import QAbstractItemView, QStyleOptionViewItem

    from pdcp_studio.model.profile_tree import ProfileTree

_CTX = "Names"
#: The templates of ``model/names.py``, marked here for Qt's translation tools.
_TEMPLATES = (
    QT_TRANSLATE_NOOP("Names", "{name} (serial {serial})"),
    QT_TRANSLATE_NOOP("Names", "{part}, {channel}"),
    QT_TRANSLATE_NOOP("Names", "channel {n}"),
    QT_TRANSLATE_NOOP("Names", "{name} ({channel})"),
    QT_TRANSLATE_NOOP("Names", "{output} → {input}"),
    QT_TRANSLATE_NOOP("Names", "VID {vid} · PID {pid} · serial {serial}"),
)
_CACHE: dict[tuple[object, ...], Names] = {}
#: The naming held for a batch (:func:`one_naming`), by thread and system.
_HELD: dict[tuple[int, int], Names] = {}


def tr(text: str) -> str:
    """A ``model/names.py`` template in the user's language."""
    return translate(_CTX, text)


def twin_format() -> str:
    """``{name} (serial {serial})``, in the user's language."""
    return tr(model_names.TWIN)


def names(system: System | None, among: Iterable[Device] = (),
          profiles: ProfileTree | None = None) -> Names:
    """The one naming of ``system`` (and ``among``) in the user's language; remembered
    while its parts' and channels' names stay the same.

    Remembered for these very objects: a naming answers from the system it was made for,
    so another system that reads the same (a copy) must not get it — the first may be
    changed in place later. (The cache keeps the objects alive, so their ids are theirs.)
    Inside :func:`one_naming` for ``system``, the naming held there."""
    if _HELD and profiles is None and not among:
        held = _HELD.get((threading.get_ident(), id(system)))
        if held is not None:
            return held
    devices = list(system.devices.values()) if system is not None else []
    keys = {d.key for d in devices}
    others = [d for d in among if d.key not in keys]
    fingerprint = (twin_format(), id(system), id(profiles), *(id(d) for d in others), *(
        (d.key, d.name, d.descriptor,
         tuple((c.index, c.descriptor, c.profile) for c in d.channels.values()))
        for d in devices + others))
    found = _CACHE.get(fingerprint)
    if found is None:
        if len(_CACHE) > 8:
            _CACHE.clear()
        found = _CACHE[fingerprint] = Names(system, profiles=profiles, among=others, tr=tr)
    return found


@contextmanager
def one_naming(system: System | None) -> Iterator[Names]:
    """For a batch that names many parts of ``system`` while nothing changes it (a plan's
    rows and ghost links, a configuration's steps): inside, on this thread, every
    :func:`names` of ``system`` (and so :func:`part_name`, :func:`channel_name`) answers from
    one naming, looked up once. Each lookup otherwise reads the whole system to see that no
    name changed — 1.7 ms on 254 devices, so a 254-device autoconfigure preview's 7,268
    lookups froze the window for 12 s."""
    naming = names(system)
    key = (threading.get_ident(), id(system))
    outer = _HELD.get(key)
    _HELD[key] = naming
    try:
        yield naming
    finally:
        if outer is None:
            del _HELD[key]
        else:
            _HELD[key] = outer


def names_among(devices: Iterable[Device]) -> dict[DeviceKey, str]:
    """The names of ``devices`` taken together (serial numbers where two read alike)."""
    return model_names.parts_named(devices, default_catalog(), twin_format())


def part_names(system: System | None, among: Iterable[Device] = ()
               ) -> dict[DeviceKey, str]:
    """Every part of ``system`` by key.

    ``among``: other parts known to be there (the graph's, for a wizard's fresh scan that
    no longer sees a part taken out): a part of ``system`` that reads like one of them
    gets its serial number too, so it is called what the graph calls it."""
    if system is None:
        return {}
    every = names(system, among).parts()
    return {k: every[k] for k in system.devices}


def part_name(system: System | None, key: DeviceKey, among: Iterable[Device] = ()) -> str:
    """The name of the part ``key`` (in ``system`` if it is there, else by its product,
    with its serial number where a part of ``system`` reads the same)."""
    return names(system, among).part(key)


def channel_name(system: System | None, ref: ChannelRef, profile_name: str = "",
                 profiles: ProfileTree | None = None) -> str:
    """``Multi-grip hand with wrist rotator, Power grip``: a channel's one name (its part's
    name as :func:`part_name` gives it). ``profile_name`` names a channel without a
    descriptor when ``profiles`` is not given (the graph's short profile name)."""
    channel = names(system, (), profiles).channel_only(ref, profile_name)
    return tr(model_names.CHANNEL).format(part=part_name(system, ref.device), channel=channel)


def numbers(key: DeviceKey) -> str:
    """``VID 2641 · PID 257 · serial 101``: the engineer's detail for a tooltip."""
    return tr(model_names.NUMBERS).format(vid=key.vid, pid=key.pid, serial=key.serial)


_TWIN_END = re.compile(r"\d+\)$")


def keep_serials_seen(view: QAbstractItemView) -> None:
    """In ``view`` (a tree or list), a name that ends in a serial number ("… (serial
    302)") is cut in the middle, so the two hands alike never read the same when the
    column is narrow; every other text is cut at its end as usual."""
    from PySide6.QtCore import Qt
    from PySide6.QtWidgets import QStyledItemDelegate

    class _TwinElide(QStyledItemDelegate):
        def initStyleOption(self, option: QStyleOptionViewItem,
                            index: QModelIndex | QPersistentModelIndex) -> None:
            super().initStyleOption(option, index)
            twin = index.column() == 0 and bool(_TWIN_END.search(option.text or "")) and \
                twin_format().format(name="", serial="").strip(" )") in option.text
            option.textElideMode = (Qt.TextElideMode.ElideMiddle if twin
                                    else view.textElideMode())

    delegate = _TwinElide(view)
    view.setItemDelegateForColumn(0, delegate)
