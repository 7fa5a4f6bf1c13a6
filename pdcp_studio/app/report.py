"""The fitting report as PDF: what was fitted, how it is linked, what changed, what the next
power-on does, its checksum — on A4 portrait pages, each with "Page N of M".

Public API
    ``write_report(path, system, tree, graph_image=None, title=..., *, date=None,
    collection=None, fitting=None) -> Path`` — GUI thread (text layout); about 50 ms for a
    small rig. ``graph_image`` is a ``QImage`` of the bus graph (the main window renders its
    scene); ``collection`` a stored configuration whose checksum to print instead of the
    on-screen links'. ``configuration_checksum(system, collection=None) -> int`` and
    ``report_html(...)`` are the parts, for previews and tests.

The prosthetist files it with the patient's records, so it names every part as the app does
(``words/part_names.py``), every link with its profile names, and the CRC-16 checksum the
stored configuration carries (the value ``pdcp-studio config decode`` verifies), so a later
reading of the arbitrator can be matched against the paper. With a :class:`FittingInfo`
(``fitting=``) the report fills in the patient reference, the prosthetist, the time and the
policy, lists the changes made in this session with their effect and what the next power-on
does (from the fitting history: :mod:`.report_entries`) and the findings of the checks.
Without one, those fields are blank lines to fill in. Codes and hex appear only in the
closing Technical detail section.

The page is an HTML ``QTextDocument`` laid out at 96 dpi with the page's size, so it breaks
its own pages (tables read down, one part per row, their header repeated on each page, text
wrapped inside cells); each page is drawn on a ``QPdfWriter`` through a scaled painter, with
a footer line.
"""

from __future__ import annotations

import datetime as _dt
import html
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QBuffer, QIODevice, QMarginsF, QRectF, QSizeF, Qt, QUrl
from PySide6.QtGui import (
    QGuiApplication,
    QImage,
    QPageLayout,
    QPageSize,
    QPainter,
    QPdfWriter,
    QTextDocument,
)

from pdcp_studio.app import report_entries as entries
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
#: Kept here for callers of the report's words.
action_words = entries.action_words
#: The source text; shown translated (``_t``) like every word of the report.
DEFAULT_TITLE = QT_TRANSLATE_NOOP("FittingReport", "PDCP fitting report")
LAYOUT_DPI = 96.0
PDF_DPI = 300
GRAPH_MAX_HEIGHT_FRACTION = 0.45  # of the page
FOOTER_HEIGHT = 24.0  # layout pixels at the foot of each page for its number
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

    @property
    def anchor(self) -> str:
        """The fitting history's anchor the last change here wrote to the prosthesis (its
        entry and hash, reference §5 Decision); empty without a recorded change."""
        last = self.changes[-1] if self.changes else None
        if not isinstance(last, dict) or not last.get("hash"):
            return ""
        return _t("entry {id}, hash {hash}").format(id=last.get("id"), hash=last.get("hash"))


def _t(text: str) -> str:
    """``text`` in the app's language (the German build prints a German report)."""
    return translate(_CTX, text)


_SEVERITIES = {
    "error": QT_TRANSLATE_NOOP("FittingReport", "Error"),
    "warning": QT_TRANSLATE_NOOP("FittingReport", "Warning"),
    "info": QT_TRANSLATE_NOOP("FittingReport", "Info"),
}


def _version(value: int) -> str:
    return f"{value >> 8}.{value & 0xFF}" if value else "—"


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


def _end(system: System, tree: ProfileTree, ref: ChannelRef) -> str:
    """One end of a link: the part and the channel by their one names (``model/names.py``:
    the descriptor, "channel N" only where there is none), then what the channel carries."""
    from pdcp_studio.app.words import part_names
    from pdcp_studio.model import names as model_names

    ch = system.channel(ref)
    name = _device_name(system, ref.device)
    channel = part_names.names(system).channel_only(ref)
    profile = _profile(tree, ch.profile) if ch else "?"
    end = part_names.tr(model_names.CHANNEL).format(part=f"<b>{_e(name)}</b>",
                                                    channel=_e(channel))
    return f"{end}<br>{profile}"


def _ref_codes(system: System, ref: ChannelRef) -> str:
    ch = system.channel(ref)
    codes = (_t("type {type}, profile {profile}").format(
        type=prof.fmt(ch.type), profile=prof.fmt(ch.profile)) if ch
        else _t("not on the bus"))
    return _t("VID {vid} PID {pid} serial {serial} channel {index} ({codes})").format(
        vid=f"0x{ref.vid:04X}", pid=f"0x{ref.pid:04X}", serial=ref.serial, index=ref.index,
        codes=codes)


