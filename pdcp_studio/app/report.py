"""A one-page fitting report as PDF: what was fitted, how it is linked, its checksum.

Public API
    ``write_report(path, system, tree, graph_image=None, title=..., *, date=None,
    collection=None) -> Path`` — GUI thread (text layout); about 50 ms for a small rig.
    ``graph_image`` is a ``QImage`` of the bus graph (the main window renders its scene);
    ``collection`` a stored configuration whose checksum to print instead of the on-screen
    links'. ``configuration_checksum(system, collection=None) -> int`` and
    ``report_html(...)`` are the parts, for previews and tests.

The prosthetist files it with the patient's records, so it names every device by
VID/PID/serial, every link with its profile names, and the CRC-16 checksum the stored
configuration carries (the value ``pdcp-studio config decode`` verifies), so a later
reading of the arbitrator can be matched against the paper. With a :class:`FittingInfo`
(``fitting=``) the report fills in the patient reference, the prosthetist and the time of
the session, lists the changes made in this session (from the fitting history) and the
findings of the checks; devices carry their firmware and hardware versions, and links to a
missing device are marked as such. Without one, those fields are blank lines to fill in.

The page is an HTML ``QTextDocument`` laid out at 96 dpi and drawn on a ``QPdfWriter``
through a scaled painter; if the content is taller than the page it is scaled down to fit,
so the report is always exactly one page.
"""

from __future__ import annotations

import datetime as _dt
import html
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QBuffer, QIODevice, QMarginsF, QSizeF, Qt, QUrl
from PySide6.QtGui import (
    QGuiApplication,
    QImage,
    QPageLayout,
    QPageSize,
    QPainter,
    QPdfWriter,
    QTextDocument,
)

from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.words.plural import count
from pdcp_studio.model import profile as prof
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.profile_tree import ProfileTree
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System
from pdcp_studio.storage.atomic import atomic_write_bytes

if TYPE_CHECKING:
    from pdcp_studio.bus.transaction import Policy

_CTX = "FittingReport"
#: The source text; shown translated (``_t``) like every word of the report.
DEFAULT_TITLE = QT_TRANSLATE_NOOP("FittingReport", "PDCP fitting report")
LAYOUT_DPI = 96.0
PDF_DPI = 300
GRAPH_MAX_HEIGHT_FRACTION = 0.38  # of the page: leaves room for the tables
_GRAPH_URL = QUrl("pdcp-report:graph")
_app: QGuiApplication | None = None


@dataclass
class FittingInfo:
    """Who, for whom, when and what: the session's part of a fitting report.

    ``changes`` are fitting-history entries (dicts as ``History.entries`` returns them), in
    the order they were made; ``time`` is UTC."""

    patient: str = ""
    prosthetist: str = ""
    time: _dt.datetime | None = None
    bus: str = ""
    changes: list[dict[str, Any]] = field(default_factory=list)
    #: The prosthesis's profile-layer policy (a ``Policy``; None: not known, e.g. offline).
    policy: Policy | None = None


def _t(text: str) -> str:
    """``text`` in the app's language (the German build prints a German report)."""
    return translate(_CTX, text)


#: Fitting-history actions and their words, by the action's first words.
_ACTIONS = (
    ("config write", QT_TRANSLATE_NOOP("FittingReport", "Stored set-up written")),
    ("config save", QT_TRANSLATE_NOOP("FittingReport", "Current links stored as the set-up")),
    ("policy autoconfigure on", QT_TRANSLATE_NOOP("FittingReport", "Autoconfigure turned on")),
    ("policy autoconfigure off", QT_TRANSLATE_NOOP("FittingReport", "Autoconfigure turned off")),
    ("add link", QT_TRANSLATE_NOOP("FittingReport", "Link added")),
    ("remove link", QT_TRANSLATE_NOOP("FittingReport", "Link removed")),
    ("set parameter", QT_TRANSLATE_NOOP("FittingReport", "Setting changed")),
    ("write to prosthesis",
     QT_TRANSLATE_NOOP("FittingReport", "Changes written to the prosthesis")),
)
_OUTCOMES = {
    "applied": QT_TRANSLATE_NOOP("FittingReport", "applied"),
    "rolled_back": QT_TRANSLATE_NOOP("FittingReport", "rolled back"),
    "failed": QT_TRANSLATE_NOOP("FittingReport", "failed"),
}
_SEVERITIES = {
    "error": QT_TRANSLATE_NOOP("FittingReport", "Error"),
    "warning": QT_TRANSLATE_NOOP("FittingReport", "Warning"),
    "info": QT_TRANSLATE_NOOP("FittingReport", "Info"),
}


