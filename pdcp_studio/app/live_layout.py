"""Card positions of a live view, remembered per prosthesis instead of asked to be saved.

On a live bus with no project file the bus is the document: moving a card there is not a
change anyone should be asked to save ("Save the changes to sim:thesis-test4?"). The
positions are kept in the application's settings under the prosthesis's bus URL and used
again the next time it is connected; only the layout is kept (never links or parameters).
"""

from __future__ import annotations

import hashlib
import json
import logging
from typing import Any

from PySide6.QtCore import QSettings

from pdcp_studio.model.refs import DeviceKey

log = logging.getLogger(__name__)

GROUP = "live_layouts"
#: Prostheses remembered at most (the least recently saved are forgotten).
MAX_LAYOUTS = 50


def _key(url: str) -> str:
    # A URL holds "/" and ":", which QSettings reads as groups: name it by a digest.
    return f"{GROUP}/{hashlib.sha1(url.encode('utf-8')).hexdigest()[:16]}"


def load(url: str) -> dict[DeviceKey, tuple[float, float]]:
    """The card positions remembered for ``url`` (empty when none or unreadable)."""
    if not url:
        return {}
    raw = QSettings().value(_key(url), "")
    if not raw:
        return {}
    try:
        doc = json.loads(str(raw))
        out = {}
        for text, (x, y) in doc.get("positions", {}).items():
            vid, pid, serial = (int(v) for v in text.split("/"))
            out[DeviceKey(vid, pid, serial)] = (float(x), float(y))
        return out
    except (ValueError, TypeError, AttributeError) as err:
        log.warning("remembered layout of %s ignored: %s", url, err)
        return {}


def save(url: str, positions: dict[Any, tuple[float, float]]) -> None:
    """Remember ``positions`` for ``url`` (QSettings writes its file safely)."""
    if not url:
        return
    import time

    settings = QSettings()
    doc = {"url": url, "saved": time.time(),
           "positions": {f"{k.vid}/{k.pid}/{k.serial}": [round(x, 1), round(y, 1)]
                         for k, (x, y) in positions.items()}}
    settings.setValue(_key(url), json.dumps(doc))
    _forget_oldest(settings)


def _forget_oldest(settings: QSettings) -> None:
    settings.beginGroup(GROUP)
    try:
        keys = settings.childKeys()
        if len(keys) <= MAX_LAYOUTS:
            return
        ages = []
        for k in keys:
            try:
                ages.append((float(json.loads(str(settings.value(k))).get("saved", 0)), k))
            except (ValueError, TypeError, AttributeError):
                ages.append((0.0, k))
        for _age, k in sorted(ages)[:len(keys) - MAX_LAYOUTS]:
            settings.remove(k)
    finally:
        settings.endGroup()
