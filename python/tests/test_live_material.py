"""set() of a flexible body's fracture energy: the model built again, the state carried on."""

import numpy as np
import periflex
import pytest

from conftest import SCENES

COARSE = {"flex_body.plate.grid_spacing": 2e-3}
G0 = "flex_body.plate.material.fracture_energy"


def plate(**extra):
    return periflex.Simulation(SCENES / "notched_plate.toml", overrides={**COARSE, **extra})


def test_fracture_energy_set_before_stepping_runs_as_the_override():
    live, built = plate(), plate(**{G0: 40.0})
    live.set(G0, 40.0)
    live.advance_to(5e-4)
    built.advance_to(5e-4)
    np.testing.assert_array_equal(live.positions, built.positions)
    np.testing.assert_array_equal(live.damage, built.damage)
    assert live.series_row() == built.series_row()


def test_fracture_energy_set_mid_run_keeps_the_state_and_changes_what_breaks():
    sim = plate()
    sim.advance_to(3.5e-4)  # before the crack starts (about 0.4 ms)
    broken = sim.broken_bonds.sum()
    view = sim.positions
    before = view.copy()
    state = sim.save_state()
    sim.set(G0, 30.0)
    # the state is the one of now, in the new model
    assert sim.time == pytest.approx(3.5e-4, rel=1e-12) and sim.broken_bonds.sum() == broken
    np.testing.assert_array_equal(sim.positions, before)
    # the view taken before shows the old model, still alive
    np.testing.assert_array_equal(view, before)
    sim.advance_to(6e-4)
    weak = sim.broken_bonds.sum()
    # the same state under the scene's G0 (300 J/m^2) breaks fewer bonds by then
    strong = plate()
    strong.restore_state(state)
    strong.advance_to(6e-4)
    assert weak > 2 * strong.broken_bonds.sum() > 0


def test_refused_value_changes_nothing():
    sim = plate()
    sim.step(10)
    with pytest.raises(periflex.InputError) as caught:
        sim.set(G0, -5.0)
    assert "fracture_energy" in str(caught.value)
    assert sim.steps == 10


def test_checkpoint_after_set_names_the_new_value(tmp_path):
    sim = plate()
    sim.step(20)
    sim.set(G0, 30.0)
    sim.step(20)
    sim.write_checkpoint(tmp_path / "a.pfstate")
    resumed = periflex.Simulation.from_checkpoint(tmp_path / "a.pfstate")
    sim.step(30)
    resumed.step(30)
    np.testing.assert_array_equal(sim.positions, resumed.positions)