def _version(value: int) -> str:
    return f"{value >> 8}.{value & 0xFF}" if value else "—"


def action_words(action: str) -> str:
    """A fitting-history action (``config write``, ``apply autoconfigure``, ``policy
    autoconfigure off``…) in words for the report; unknown ones as they are."""
    from pdcp_studio.app.docks.plan_panel import OPERATIONS

    words = action.strip()
    low = words.lower()
    if low.startswith("undo "):
        return _t("Undone: {0}").format(action_words(words[5:]))
    if low.startswith("redo "):
        return _t("Done again: {0}").format(action_words(words[5:]))
    if low.startswith("apply "):
        mode = low.split()[1] if len(low.split()) > 1 else ""
        known = dict(OPERATIONS).get(mode)
        title = translate("PlanPanel", known) if known else mode.replace("-", " ")
        return _t("{0} carried out").format(title)
    for prefix, text in _ACTIONS:
        if low.startswith(prefix):
            return _t(text)
    return words


def _change_rows(changes: list[dict[str, Any]]) -> str:
    rows = []
    for e in changes:
        outcome = e.get("outcome") or {}
        status = outcome.get("status", "")
        word = _t(_OUTCOMES[status]) if status in _OUTCOMES else status
        if status == "applied" and e.get("verified"):
            word = _t("applied, verified")
        actions = (e.get("plan") or {}).get("actions") or []
        adds = sum(1 for a in actions if a.get("op") == "add")
        removes = len(actions) - adds
        params = len((e.get("plan") or {}).get("parameters") or [])
        what = _t("{added}, {removed}").format(added=count(_CTX, "%n link(s) added", adds),
                                               removed=count(_CTX, "%n removed", removes))
        if params:
            what += ", " + count(_CTX, "%n parameter(s)", params)
        rows.append(f"<tr><td>{_e(e.get('id', ''))}</td>"
                    f"<td>{_e(str(e.get('time', '')).replace('T', ' ').rstrip('Z'))}</td>"
                    f"<td>{_e(action_words(str(e.get('action', ''))))}</td><td>{_e(what)}</td>"
                    f"<td>{_e(word)}</td><td>{_e(e.get('operator') or '')}</td></tr>")
    return "".join(rows) or (f"<tr><td colspan=6><i>{_e(_t('no change was made in this session'))}"
                             "</i></td></tr>")


def _finding_rows(system: System, autoconfigure: bool = True) -> str:
    from pdcp_studio.app.words.finding_text import plain_finding
    from pdcp_studio.engine import check_system

    findings = check_system(system, autoconfigure=autoconfigure) if system.devices else []
    rows = [f"<tr><td>{_e(_t(_SEVERITIES.get(f.severity.value, f.severity.value)))}</td>"
            f"<td>{_e(plain_finding(f, system, autoconfigure))}</td></tr>"
            for f in findings]
    return "".join(rows) or f"<tr><td colspan=2><i>{_e(_t('every check passed'))}</i></td></tr>"


def configuration_checksum(system: System, collection: ConfigCollection | None = None) -> int:
    """The CRC-16/CCITT-FALSE checksum record ``config_codec`` writes for ``collection``
    (default: the system's links as configuration 1) — what ``config decode`` shows."""
    from pdcp_studio.engine import configuration_from_system
    from pdcp_studio.storage import config_codec

    if collection is None:
        collection = ConfigCollection([configuration_from_system(system)])
    checksum = config_codec.decode(config_codec.dumps(collection)).checksum
    assert checksum is not None  # the writer always emits one
    return checksum


def _e(text: object) -> str:
    return html.escape(str(text))


def _profile(tree: ProfileTree, value: int) -> str:
    """What a channel carries, by the profile tree's names (the code is in the detail)."""
    if tree.node(value) is None:
        return f"<i>{_e(_t('a kind of signal the profile tree does not name'))}</i>"
    return _e(tree.name_of(value))


