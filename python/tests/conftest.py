"""Shared paths of the Python module's tests (run with PYTHONPATH=build/python, see README)."""

import os
import pathlib
import shutil

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"
HOSTILE = ROOT / "tests" / "data" / "hostile"


def program():
    """The built program, to compare the module's messages with (None when it is not built)."""
    path = os.environ.get("PERIFLEX_BINARY") or shutil.which("periflex")
    return path if path and os.path.exists(path) else None


@pytest.fixture
def pendulum():
    import periflex

    return periflex.Simulation(SCENES / "pendulum.toml")


@pytest.fixture
def small_plate():
    """The notched plate at a coarse grid (about a thousand particles), pulled hard enough to crack."""
    import periflex

    return periflex.Simulation(SCENES / "notched_plate.toml", overrides={"flex_body.plate.grid_spacing": 2e-3})