def _detail_links(system: System, links: list[Link]) -> str:
    """Links by identity and channel codes, one line each (for matching a reading)."""
    return "".join(f"<li>{_e(_ref_codes(system, lk.output))} → "
                   f"{_e(_ref_codes(system, lk.input))}</li>" for lk in links)


def _device_rows(system: System) -> str:
    """One row per part (never several parts side by side: the table must read down)."""
    from pdcp_studio.model.catalog import default_catalog

    catalog = default_catalog()
    rows = []
    for d in system.devices.values():
        state = f" <i>{_e(_t('(missing)'))}</i>" if not d.present else ""
        entry = catalog.lookup(d.vid, d.pid)
        product = (_t("{product} ({vendor})").format(product=entry.product, vendor=entry.vendor)
                   if entry else _t("not in the catalogue"))
        rows.append(f"<tr><td>{_e(_device_name(system, d.key))}{state}</td>"
                    f"<td>{_e(product)}</td><td>{d.vid} / {d.pid} / {d.serial}</td>"
                    f"<td>{_version(d.fw_version)}</td><td>{_version(d.hw_version)}</td></tr>")
    return "".join(rows) or f"<tr><td colspan=5><i>{_e(_t('no devices'))}</i></td></tr>"


def _table(heads: list[tuple[str, int]], rows: str) -> str:
    """A full-width grid whose header row repeats on every page it runs onto."""
    cells = "".join(f"<th width={w}%>{_e(h)}</th>" for h, w in heads)
    return (f"<table class=grid width=100% cellspacing=0 cellpadding=3>"
            f"<thead><tr>{cells}</tr></thead>{rows}</table>")


def _lines_html(lines: list[str]) -> str:
    return "".join(f"<br>{_e(line)}" for line in lines)


def _change_rows(system: System, changes: list[dict[str, Any]]) -> str:
    rows = []
    for i, e in enumerate(changes):
        what = _e(entries.change_words(e, changes[:i]))
        what += _lines_html(entries.replaced_lines(system, e, changes[:i])
                            + entries.effect_lines(e))
        # The prediction's own sentences ("At the next power-on …"), a line each.
        what += "<i>" + _lines_html(entries.power_on_lines(e)) + "</i>"
        rows.append(f"<tr><td>{_e(e.get('id', ''))}</td>"
                    f"<td>{_e(str(e.get('time', '')).replace('T', ' ').rstrip('Z'))}</td>"
                    f"<td>{_e(entries.action_words(str(e.get('action', ''))))}</td>"
                    f"<td>{what}</td><td>{_e(entries.outcome_words(e))}</td>"
                    f"<td>{_e(e.get('operator') or '')}</td></tr>")
    return "".join(rows) or (f"<tr><td colspan=6><i>{_e(_t('no change was made in this session'))}"
                             "</i></td></tr>")


def _power_on_html(changes: list[dict[str, Any]]) -> str:
    """The next-power-on statement: the last change that reached the prosthesis decides."""
    written = [e for e in changes if entries.link_changes(e) is not None]
    if not written:
        text = _t("No change was written in this session: the prosthesis starts up as it "
                  "did before.")
        return f"<p>{_e(text)}</p>"
    last = written[-1]
    lines = entries.power_on_lines(last)
    head = _t("After entry {0}, the last change written:").format(last.get("id", ""))
    body = "<br>".join(_e(line) for line in lines)
    return f"<p>{_e(head)}<br><b>{body}</b></p>"


def _policy_html(info: FittingInfo | None) -> str:
    """The prosthesis's profile-layer policy, in a sentence."""
    if info is None or info.policy is None:
        return _e(_t("Autoconfigure: not known (the prosthesis was not connected)"))
    if info.policy.autoconfigure:
        return _t("Autoconfigure: {on} (the prosthesis may link parts that nothing drives on "
                  "its own)").format(on=f"<b>{_e(_t('on'))}</b>")
    return _t("Autoconfigure: {off} (the prosthesis repairs known links and finds "
              "replacements for missing parts, but links nothing new on its own)").format(
                  off=f"<b>{_e(_t('off'))}</b>")


