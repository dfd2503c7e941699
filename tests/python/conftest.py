"""Shared fixtures of the Python tests: the package on sys.path, worlds that close themselves."""
import sys
from pathlib import Path

import pytest

# Run straight from a checkout (`pytest tests/python`) as well as through `make test-python`.
_PACKAGE_ROOT = Path(__file__).resolve().parents[2] / "plugin" / "python"
if str(_PACKAGE_ROOT) not in sys.path:
    sys.path.insert(0, str(_PACKAGE_ROOT))

import physpix  # noqa: E402


@pytest.fixture
def world():
    """A default world (gravity (0, 980) px/s², CPU backend so results do not depend on the machine)."""
    with physpix.World(backend="cpu") as w:
        yield w


@pytest.fixture
def space():
    """A world without gravity, for mass and collision checks."""
    with physpix.World(gravity=(0, 0), backend="cpu") as w:
        yield w
