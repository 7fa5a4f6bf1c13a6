"""The Bus menu's commands: connect, scan, read the stored configuration, cancel, compare
and write configurations, and what the window does when a session starts or another
arbitrator appears.

The connection itself is :mod:`pdcp_studio.app.live.live_bus`; the docks a bus brings are
:mod:`.bus_docks`.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any

from PySide6.QtWidgets import QWidget

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.live.live_bus import LiveController
from pdcp_studio.app.window.status import StatusLine
from pdcp_studio.app.words.plural import count

if TYPE_CHECKING:
    from pdcp_studio.app.live.session_bridge import SessionBridge

_CTX = "WindowBus"


def _t(text: str) -> str:
    return translate(_CTX, text)


class BusCommands:
    """What the Bus menu does with the live connection; dialogs open over ``parent``.

    ``maybe_save()`` asks before the document gives way, ``connect_bus(url)`` connects;
    ``offer_arbitrator(url, message, later)`` offers the safe ways on when another
    arbitrator holds the bus; ``history_changed()`` after a configuration was written."""

    def __init__(self, doc: Document, live: LiveController, status: StatusLine,
                 parent: QWidget, *, maybe_save: Callable[[], bool],
                 connect_bus: Callable[[str], None],
                 offer_arbitrator: Callable[[str, str, bool], None],
                 history_changed: Callable[[], object]) -> None:
        self.doc = doc
        self.live = live
        self.status = status
        self.parent = parent
        self._maybe_save = maybe_save
        self._connect_bus = connect_bus
        self._offer_arbitrator = offer_arbitrator
        self._history_changed = history_changed
        self.compare_dialog: Any = None

    def ask_connect(self) -> None:
        from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog

        url = ConnectDialog.get_url(self.parent)
        if url and self._maybe_save():
            self._connect_bus(url)

    def offer_other_arbitrator(self, url: str, message: str) -> bool:
        """A Connect that found another arbitrator on the bus: offer a listen-only monitor
        or the host link instead (True when that was the failure)."""
        from pdcp_studio.app.dialogs import arbitrator_found

        connecting = self.live.connecting
        if not arbitrator_found.is_other_arbitrator(getattr(connecting, "exception", None)):
            return False
        self._offer_arbitrator(url, message, False)
        return True

    def scan_bus(self) -> Any:
        """Scan the bus on its worker; the status bar says when it started and finished."""
        worker = self.live.scan()
        if worker is not None:
            self.status.say(_t("Scanning the bus…"), 0)
        return worker

    def scan_finished(self, system: Any) -> None:
        devices = len(getattr(system, "devices", {}))
        links = len(getattr(system, "links", []))
        self.status.say(_t("Scan finished: {devices}, {links}").format(
            devices=count(_CTX, "%n device(s)", devices),
            links=count(_CTX, "%n link(s)", links)))

    def session_started(self, bridge: SessionBridge) -> None:
        """Plans get the new session's stored configuration, read again whenever it may
        have changed."""
        bridge.simChanged.connect(self._sim_changed)
        bridge.configurationWritten.connect(lambda _c: self.reread_configuration())
        # Any transaction on this prosthesis (ours, or the arbitrator's own over the host
        # link) may have changed the stored configuration: previews must use the new one.
        bridge.busEvent.connect(self._bus_event)
        self.reread_configuration()

    def _sim_changed(self, _what: object) -> None:
        self.live.refresh()
        self.reread_configuration()

    def _bus_event(self, event: Any) -> None:
        kind = type(event).__name__
        if kind == "TransactionDone":
            self.reread_configuration()
        elif kind == "BusState" and event.state == "yielded":
            self._other_arbitrator_appeared(event.message)

    def _other_arbitrator_appeared(self, message: str) -> None:
        """Another arbitrator started on our bus: our session has stopped writing (§5).
        Say so plainly and offer the safe ways on, as when it is found on connecting."""
        url = self.live.url
        self.live.disconnect_bus()  # it writes nothing more; edits could not be written
        self._offer_arbitrator(url, message, True)

    def reread_configuration(self) -> None:
        """Read the arbitrator's stored configuration again (after connecting, every write
        and every bus event that may change it): previews always use the current one."""
        bridge = self.live.bridge
        if bridge is None:
            return
        session = bridge.session
        bridge.run(lambda _p, _c: session.read_configuration(), "Read configuration",
                   partial(self._stored_configuration_seen, bridge))

    def _stored_configuration_seen(self, bridge: SessionBridge, collection: Any) -> None:
        if bridge is self.live.bridge and self.doc.session is bridge:
            self.doc.config = collection

    def read_configuration(self) -> None:
        """Ask the arbitrator for its stored configuration (on the bridge's worker)."""
        bridge = self.live.bridge
        if bridge is None:
            self.status.say(_t("Read configuration: connect to a bus first"))
            return
        bridge.run(lambda _p, _c: bridge.session.read_configuration(),
                   "Read configuration", self._configuration_read)

    def _configuration_read(self, collection: Any) -> None:
        self.doc.config = collection
        n = len(getattr(collection, "configurations", []))
        links = sum(len(c.links) for c in getattr(collection, "configurations", []))
        self.status.say(_t("Read the arbitrator's stored configuration: {configurations}, "
                           "{links} — Find replacements and Start-up now use it").format(
            configurations=count(_CTX, "%n configuration(s)", n),
            links=count(_CTX, "%n link(s)", links)))

    def cancel_bus_work(self) -> None:
        if self.live.connecting is not None and self.live.connecting.is_running:
            self.live.connecting.cancel()
        if self.live.bridge is not None:
            self.live.bridge.cancel_all()
        self.status.say(_t("Cancelling…"))

    def show_compare(self) -> None:
        from pdcp_studio.app.dialogs import compare_dialog as mod

        dialog = mod.CompareDialog(self.doc.system, bridge=self.live.bridge,
                                   profile_name=self.doc.profile_name, parent=self.parent)
        if self.doc.config is not None:
            dialog.set_file_sources(mod.sources_of_collection(self.doc.title, self.doc.config),
                                    self.doc.config)
        dialog.show()

    def compare_with_prosthesis(self, path: str | Path) -> Any:
        """Compare a file's links with the prosthesis (on screen and its arbitrator's stored
        configuration), staying connected; returns the dialog."""
        from pdcp_studio.app.dialogs import compare_dialog as mod

        dialog = mod.CompareDialog(self.doc.system, bridge=self.live.bridge,
                                   profile_name=self.doc.profile_name, parent=self.parent)
        dialog.load_file(path)
        if self.live.bridge is not None:
            dialog.read_arbitrator()
        dialog.show()
        self.compare_dialog = dialog
        return dialog

    def ask_write_configuration(self) -> None:
        from pdcp_studio.app.dialogs import write_config_dialog as mod

        if self.live.bridge is None:
            self.status.error(_t("Write configuration"), _t("connect to a bus first"))
            return
        dialog = mod.WriteConfigDialog.for_system(self.live.bridge, self.doc.system,
                                                  self.parent)
        # Whatever came of it, plans must use what the arbitrator stores now.
        dialog.verified.connect(lambda _ok, _msg: self.reread_configuration())
        dialog.verified.connect(lambda _ok, _msg: self._history_changed())
        dialog.show()
