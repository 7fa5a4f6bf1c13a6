"""Shared fixtures of the CLI tests."""

from __future__ import annotations

import pytest

from pdcp_studio.bus.connection import open_connections


@pytest.fixture
def no_bus_left_open():
    """Fails the test when it leaves a bus connection open (use with ``usefixtures``)."""
    yield
    assert not open_connections(), "a test left a bus open"
