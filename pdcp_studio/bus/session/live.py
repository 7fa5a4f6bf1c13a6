"""The live sessions under the names the app, the CLI and the tests import them by.

The parts live in modules of their own: the base class (base.py), the in-process arbitrator's
session (in_process.py), the simulator's (sim.py), opening a URL (opening.py, open_sim.py,
open_can.py).
"""

from pdcp_studio.bus.session.base import ConfigVerifyError
from pdcp_studio.bus.session.in_process import Session
from pdcp_studio.bus.session.open_can import OtherArbitratorError, open_can_session
from pdcp_studio.bus.session.open_sim import open_sim_session
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.session.sim import SimSession
from pdcp_studio.bus.session.urls import BusUrlError

__all__ = ["BusUrlError", "ConfigVerifyError", "OtherArbitratorError", "Session", "SimSession",
           "open_can_session", "open_session", "open_sim_session"]
