"""The main window's side of the profile-layer policy (issue 17): may the prosthesis
autoconfigure unconnected terminal channels on its own?

The policy is shown beside the connection in the status bar while live, read on the bridge's
worker after connecting, after every transaction and after an arbitrator reset. Bus ▸
Autoconfigure on this prosthesis changes it through the one transaction road
(:class:`~pdcp_studio.app.window.controllers.transaction_flow.TransactionFlow`: previewed,
confirmed, recorded in the fitting history); the check mark always shows what the prosthesis
has, never a wish. What a switch changes is decided once, on the bridge's worker, from the
prosthesis as read (``engine/policy_change.py``): turning it on makes the links the duty cycle
would make in the same transaction, turning it off says which links stay.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import TYPE_CHECKING, Any

from PySide6.QtGui import QAction
from PySide6.QtWidgets import QLabel

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.live.live_bus import LiveController
from pdcp_studio.app.words.plural import count

if TYPE_CHECKING:
    from pdcp_studio.app.live.session_bridge import SessionBridge

_CTX = "WindowPolicy"


def _t(text: str) -> str:
    return translate(_CTX, text)


class PolicyController:
    """Keeps ``label`` (status bar) and ``action`` (Bus menu, checkable) on what the
    connected prosthesis has; ``run_change(change, title)`` carries a change out as a
    transaction. ``last_switch`` is the last policy switch decided
    (:class:`~pdcp_studio.engine.policy_change.PolicySwitch`: its ``words`` say, in the
    user's language, which links stay when autoconfigure is turned off)."""

    def __init__(self, doc: Document, live: LiveController, label: QLabel, action: QAction,
                 run_change: Callable[[Any, str], bool]) -> None:
        self.doc = doc
        self.live = live
        self.label = label
        self.action = action
        self._run_change = run_change
        self.last_switch: Any = None
        label.setContentsMargins(6, 0, 6, 0)
        label.hide()
        doc.policyChanged.connect(lambda _p: self.show_policy())
        live.sessionStarted.connect(self._session_started)
        live.stateChanged.connect(lambda _s: self.show_policy())
        self.show_policy()

    def _session_started(self, bridge: SessionBridge) -> None:
        self.doc.set_policy(None)  # the previous prosthesis's policy is not this one's
        bridge.busEvent.connect(self._bus_event)
        bridge.simChanged.connect(lambda _what: self.read_policy())
        self.read_policy()

    def _bus_event(self, event: Any) -> None:
        # A transaction (ours or over the host link) may have changed it; an arbitrator
        # that restarted (start-up's plan, a bus that came back) may hold another one.
        kind = type(event).__name__
        if kind in ("TransactionDone", "PlanApplied", "TerminalsUnconnected") or (
                kind == "BusState" and event.state in ("arbitrating", "reconnected")):
            self.read_policy()

    def read_policy(self) -> None:
        """Ask the prosthesis for its policy (on the bridge's worker, never the GUI thread)."""
        bridge: SessionBridge | None = self.live.bridge
        shown: object = self.doc.session  # the bridge, when the document shows the bus
        if bridge is None or shown is not bridge:
            return
        session = bridge.session
        bridge.run(lambda _p, _c: session.read_policy(), "Read the policy",
                   partial(self._policy_read, bridge))

    def _policy_read(self, bridge: SessionBridge, policy: Any) -> None:
        if bridge is self.live.bridge and self.doc.session is bridge:
            self.doc.set_policy(policy)
            self.show_policy()  # the check mark follows the prosthesis, even if unchanged

    def show_policy(self) -> None:
        live = self.live.is_live and self.doc.session is self.live.bridge
        policy = self.doc.policy if live else None
        self.action.setEnabled(policy is not None)
        self.action.setChecked(policy is not None and bool(policy.autoconfigure))
        label = self.label
        if policy is None:
            label.setVisible(live)
            label.setText(_t("Autoconfigure: …"))
            label.setToolTip(_t("Reading the prosthesis's policy…"))
            label.setStyleSheet("color: #66707b;")
            return
        label.show()
        if policy.autoconfigure:
            label.setText(_t("Autoconfigure: on"))
            label.setToolTip(_t(
                "This prosthesis links unconnected hand, wrist or elbow channels on its own "
                "when it starts or a part is swapped (Bus menu to change)"))
            label.setStyleSheet("color: #1f2933;")
        else:
            label.setText(_t("Autoconfigure: off"))
            label.setToolTip(_t(
                "This prosthesis repairs its known links and finds replacements for swapped "
                "parts, but links nothing new on its own (Bus menu to change)"))
            label.setStyleSheet("color: #8a5a00; font-weight: bold;")

    def set_autoconfigure(self, on: bool) -> bool:
        """Bus ▸ Autoconfigure on this prosthesis: change the policy as one transaction.

        The check mark goes back to what the prosthesis has until the transaction says
        otherwise (a declined or failed change leaves it as it was). The change is decided
        on the worker from the prosthesis as it is now, then previewed and confirmed."""
        self.show_policy()
        bridge: SessionBridge | None = self.live.bridge
        if bridge is None or self.doc.session is not bridge:
            return False
        session = bridge.session

        def decide(_progress: Any, _cancel: Any) -> Any:
            from pdcp_studio.app.words.plan_words import channel_words
            from pdcp_studio.engine.policy_change import policy_switch

            system = session.system()
            return policy_switch(system, session.read_policy().autoconfigure, bool(on),
                                 name=lambda ref: channel_words(system, ref),
                                 say=lambda text, n: count(_CTX, text, n))

        worker = bridge.run(decide, _t("Read the policy"), partial(self._decided, bridge))
        return worker is not None

    def _decided(self, bridge: SessionBridge, switch: Any) -> None:
        from pdcp_studio.bus.transaction import Change, Policy

        if bridge is not self.live.bridge or self.doc.session is not bridge:
            return
        change = Change.from_plan(switch.plan, switch.action)
        change.policy = Policy(autoconfigure=switch.after)
        title = _t("Turn autoconfigure on") if switch.after else _t("Turn autoconfigure off")
        self.last_switch = switch
        self._run_change(change, title)


# The headlines engine/policy_change.py says, for the translation files.
KEPT = QT_TRANSLATE_NOOP(_CTX, "Every link stays as it is (%n link(s)); from now on "
                               "unconnected hand, wrist or elbow channels stay unconnected "
                               "until you link them:")
NONE_KEPT = QT_TRANSLATE_NOOP(_CTX, "No link is removed (there are none); from now on "
                                    "unconnected hand, wrist or elbow channels stay "
                                    "unconnected until you link them.")
