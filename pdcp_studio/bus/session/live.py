"""The live sessions under the names the app, the CLI and the tests import them by.

The parts live in modules of their own: the base class (base.py), the in-process arbitrator's
session and ``can:`` buses (in_process.py), the simulator's (sim.py), opening any URL through
the table of schemes (opening.py).
"""

from pdcp_studio.bus.session.base import ConfigVerifyError
from pdcp_studio.bus.session.in_process import OtherArbitratorError, Session, open_can_session
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.session.sim import SimSession, open_sim_session
from pdcp_studio.bus.session.urls import BusUrlError

__all__ = ["BusUrlError", "ConfigVerifyError", "OtherArbitratorError", "Session", "SimSession",
           "open_can_session", "open_session", "open_sim_session"]
