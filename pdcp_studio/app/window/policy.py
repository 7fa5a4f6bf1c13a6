"""The main window's side of the profile-layer policy (issue 17): may the prosthesis
autoconfigure unconnected terminal channels on its own?

The policy is shown beside the connection in the status bar while live, read on the
bridge's worker after connecting, after every transaction and after an arbitrator reset.
Bus ▸ Autoconfigure on this prosthesis changes it through the one transaction road
(:class:`~pdcp_studio.app.window.transaction_flow.TransactionFlow`: previewed, confirmed, recorded
in
the fitting history); the check mark always shows what the prosthesis has, never a wish.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from PySide6.QtGui import QAction
from PySide6.QtWidgets import QLabel


class PolicyMixin:
    """Builds ``policy_label`` (status bar) and ``act_autoconfigure`` (Bus menu)."""

    if TYPE_CHECKING:  # a mixin of a QObject: Qt gives it tr()
        tr: Callable[[str], str]

    def _build_policy(self) -> None:
        self.policy_label = QLabel()
        self.policy_label.setContentsMargins(6, 0, 6, 0)
        self.policy_label.hide()
        self.statusBar().addPermanentWidget(self.policy_label)
        self.act_autoconfigure = QAction(self.tr("&Autoconfigure on this prosthesis"), self)
        self.act_autoconfigure.setCheckable(True)
        self.act_autoconfigure.setEnabled(False)
        self.act_autoconfigure.setStatusTip(self.tr(
            "Whether the prosthesis may link unconnected hand, wrist or elbow channels on its "
            "own; the change is previewed, confirmed and recorded in the fitting history"))
        self.act_autoconfigure.triggered.connect(self.set_autoconfigure)
        self.bus_menu.addSeparator()
        self.bus_menu.addAction(self.act_autoconfigure)
        self.doc.policyChanged.connect(lambda _p: self._show_policy())
        self.live.sessionStarted.connect(self._policy_session_started)
        self.live.stateChanged.connect(lambda _s: self._show_policy())
        self._show_policy()

    def _policy_session_started(self, bridge: Any) -> None:
        self.doc.set_policy(None)  # the previous prosthesis's policy is not this one's
        bridge.busEvent.connect(self._policy_bus_event)
        bridge.simChanged.connect(lambda _what: self.read_policy())
        self.read_policy()

    def _policy_bus_event(self, event: Any) -> None:
        # A transaction (ours or over the host link) may have changed it; an arbitrator
        # that restarted (start-up's plan, a bus that came back) may hold another one.
        kind = type(event).__name__
        if kind in ("TransactionDone", "PlanApplied", "TerminalsUnconnected") or (
                kind == "BusState" and event.state in ("arbitrating", "reconnected")):
            self.read_policy()

    def read_policy(self) -> None:
        """Ask the prosthesis for its policy (on the bridge's worker, never the GUI thread)."""
        bridge = self.live.bridge
        if bridge is None or self.doc.session is not bridge:
            return
        session = bridge.session
        bridge.run(lambda _p, _c: session.read_policy(), "Read the policy",
                   lambda policy, b=bridge: self._policy_read(b, policy))

    def _policy_read(self, bridge: Any, policy: Any) -> None:
        if bridge is self.live.bridge and self.doc.session is bridge:
            self.doc.set_policy(policy)
            self._show_policy()  # the check mark follows the prosthesis, even if unchanged

    def _show_policy(self) -> None:
        live = self.live.is_live and self.doc.session is self.live.bridge
        policy = self.doc.policy if live else None
        self.act_autoconfigure.setEnabled(policy is not None)
        self.act_autoconfigure.setChecked(policy is not None and bool(policy.autoconfigure))
        if policy is None:
            self.policy_label.setVisible(live)
            self.policy_label.setText(self.tr("Autoconfigure: …"))
            self.policy_label.setToolTip(self.tr("Reading the prosthesis's policy…"))
            self.policy_label.setStyleSheet("color: #66707b;")
            return
        self.policy_label.show()
        if policy.autoconfigure:
            self.policy_label.setText(self.tr("Autoconfigure: on"))
            self.policy_label.setToolTip(self.tr(
                "This prosthesis links unconnected hand, wrist or elbow channels on its own "
                "when it starts or a part is swapped (Bus menu to change)"))
            self.policy_label.setStyleSheet("color: #1f2933;")
        else:
            self.policy_label.setText(self.tr("Autoconfigure: off"))
            self.policy_label.setToolTip(self.tr(
                "This prosthesis repairs its known links and finds replacements for swapped "
                "parts, but links nothing new on its own (Bus menu to change)"))
            self.policy_label.setStyleSheet("color: #8a5a00; font-weight: bold;")

    def set_autoconfigure(self, on: bool) -> bool:
        """Bus ▸ Autoconfigure on this prosthesis: change the policy as one transaction.

        The check mark goes back to what the prosthesis has until the transaction says
        otherwise (a declined or failed change leaves it as it was)."""
        from pdcp_studio.bus.transaction import Change, Policy

        self._show_policy()
        word = "on" if on else "off"
        change = Change(f"policy autoconfigure {word}", policy=Policy(autoconfigure=bool(on)))
        title = (self.tr("Turn autoconfigure on") if on else
                 self.tr("Turn autoconfigure off"))
        return bool(self.flow.run(change, title))