def _device_name(system: System, key: DeviceKey) -> str:
    from pdcp_studio.app.words.part_names import part_name

    return part_name(system, key)


def _end(system: System, tree: ProfileTree, ref: ChannelRef, compact: bool = False) -> str:
    ch = system.channel(ref)
    name = _device_name(system, ref.device)
    if compact:
        what = tree.short_name(ch.profile) if ch and tree.node(ch.profile) else ""
        return (_t("{device}, channel {n}").format(device=_e(name), n=ref.index)
                + (f" ({_e(what)})" if what else ""))
    desc = f" — {ch.descriptor}" if ch and ch.descriptor else ""
    profile = _profile(tree, ch.profile) if ch else "?"
    end = _t("{device}, channel {n}").format(device=f"<b>{_e(name)}</b>", n=ref.index)
    return f"{end}{_e(desc)}<br>{profile}"


def _detail_rows(system: System) -> str:
    """The engineer's detail: identities and channel codes, for matching a reading."""
    rows = []
    for i, lk in enumerate(system.links, 1):
        ends = []
        for ref in (lk.output, lk.input):
            ch = system.channel(ref)
            codes = (_t("type {type}, profile {profile}").format(
                type=prof.fmt(ch.type), profile=prof.fmt(ch.profile)) if ch
                else _t("not on the bus"))
            ends.append(_t("VID {vid} PID {pid} serial {serial} channel {index} ({codes})")
                        .format(vid=f"0x{ref.vid:04X}", pid=f"0x{ref.pid:04X}",
                                serial=ref.serial, index=ref.index, codes=_e(codes)))
        rows.append(f"<tr><td>{i}</td><td>{ends[0]}</td><td>→</td><td>{ends[1]}</td></tr>")
    return "".join(rows)


def _device_rows(system: System, per_row: int) -> str:
    from pdcp_studio.model.catalog import default_catalog

    catalog = default_catalog()
    cells = []
    for d in system.devices.values():
        state = f" <i>{_e(_t('(missing)'))}</i>" if not d.present else ""
        entry = catalog.lookup(d.vid, d.pid)
        product = (_t("{product} ({vendor})").format(product=entry.product, vendor=entry.vendor)
                   if entry else _t("not in the catalogue"))
        cells.append(f"<td>{_e(_device_name(system, d.key))}{state}</td><td>{_e(product)}</td>"
                     f"<td>{d.vid} / {d.pid} / {d.serial}</td>"
                     f"<td>{_version(d.fw_version)}</td><td>{_version(d.hw_version)}</td>")
    if not cells:
        return f"<tr><td colspan=5><i>{_e(_t('no devices'))}</i></td></tr>"
    cells += ["<td></td>" * 5] * (-len(cells) % per_row)
    return "".join("<tr>" + "".join(cells[i:i + per_row]) + "</tr>"
                   for i in range(0, len(cells), per_row))


