"""One name per part in every panel and wizard: the graph, the tree, the Simulator panel,
Checks, the plan and the guided tasks all ask here.

A part is called by its own name (what it tells the bus, or the name a system file gives
it), else by its product from the device catalogue (``model/catalog.py``); its serial
number is added, in plain words, only where two parts of the prosthesis would otherwise
read the same. The numbers (VID/PID/serial) stay in tooltips and the inspector's detail.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import TYPE_CHECKING

from pdcp_studio.app.i18n import translate
from pdcp_studio.model.catalog import default_catalog
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Device, System

if TYPE_CHECKING:
    from PySide6.QtCore import QModelIndex, QPersistentModelIndex
    from PySide6.QtWidgets import QAbstractItemView, QStyleOptionViewItem

_CTX = "PartNames"
_CACHE: dict[tuple[object, ...], dict[DeviceKey, str]] = {}


def twin_format() -> str:
    """``{name} (serial {serial})``, in the user's language."""
    return translate(_CTX, "{name} (serial {serial})")


def names_among(devices: Iterable[Device]) -> dict[DeviceKey, str]:
    """The names of ``devices`` taken together (serial numbers where two read alike)."""
    return default_catalog().part_names(devices, twin_format())


def part_names(system: System | None, among: Iterable[Device] = ()
               ) -> dict[DeviceKey, str]:
    """Every part of ``system`` by key (remembered while its parts' names stay the same).

    ``among``: other parts known to be there (the graph's, for a wizard's fresh scan that
    no longer sees a part taken out): a part of ``system`` that reads like one of them
    gets its serial number too, so it is called what the graph calls it."""
    if system is None:
        return {}
    devices = list(system.devices.values())
    keys = {d.key for d in devices}
    others = [d for d in among if d.key not in keys]
    fingerprint = (twin_format(), len(devices),
                   *((d.key, d.name, d.descriptor) for d in devices + others))
    names = _CACHE.get(fingerprint)
    if names is None:
        if len(_CACHE) > 8:
            _CACHE.clear()
        every = names_among(devices + others)
        names = _CACHE[fingerprint] = {k: every[k] for k in keys}
    return names


def part_name(system: System | None, key: DeviceKey, among: Iterable[Device] = ()) -> str:
    """The name of the part ``key`` (in ``system`` if it is there, else from the catalogue)."""
    name = part_names(system, among).get(key)
    if name is not None:
        return name
    return default_catalog().label(key)


def numbers(key: DeviceKey) -> str:
    """``VID 2641 · PID 257 · serial 101``: the engineer's detail for a tooltip."""
    return translate(_CTX, "VID {vid} · PID {pid} · serial {serial}").format(
        vid=key.vid, pid=key.pid, serial=key.serial)


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
