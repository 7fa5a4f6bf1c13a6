"""What the CLI and the desktop app import to talk to a live bus, whatever its transport.

:class:`BusSession` (bus/session/base.py) is the session's one face; ``open_session(url)``
opens any bus URL (bus/session/opening.py); the change road's PC half — preview, the user's
confirmation, the record — is :func:`run_transaction` (bus/session/change_road.py); what only
some sessions can do is a capability checked with ``isinstance`` (bus/session/capabilities.py).
"""

from pdcp_studio.bus.session.base import BusSession, ConfigVerifyError, ProgressFn
from pdcp_studio.bus.session.capabilities import SimulatedDevices, SimulatorControls
from pdcp_studio.bus.session.change_road import (
    ChangePreview,
    ConfirmFn,
    preview_change,
    run_transaction,
)
from pdcp_studio.bus.session.opening import open_session

__all__ = [
    "BusSession",
    "ChangePreview",
    "ConfigVerifyError",
    "ConfirmFn",
    "ProgressFn",
    "SimulatedDevices",
    "SimulatorControls",
    "open_session",
    "preview_change",
    "run_transaction",
]