def report_html(system: System, tree: ProfileTree, *, title: str | None = None,
                date: _dt.date | None = None, graph_size: QSizeF | None = None,
                checksum: int | None = None, compact: bool = False,
                stored_note: str = "", fitting: FittingInfo | None = None) -> str:
    """The report's HTML (for tests and previews); ``graph_size`` adds the graph image.

    ``compact`` (for big systems) puts three devices on a row and one line per link.
    """
    date = date or _dt.date.today()
    title = title or _t(DEFAULT_TITLE)
    blank = "_" * 38
    per_row = 3 if compact else 1
    columns = (_t("Name"), _t("Product"), _t("Maker / product / serial no."), _t("Firmware"),
               _t("Hardware"))
    widths = ("", "", "", "", "") if compact else (" width=26%", " width=26%", " width=22%",
                                                   " width=13%", " width=13%")
    heads = "".join(f"<th{w}>{_e(c)}</th>" for w, c in zip(widths, columns, strict=True))
    devices = f"<tr>{heads * per_row}</tr>{_device_rows(system, per_row)}"

    def missing(lk: Link) -> str:
        gone = [system.device(r.device) for r in (lk.output, lk.input)]
        if any(d is None or not d.present for d in gone):
            return f" <i style='color:#b00000'>{_e(_t('(to a missing device)'))}</i>"
        return ""

    links = "".join(
        f"<tr><td>{i}</td><td>{_end(system, tree, lk.output, compact)}</td><td>→</td>"
        f"<td>{_end(system, tree, lk.input, compact)}{missing(lk)}</td></tr>"
        for i, lk in enumerate(system.links, 1)
    ) or f"<tr><td colspan=4><i>{_e(_t('no links'))}</i></td></tr>"
    info = fitting
    when = date.isoformat()
    patient = prosthetist = prosthesis = blank
    session_html = ""
    policy_html = ""
    autoconfigure = True
    if info is not None and info.policy is not None:
        autoconfigure = bool(info.policy.autoconfigure)
        policy_html = "<p>" + (
            _t("Autoconfigure: {on} (the prosthesis may link parts that nothing drives on "
               "its own)").format(on=f"<b>{_e(_t('on'))}</b>") if autoconfigure
            else _t("Autoconfigure: {off} (the prosthesis repairs known links and finds "
                    "replacements for missing parts, but links nothing new on its own)")
            .format(off=f"<b>{_e(_t('off'))}</b>")) + "</p>"
    if info is not None:
        if info.time is not None:
            when = info.time.strftime("%Y-%m-%d %H:%M UTC")
        patient = _e(info.patient) or blank
        prosthetist = _e(info.prosthetist) or blank
        prosthesis = _e(info.bus) or blank
        cells = "".join(f"<th>{_e(c)}</th>" for c in (
            "#", _t("Time (UTC)"), _t("Action"), _t("Change"), _t("Outcome"), _t("By")))
        session_html = (
            f"<h2>{_e(_t('Changes made in this session ({n})').format(n=len(info.changes)))}"
            f"</h2><table class=grid width=100%><tr>{cells}</tr>"
            f"{_change_rows(info.changes)}</table>")
    findings = (f"<h2>{_e(_t('Checks'))}</h2><table class=grid width=100%><tr>"
                f"<th width=12%>{_e(_t('Finding'))}</th><th>{_e(_t('What'))}</th></tr>"
                f"{_finding_rows(system, autoconfigure)}</table>")
    crc = "—" if checksum is None else f"0x{checksum:04X}"
    detail = _detail_rows(system) if not compact else ""
    graph = ""
    if graph_size is not None:
        graph = (f"<p align=center><img src='{_GRAPH_URL.toString()}' "
                 f"width={graph_size.width():.0f} height={graph_size.height():.0f}></p>")
    return f"""
<style>
 body {{ font-family: 'DejaVu Sans', sans-serif; font-size: 9pt; }}
 h1 {{ font-size: 16pt; margin-bottom: 2px; }}
 h2 {{ font-size: 11pt; margin-top: 10px; margin-bottom: 3px; }}
 table.grid {{ border-collapse: collapse; }}
 table.grid td, table.grid th {{ border: 1px solid #999; padding: 2px 5px; }}
 th {{ background: #e8e8e8; text-align: left; }}
 .hex {{ color: #555; font-family: 'DejaVu Sans Mono', monospace; }}
</style>
<h1>{_e(title)}</h1>
<p>{_e(_t("Date: {0}").format(when))}</p>
<table cellpadding=3>
 <tr><td>{_e(_t("Patient:"))}</td><td>{patient}</td><td>{_e(_t("Prosthesis:"))}</td>
 <td>{prosthesis}</td></tr>
 <tr><td>{_e(_t("Prosthetist:"))}</td><td>{prosthetist}</td><td>{_e(_t("Signature:"))}</td>
 <td>{blank}</td></tr>
</table>
{policy_html}
<h2>{_e(_t("Devices ({n})").format(n=len(system.devices)))}</h2>
<table class=grid width=100%>{devices}</table>
<h2>{_e(_t("Links ({n})").format(n=len(system.links)))}</h2>
<table class=grid width=100%>
 <tr><th width=4%>#</th><th width=46%>{_e(_t("Output"))}</th><th width=3%></th>
 <th width=47%>{_e(_t("Input"))}</th></tr>{links}
</table>
<h2>{_e(_t("Stored set-up"))}</h2>
<p>{_t("Check number: {crc}{note}. A later reading of the prosthesis that shows the same "
       "number has the same links.").format(crc=f"<b class=hex>{crc}</b>",
                                            note=_e(stored_note))}</p>
{session_html}
{findings}
{graph}
<h2 style='font-size:8pt'>{_e(_t("Technical detail"))}</h2>
<p style='font-size:7pt; color:#444'>{_e(_t(
    "Check number: CRC-16/CCITT-FALSE of the stored configuration record. Links by identity "
    "(VID, PID, serial number, channel index) with the channels' type and profile codes:"))}</p>
<table style='font-size:7pt; color:#444' cellpadding=1>{detail}</table>
<p style='color:#777; font-size:7pt'>{_e(_t("Generated by PDCP Studio."))}</p>
"""