def _technical_html(system: System, checksum: int | None,
                    changes: list[dict[str, Any]], anchor: str = "") -> str:
    """The closing section: every code the body leaves out, complete."""
    from pdcp_studio.bus.transaction import link_from_json

    crc = "—" if checksum is None else f"0x{checksum:04X}"
    crc_words = _t("Check number: CRC-16/CCITT-FALSE of the stored configuration record")
    parts = [f"<p>{_e(crc_words)}: <span class=hex>{crc}</span></p>"]
    if anchor:
        parts.append(f"<p>{_e(_t('Fitting history anchor in the prosthesis'))}: "
                     f"<span class=hex>{_e(anchor)}</span></p>")
    identity = _t("VID {vid} PID {pid} serial {serial}")
    devices = "".join(
        "<li>" + _e(_device_name(system, d.key)) + ": " + _e(identity.format(
            vid=f"0x{d.vid:04X}", pid=f"0x{d.pid:04X}", serial=d.serial)) + "</li>"
        for d in system.devices.values())
    if devices:
        parts.append(f"<p>{_e(_t('Parts by identity:'))}</p><ul>{devices}</ul>")
    links_words = _t("Links by identity (VID, PID, serial number, channel index) with the "
                     "channels' type and profile codes:")
    parts.append(f"<p>{_e(links_words)}</p>")
    parts.append(f"<ul>{_detail_links(system, list(system.links))}</ul>" if system.links
                 else f"<p><i>{_e(_t('no links'))}</i></p>")
    for e in changes:
        lines = [_e(x) for x in entries.technical_lines(e)]
        crcs = (e.get("config_crc_before"), e.get("config_crc_after"))
        if any(crcs):
            lines.append(_e(_t("stored configuration check number {before} → {after}").format(
                before=crcs[0] or "—", after=crcs[1] or "—")))
        pon = e.get("next_power_on")
        if isinstance(pon, dict):
            for key, word in (("links_added", _t("next power-on adds")),
                              ("links_removed", _t("next power-on removes"))):
                for doc in pon.get(key) or []:
                    try:
                        lk = link_from_json(doc)
                    except (KeyError, TypeError, ValueError):
                        continue
                    lines.append(f"{_e(word)}: {_e(_ref_codes(system, lk.output))} → "
                                 f"{_e(_ref_codes(system, lk.input))}")
        if lines:
            parts.append(f"<p>{_e(_t('Entry {0}:').format(e.get('id', '')))}</p><ul>"
                         + "".join(f"<li>{x}</li>" for x in lines) + "</ul>")
    return "".join(parts)


def report_html(system: System, tree: ProfileTree, *, title: str | None = None,
                date: _dt.date | None = None, graph_size: QSizeF | None = None,
                checksum: int | None = None, stored_note: str = "",
                fitting: FittingInfo | None = None) -> str:
    """The report's HTML (for tests and previews); ``graph_size`` adds the graph image."""
    from pdcp_studio.app.words.part_names import one_naming

    with one_naming(system):  # every part and link is named: one lookup for all
        return _report_html(system, tree, title=title, date=date, graph_size=graph_size,
                            checksum=checksum, stored_note=stored_note, fitting=fitting)


