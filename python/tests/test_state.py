"""Saved states: bytes that make the following steps repeat bit for bit; checkpoint files."""

import numpy as np
import periflex
import pytest

from conftest import SCENES


def record(sim):
    return sim.positions.copy(), sim.velocities.copy(), sim.damage.copy(), sim.time, sim.steps


def test_restored_state_continues_bit_for_bit(small_plate):
    small_plate.step(30)
    state = small_plate.save_state()
    assert isinstance(state, bytes)
    small_plate.step(40)
    first = record(small_plate)
    small_plate.restore_state(state)
    assert small_plate.steps == 30
    small_plate.step(40)
    second = record(small_plate)
    for a, b in zip(first, second):
        np.testing.assert_array_equal(a, b)


def test_a_state_of_another_model_is_refused(small_plate, pendulum):
    with pytest.raises(ValueError):
        small_plate.restore_state(pendulum.save_state())
    with pytest.raises(ValueError):
        pendulum.restore_state(b"not a state")


def test_checkpoint_file_continues_bit_for_bit(tmp_path):
    overrides = {"flex_body.plate.grid_spacing": 2e-3}
    sim = periflex.Simulation(SCENES / "notched_plate.toml", overrides=overrides)
    sim.step(25)
    path = tmp_path / "state.pfstate"
    sim.write_checkpoint(path)
    sim.step(25)
    resumed = periflex.Simulation.from_checkpoint(path, SCENES / "notched_plate.toml", overrides=overrides)
    assert resumed.steps == 25
    resumed.step(25)
    for a, b in zip(record(sim), record(resumed)):
        np.testing.assert_array_equal(a, b)
    with pytest.raises(periflex.InputError, match="another scene"):
        periflex.Simulation.from_checkpoint(path, SCENES / "notched_plate.toml")
