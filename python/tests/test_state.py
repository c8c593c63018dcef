"""Saved states: bytes that make the following steps repeat bit for bit; checkpoint files."""

import numpy as np
import periflex
import pytest

from conftest import SCENES, program


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


def test_from_checkpoint_without_the_scene_reads_the_record_beside_it(tmp_path):
    overrides = {"flex_body.plate.grid_spacing": 2e-3}
    sim = periflex.Simulation(SCENES / "notched_plate.toml", overrides=overrides)
    sim.step(25)
    sim.write_checkpoint(tmp_path / "state.pfstate")
    sim.step(25)
    resumed = periflex.Simulation.from_checkpoint(tmp_path / "state.pfstate")
    assert resumed.steps == 25
    resumed.step(25)
    for a, b in zip(record(sim), record(resumed)):
        np.testing.assert_array_equal(a, b)


def test_from_checkpoint_of_a_scene_given_as_text_needs_the_scene(tmp_path):
    text = (SCENES / "pendulum.toml").read_text()
    sim = periflex.Simulation(text)
    sim.step(5)
    sim.write_checkpoint(tmp_path / "state.pfstate")
    with pytest.raises(periflex.InputError, match="records no scene"):
        periflex.Simulation.from_checkpoint(tmp_path / "state.pfstate")
    assert periflex.Simulation.from_checkpoint(tmp_path / "state.pfstate", text).steps == 5


@pytest.mark.skipif(program() is None, reason="the program is not built")
def test_from_checkpoint_of_a_checkpointing_run_needs_no_scene(tmp_path):
    import subprocess

    done = subprocess.run([program(), "run", str(SCENES / "pendulum.toml"), "--until", "0.1",
                           "--checkpoint-every", "0.05", "--out", str(tmp_path), "--quiet"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    files = sorted((tmp_path / "checkpoints").glob("*.pfstate"))
    assert files
    sim = periflex.Simulation.from_checkpoint(files[0])
    assert sim.time == pytest.approx(0.05)