def _report_html(system: System, tree: ProfileTree, *, title: str | None,
                 date: _dt.date | None, graph_size: QSizeF | None, checksum: int | None,
                 stored_note: str, fitting: FittingInfo | None) -> str:
    date = date or _dt.date.today()
    title = title or _t(DEFAULT_TITLE)
    blank = "_" * 30
    info = fitting
    when = date.isoformat()
    patient = prosthetist = prosthesis = blank
    changes: list[dict[str, Any]] = []
    autoconfigure = True
    if info is not None:
        if info.time is not None:
            when = info.time.strftime("%Y-%m-%d %H:%M UTC")
        patient = _e(info.patient) or blank
        prosthetist = _e(info.prosthetist) or blank
        prosthesis = _e(info.bus) or blank
        changes = info.changes
        if info.policy is not None:
            autoconfigure = bool(info.policy.autoconfigure)
    devices = _table([(_t("Name"), 26), (_t("Product"), 30),
                      (_t("Maker / product / serial no."), 18), (_t("Firmware"), 13),
                      (_t("Hardware"), 13)], _device_rows(system))
    links = _table([("#", 5), (_t("Output"), 46), ("", 3), (_t("Input"), 46)], "".join(
        f"<tr><td>{i}</td><td>{_end(system, tree, lk.output)}</td><td>→</td>"
        f"<td>{_end(system, tree, lk.input)}{_missing(system, lk)}</td></tr>"
        for i, lk in enumerate(system.links, 1)
    ) or f"<tr><td colspan=4><i>{_e(_t('no links'))}</i></td></tr>")
    session_html = ""
    if info is not None:
        session_html = (
            f"<h2>{_e(_t('Changes made in this session ({n})').format(n=len(changes)))}</h2>"
            + _table([("#", 5), (_t("Time (UTC)"), 15), (_t("Action"), 20), (_t("Change"), 36),
                      (_t("Outcome"), 12), (_t("By"), 12)], _change_rows(system, changes))
            + f"<h2>{_e(_t('Next power-on'))}</h2>{_power_on_html(changes)}")
    findings = (f"<h2>{_e(_t('Checks'))}</h2>"
                + _table([(_t("Finding"), 14), (_t("What"), 86)],
                         _finding_rows(system, autoconfigure)))
    crc = "—" if checksum is None else f"0x{checksum:04X}"
    graph = ""
    if graph_size is not None:
        graph = (f"<p align=center><img src='{_GRAPH_URL.toString()}' "
                 f"width={graph_size.width():.0f} height={graph_size.height():.0f}></p>")
    return f"""
<style>
 body {{ font-family: 'DejaVu Sans', sans-serif; font-size: 9pt; }}
 h1 {{ font-size: 16pt; margin-bottom: 2px; }}
 h2 {{ font-size: 11pt; margin-top: 12px; margin-bottom: 4px; }}
 table.grid {{ border-collapse: collapse; }}
 table.grid td, table.grid th {{ border: 1px solid #999; padding: 2px 4px; }}
 th {{ background: #e8e8e8; text-align: left; }}
 .hex {{ color: #333; font-family: 'DejaVu Sans Mono', monospace; }}
 .detail {{ font-size: 7.5pt; color: #333; }}
</style>
<h1>{_e(title)}</h1>
<table cellpadding=3 width=100%>
 <tr><td width=22%>{_e(_t("Date:"))}</td><td width=28%>{_e(when)}</td>
 <td width=20%>{_e(_t("Prosthesis:"))}</td><td width=30%>{prosthesis}</td></tr>
 <tr><td>{_e(_t("Patient:"))}</td><td>{patient}</td>
 <td>{_e(_t("Prosthetist:"))}</td><td>{prosthetist}</td></tr>
 <tr><td>{_e(_t("Signature:"))}</td><td colspan=3>{blank}</td></tr>
</table>
<p>{_policy_html(info)}</p>
<h2>{_e(_t("Devices ({n})").format(n=len(system.devices)))}</h2>
{devices}
<h2>{_e(_t("Links ({n})").format(n=len(system.links)))}</h2>
{links}
<h2>{_e(_t("Stored set-up"))}</h2>
<p>{_t("Check number: {crc}{note}. A later reading of the prosthesis that shows the same "
       "number has the same links.").format(crc=f"<b class=hex>{crc}</b>",
                                            note=_e(stored_note))}</p>
{session_html}
{findings}
{graph}
<h2>{_e(_t("Technical detail"))}</h2>
<div class=detail>{_technical_html(system, checksum, changes,
                                   info.anchor if info is not None else "")}</div>
<p style='color:#777; font-size:7pt'>{_e(_t("Generated by PDCP Studio."))}</p>
"""


def _missing(system: System, lk: Link) -> str:
    gone = [system.device(r.device) for r in (lk.output, lk.input)]
    if any(d is None or not d.present for d in gone):
        return f" <i style='color:#b00000'>{_e(_t('(to a missing device)'))}</i>"
    return ""


def _ensure_gui_app() -> None:
    """Text layout needs a QGuiApplication; a command-line caller may not have made one."""
    global _app
    if QGuiApplication.instance() is None:
        _app = QGuiApplication([])


def footer_text(page: int, pages: int, when: str, patient: str) -> str:
    """The line at the foot of every page: whose report, when, and ``Page 1 of 3``."""
    who = _t("Patient: {0}").format(patient) if patient else ""
    left = " · ".join(x for x in (_t(DEFAULT_TITLE), who, when) if x)
    return f"{left} — " + _t("Page {page} of {pages}").format(page=page, pages=pages)


def _note(system: System, collection: ConfigCollection | None) -> str:
    if collection is None:
        return " " + count(_CTX, "(the %n link(s) above, as they would be stored)",
                           len(system.links))
    n = sum(len(c.links) for c in collection.configurations)
    return " " + _t("(what the prosthesis stores: {links} in {setups})").format(
        links=count(_CTX, "%n link(s)", n),
        setups=count(_CTX, "%n set-up(s)", len(collection.configurations)))


