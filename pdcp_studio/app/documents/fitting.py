"""Who fits which prosthesis: the operator's name and the patient reference.

The operator (the prosthetist) is, on the clinic's archive, the signed-in role
(``sign_in.py``); else ``$PDCP_STUDIO_OPERATOR`` when set; otherwise the name asked once and
remembered in QSettings (the login name is offered). The patient reference is
free text — no more than the clinic chooses — that belongs to the prosthesis: remembered per
prosthesis (its devices' VID/PID/serials), else the one last recorded in the fitting history
for it. Both go into every history entry and the fitting report.
"""

from __future__ import annotations

import getpass
import hashlib
import os
from collections.abc import Iterable
from typing import Any

from PySide6.QtCore import QCoreApplication, QSettings
from PySide6.QtWidgets import QInputDialog, QLineEdit, QWidget

from pdcp_studio.app.i18n import translate
from pdcp_studio.model.refs import DeviceKey

ENV_OPERATOR = "PDCP_STUDIO_OPERATOR"
OPERATOR_KEY = "fitting/operator"
PATIENT_KEY = "fitting/patient/{}"


def _tr(text: str) -> str:
    return QCoreApplication.translate("Fitting", text)


def prosthesis_id(devices: Iterable[DeviceKey]) -> str:
    """A stable name for a prosthesis: a digest of its devices' VID/PID/serials, sorted."""
    text = ",".join(f"{k.vid}/{k.pid}/{k.serial}" for k in sorted(set(devices)))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def login_name() -> str:
    try:
        return getpass.getuser()
    except Exception:  # no login name on this system
        return ""


def stored_operator(settings: QSettings | None = None) -> str:
    """The operator without asking: the role signed in to the clinic's archive, else the
    environment, else the remembered name ("" if none)."""
    from pdcp_studio.app.documents.sign_in import signed_in_operator

    signed = signed_in_operator()
    if signed:  # the clinic's archive records the signed-in role, whatever else says
        return signed
    env = os.environ.get(ENV_OPERATOR, "").strip()
    if env:
        return env
    return str((settings or QSettings()).value(OPERATOR_KEY, "") or "").strip()


def operator_name(parent: QWidget | None = None, *, settings: QSettings | None = None,
                  ask: Any = None) -> str:
    """The operator's name, asked once and remembered ("" when the user declines).

    ``ask(parent, default) -> str | None`` replaces the dialog (tests)."""
    name = stored_operator(settings)
    if name:
        return name
    asker = ask or _ask_operator
    answer = asker(parent, login_name())
    name = (answer or "").strip()
    if name:
        set_operator(name, settings)
    return name


def set_operator(name: str, settings: QSettings | None = None) -> None:
    (settings or QSettings()).setValue(OPERATOR_KEY, name.strip())


def _ask_operator(parent: QWidget | None, default: str) -> str | None:
    text, ok = QInputDialog.getText(
        parent,
        translate("Fitting", "Your name"),
        translate(
            "Fitting",
            "Changes to a prosthesis are recorded in the fitting history with the name of "
            "who made them.\nYour name (asked once):",
        ),
        QLineEdit.EchoMode.Normal,
        default,
    )
    return text if ok else None


def patient_reference(devices: Iterable[DeviceKey], *, settings: QSettings | None = None,
                      history_entries: Iterable[dict[str, Any]] = ()) -> str:
    """The prosthesis's patient reference: remembered here, else the newest one recorded in
    the fitting history for the same devices ("" if none)."""
    keys = sorted(set(devices))
    value = (settings or QSettings()).value(PATIENT_KEY.format(prosthesis_id(keys)), None)
    if value is not None:
        return str(value)
    wanted = {(k.vid, k.pid, k.serial) for k in keys}
    for entry in reversed(list(history_entries)):
        got = {(d.get("vid"), d.get("pid"), d.get("serial")) for d in entry.get("devices") or ()}
        if got and got == wanted and entry.get("patient"):
            return str(entry["patient"])
    return ""


def set_patient_reference(devices: Iterable[DeviceKey], text: str, *,
                          settings: QSettings | None = None) -> None:
    (settings or QSettings()).setValue(PATIENT_KEY.format(prosthesis_id(devices)), text.strip())
