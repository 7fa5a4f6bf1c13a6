"""Shared test set-up: Qt runs headless; paths to the shipped resources."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

ROOT = Path(__file__).resolve().parent.parent
RESOURCES = ROOT / "resources"


@pytest.fixture
def resources() -> Path:
    return RESOURCES


@pytest.fixture
def systems_dir() -> Path:
    return RESOURCES / "systems"
