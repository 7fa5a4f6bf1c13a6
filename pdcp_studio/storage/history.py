"""The fitting history: an append-only, hash-chained archive of every change to a prosthesis.

Reference §5: every transaction is recorded — time (UTC), operator, bus URL, the prosthesis (its
devices' VID/PID/serials), the action, links and stored configuration before and after (with
their CRC), the plan with its reasons, verified or not, the interlock's outcome — plus the
patient reference the clinic chose (free text), the workstation and how the transaction ended.

The archive itself lives in :mod:`pdcp_studio.storage.archive`: one interface, an SQLite engine
(the default: ``$PDCP_STUDIO_HISTORY`` or a file in the user's data folder) and a PostgreSQL
engine (the clinic's server), chosen by ``--archive URL`` / ``$PDCP_STUDIO_ARCHIVE``, with the
hash chain in one pure module (:mod:`pdcp_studio.storage.archive.chain`). This module keeps
the names callers know (``History.open()``, ``History(path)``) and builds an entry from a
transaction's result. On SQLite the operator is ``$PDCP_STUDIO_OPERATOR`` when set, else the
login name; on PostgreSQL the signed-in role.
"""

from __future__ import annotations

import re
from datetime import UTC, datetime
from typing import TYPE_CHECKING, Any

from pdcp_studio.storage.archive.base import (
    ENV_OPERATOR,
    Archive,
    HistoryError,
    NotAllowedError,
    default_operator,
    workstation,
)
from pdcp_studio.storage.archive.chain import GENESIS, VerifyReport, canonical, entry_hash
from pdcp_studio.storage.archive.open import ENV_ARCHIVE, ENV_PATH, default_path
from pdcp_studio.storage.archive.sqlite import BUSY_TIMEOUT_S, WAL_RETRY_S, SqliteArchive

if TYPE_CHECKING:
    from pdcp_studio.bus.transaction import Change, TransactionResult

__all__ = ["BUSY_TIMEOUT_S", "ENV_ARCHIVE", "ENV_OPERATOR", "ENV_PATH", "GENESIS", "LIST_FIELDS",
           "WAL_RETRY_S", "Archive", "History", "HistoryError", "NotAllowedError",
           "VerifyReport", "canonical", "default_operator", "default_path", "entry_from_result",
           "entry_hash", "interrupted", "list_json", "utc_now", "workstation"]

#: The fields of ``history list --json`` (contracts §2), in order.
LIST_FIELDS = ("id", "time", "operator", "bus", "action", "devices", "links_before",
               "links_after", "config_crc_before", "config_crc_after", "verified", "interlock")


def utc_now() -> str:
    return datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


if TYPE_CHECKING:
    #: Every caller names the archive ``History``: to the type checker it is the interface,
    #: whichever engine (``History.open()`` may give the clinic's PostgreSQL archive).
    History = Archive
else:
    class History(SqliteArchive):
        """One SQLite archive file (``History(path)``); ``History.open()`` is the archive in
        use, whichever engine (contracts §2; :meth:`Archive.open`)."""


def interrupted(body: dict[str, Any]) -> dict[str, Any]:
    """The entry of a change whose process stopped before it was recorded."""
    return {**body, "verified": False, "links_after": None, "config_crc_after": None,
            "outcome": {"status": "interrupted", "step": "write",
                        "reason": "the PC stopped during the change: the prosthesis holds the "
                                  "state before or after it (see the next entry or read it "
                                  "back)", "notes": []}}


def list_json(entry: dict[str, Any]) -> dict[str, Any]:
    """An entry as ``history list --json`` shows it: the contract's fields, then the patient
    reference, the outcome, the workstation and (an imported entry) its origin."""
    doc = {k: entry.get(k) for k in LIST_FIELDS}
    doc["patient"] = entry.get("patient")
    doc["outcome"] = entry.get("outcome")
    doc["workstation"] = entry.get("workstation")
    if entry.get("origin") is not None:
        doc["origin"] = entry.get("origin")
    return doc


def entry_from_result(result: TransactionResult, change: Change, *, bus: str,
                      operator: str | None = None, patient: str | None = None,
                      configuration_after: Any = None, effect: Any = None,
                      parameters_after: dict[str, dict[str, str]] | None = None
                      ) -> dict[str, Any]:
    """The history entry for a finished transaction (without ``id``); ``configuration_after``
    is the stored configuration read after it and ``parameters_after`` the parts' named
    values then (what ``history restore`` writes back); ``effect`` (``engine.effect.Effect``)
    is what the change did and what the next power-on does, in words."""
    from pdcp_studio.storage import config_codec

    plan: dict[str, Any] = {"actions": change.plan_json()}
    if change.plan is not None:
        p = change.plan
        plan["mode"] = p.mode
        plan["notes"] = list(p.notes)
        plan["rejections"] = [r.to_json() for r in p.rejections]
    if change.parameters:
        plan["parameters"] = [w.to_json() for w in change.parameters]
    doc = result.to_json()
    return {
        "time": utc_now(),
        "operator": operator or default_operator(),
        "workstation": workstation(),
        "bus": bus,
        "action": change.action,
        "devices": doc["devices"],
        "links_before": doc["links_before"],
        "links_after": doc["links_after"],
        "config_crc_before": result.config_crc_before,
        "config_crc_after": result.config_crc_after,
        "verified": result.verified,
        "interlock": result.interlock,
        "patient": patient,
        "plan": plan,
        "configuration_after": (config_codec.to_json(configuration_after)
                                if configuration_after is not None else None),
        "policy_before": doc["policy_before"],
        "policy_after": doc["policy_after"],
        "outcome": {"status": result.status.value, "step": result.step,
                    "reason": result.reason, "notes": list(result.notes)},
        "effect": effect.to_json() if effect is not None else None,
        "next_power_on": effect.power_on_json() if effect is not None else None,
        "parameters_after": parameters_after,
        "replaced": replaced_from_notes(result.notes),
    }


#: How the arbitrator notes a part it forgot as replaced (the note crosses every transport,
#: the host link's result too): ``replaced 2641/769/301 by 2641/769/302``.
_REPLACED_NOTE = re.compile(r"^replaced (\d+)/(\d+)/(\d+) by (\d+)/(\d+)/(\d+)$")


def replaced_note(old: Any, new: Any) -> str:
    """The result's note for ``old`` replaced by ``new`` (device keys)."""
    return f"replaced {old.vid}/{old.pid}/{old.serial} by {new.vid}/{new.pid}/{new.serial}"


def replaced_from_notes(notes: Any) -> list[dict[str, dict[str, int]]]:
    """The entry's ``replaced`` field: ``[{"old": {vid, pid, serial}, "new": {…}}]`` — the
    parts a verified transaction left replaced (issue 26 item 6), from the result's notes."""
    out = []
    for note in notes or ():
        m = _REPLACED_NOTE.match(str(note))
        if m:
            n = [int(g) for g in m.groups()]
            out.append({"old": {"vid": n[0], "pid": n[1], "serial": n[2]},
                        "new": {"vid": n[3], "pid": n[4], "serial": n[5]}})
    return out