def page_layout() -> QPageLayout:
    """A4 portrait; the bottom margin leaves room for the page number."""
    return QPageLayout(QPageSize(QPageSize.PageSizeId.A4), QPageLayout.Orientation.Portrait,
                       QMarginsF(15, 15, 15, 12), QPageLayout.Unit.Millimeter)


def body_size() -> QSizeF:
    """One page's text area in 96-dpi layout pixels (the page less its margins and footer)."""
    rect = page_layout().paintRect(QPageLayout.Unit.Inch)
    return QSizeF(rect.width() * LAYOUT_DPI, rect.height() * LAYOUT_DPI - FOOTER_HEIGHT)


def report_document(system: System, tree: ProfileTree, graph_image: QImage | None = None,
                    title: str | None = None, *, date: _dt.date | None = None,
                    collection: ConfigCollection | None = None,
                    fitting: FittingInfo | None = None) -> QTextDocument:
    """The report laid out in pages of :func:`body_size` (what :func:`write_report` draws;
    tests look at its layout)."""
    _ensure_gui_app()
    size = body_size()
    doc = QTextDocument()
    graph_size = None
    if graph_image is not None and not graph_image.isNull():
        graph_size = QSizeF(graph_image.size())
        graph_size.scale(QSizeF(size.width() - 20, size.height() * GRAPH_MAX_HEIGHT_FRACTION),
                         Qt.AspectRatioMode.KeepAspectRatio)
        doc.addResource(QTextDocument.ResourceType.ImageResource, _GRAPH_URL, graph_image)
    doc.setDocumentMargin(0)
    doc.setPageSize(size)  # the document breaks its own pages
    doc.setHtml(report_html(system, tree, title=title or _t(DEFAULT_TITLE), date=date,
                            graph_size=graph_size,
                            checksum=configuration_checksum(system, collection),
                            stored_note=_note(system, collection), fitting=fitting))
    return doc


def write_report(path: str | Path, system: System, tree: ProfileTree,
                 graph_image: QImage | None = None, title: str | None = None, *,
                 date: _dt.date | None = None,
                 collection: ConfigCollection | None = None,
                 fitting: FittingInfo | None = None) -> Path:
    """Write the A4 portrait PDF report to ``path`` (as many pages as it takes, each with
    its page number); returns the path.

    The checksum is that of ``collection`` (e.g. the arbitrator's stored configuration) or,
    by default, of the system's links stored as configuration 1. OSError if it cannot write.
    """
    _ensure_gui_app()
    path = Path(path)
    title = title or _t(DEFAULT_TITLE)
    doc = report_document(system, tree, graph_image, title, date=date, collection=collection,
                          fitting=fitting)
    buffer = QBuffer()
    buffer.open(QIODevice.OpenModeFlag.WriteOnly)
    writer = QPdfWriter(buffer)
    writer.setResolution(PDF_DPI)
    writer.setTitle(title)
    writer.setCreator("PDCP Studio")
    writer.setPageLayout(page_layout())
    px_per_layout = writer.resolution() / LAYOUT_DPI
    size = body_size()
    page_w, body_h = size.width(), size.height()
    page_h = body_h + FOOTER_HEIGHT
    pages = max(1, doc.pageCount())
    when = (fitting.time.strftime("%Y-%m-%d %H:%M UTC") if fitting and fitting.time
            else (date or _dt.date.today()).isoformat())
    foot = QTextDocument()
    foot.setDocumentMargin(0)
    foot.setTextWidth(page_w)

    painter = QPainter()
    if not painter.begin(writer):
        raise OSError(_t("{path}: cannot write the PDF").format(path=path))
    try:
        painter.scale(px_per_layout, px_per_layout)
        for page in range(pages):
            if page:
                writer.newPage()
            painter.save()
            painter.translate(0, -page * body_h)
            doc.drawContents(painter, QRectF(0, page * body_h, page_w, body_h))
            painter.restore()
            line = footer_text(page + 1, pages, when, fitting.patient if fitting else "")
            foot.setHtml("<p style='font-family: \"DejaVu Sans\"; font-size: 7pt; "
                         f"color: #555' align=right>{_e(line)}</p>")
            painter.save()
            painter.translate(0, page_h - foot.size().height())
            foot.drawContents(painter)
            painter.restore()
    finally:
        painter.end()
    buffer.close()
    atomic_write_bytes(path, bytes(buffer.data().data()))  # a crash leaves no half PDF
    return path
