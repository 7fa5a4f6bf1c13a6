"""The banner over an opened capture: what it is, in the CLI's verdict (``pdcp``,
``not-pdcp``, ``empty``) said in words, where its node map came from, its format, and
whether it was cut short or stopped — so a car's candump never passes for a prosthesis."""

from __future__ import annotations

from pathlib import Path

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.files.capture import CaptureVerdict, NodeMapNote
from pdcp_studio.app.words.plural import count

_C = "MonitorDock"


def node_map_text(note: NodeMapNote) -> str:
    """Where the capture's node map came from ("node map inferred from traffic: …")."""
    devices = count(_C, "%n device(s)", note.devices)
    channels = count(_C, "%n channel(s)", note.channels)
    if note.source == "file":
        return translate(_C, "node map from {name}").format(name=Path(note.path).name)
    if note.source == "set-up":
        return translate(_C, "node map from the capture's set-up: {devices}, {channels}").format(
            devices=devices, channels=channels)
    if note.source == "inferred":
        return translate(_C, "node map inferred from traffic: {devices}, {channels}").format(
            devices=devices, channels=channels)
    return translate(_C, "no node map (no set-up in the capture, nothing to infer from)")


def verdict_text(verdict: CaptureVerdict, *, reading: bool = False) -> str:
    """The banner's text for ``verdict`` (``reading``: the capture is still being read)."""
    if verdict.cancelled and not verdict.frames:
        return translate(_C, "Stopped before the first frames were read")
    if verdict.verdict == "empty" and not reading:
        head = translate(_C, "Empty capture: no frames")
    elif verdict.verdict == "not-pdcp":
        head = translate(_C, "Not PDCP: shown as plain CAN frames")
    elif verdict.verdict == "empty":
        head = translate(_C, "Reading…")
    else:
        head = translate(_C, "PDCP capture")
        if verdict.node_map is not None:
            head += " · " + node_map_text(verdict.node_map)
    if verdict.format_name:
        head += " · " + verdict.format_name
    if verdict.damage:
        head += "\n" + translate(
            _C, "Cut short: {damage} — the {frames} frames before it are shown").format(
                damage=verdict.damage, frames=f"{verdict.frames:,}")
    elif verdict.cancelled:
        head += "\n" + translate(_C, "Stopped: the first {frames} frames are shown").format(
            frames=f"{verdict.frames:,}")
    return head


def problem_text(message: str) -> str:
    """Where the rows would be, when the capture could not be read at all."""
    return translate(_C, "This capture could not be read:\n{message}").format(message=message)