def _ensure_gui_app() -> None:
    """Text layout needs a QGuiApplication; a command-line caller may not have made one."""
    global _app
    if QGuiApplication.instance() is None:
        _app = QGuiApplication([])


def write_report(path: str | Path, system: System, tree: ProfileTree,
                 graph_image: QImage | None = None, title: str | None = None, *,
                 date: _dt.date | None = None,
                 collection: ConfigCollection | None = None,
                 fitting: FittingInfo | None = None) -> Path:
    """Write the one-page A4 PDF report to ``path``; returns the path.

    The checksum is that of ``collection`` (e.g. the arbitrator's stored configuration) or,
    by default, of the system's links stored as configuration 1. OSError if it cannot write.
    """
    _ensure_gui_app()
    path = Path(path)
    title = title or _t(DEFAULT_TITLE)
    checksum = configuration_checksum(system, collection)
    if collection is None:
        note = " " + count(_CTX, "(the %n link(s) above, as they would be stored)",
                           len(system.links))
    else:
        n = sum(len(c.links) for c in collection.configurations)
        note = " " + _t("(what the prosthesis stores: {links} in {setups})").format(
            links=count(_CTX, "%n link(s)", n),
            setups=count(_CTX, "%n set-up(s)", len(collection.configurations)))
    buffer = QBuffer()
    buffer.open(QIODevice.OpenModeFlag.WriteOnly)
    writer = QPdfWriter(buffer)
    writer.setResolution(PDF_DPI)
    writer.setTitle(title)
    writer.setCreator("PDCP Studio")
    writer.setPageLayout(QPageLayout(QPageSize(QPageSize.PageSizeId.A4),
                                     QPageLayout.Orientation.Portrait,
                                     QMarginsF(15, 15, 15, 15), QPageLayout.Unit.Millimeter))
    px_per_layout = writer.resolution() / LAYOUT_DPI
    page_w = writer.width() / px_per_layout  # page in 96-dpi layout pixels
    page_h = writer.height() / px_per_layout

    graph_size = None
    doc = QTextDocument()
    if graph_image is not None and not graph_image.isNull():
        size = QSizeF(graph_image.size())
        size.scale(QSizeF(page_w - 20, page_h * GRAPH_MAX_HEIGHT_FRACTION),
                   Qt.AspectRatioMode.KeepAspectRatio)
        graph_size = size
        doc.addResource(QTextDocument.ResourceType.ImageResource, _GRAPH_URL, graph_image)
    doc.setDocumentMargin(0)
    doc.setTextWidth(page_w)
    for compact in (False, True):
        doc.setHtml(report_html(system, tree, title=title, date=date, graph_size=graph_size,
                                checksum=checksum, compact=compact, stored_note=note,
                                fitting=fitting))
        if doc.size().height() <= page_h:
            break
    height = doc.size().height()
    scale = min(1.0, page_h / height) if height > 0 else 1.0
    if scale < 1.0:  # too tall: lay out wider so it scales down evenly, then fit
        doc.setTextWidth(page_w / scale)
        scale = min(page_w / doc.textWidth(), page_h / doc.size().height())

    painter = QPainter()
    if not painter.begin(writer):
        raise OSError(_t("{path}: cannot write the PDF").format(path=path))
    try:
        painter.scale(px_per_layout * scale, px_per_layout * scale)
        doc.drawContents(painter)
    finally:
        painter.end()
    buffer.close()
    atomic_write_bytes(path, bytes(buffer.data().data()))  # a crash leaves no half PDF
    return path

