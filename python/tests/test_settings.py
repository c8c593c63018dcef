"""Live settings changed as the window changes them."""

import periflex
import pytest


def test_set_changes_the_step_and_the_clock(pendulum):
    pendulum.step(10)
    pendulum.set("solver.dt", 5e-4)
    assert pendulum.settings["dt"] == 5e-4
    pendulum.step(4)
    assert pendulum.time == pytest.approx(10e-3 + 4 * 5e-4, rel=1e-12)
    pendulum.set("integrator", "verlet")
    pendulum.set("fracture", False)
    assert pendulum.settings["integrator"] == "verlet" and pendulum.settings["fracture"] is False


def test_unknown_key_and_bad_value_are_refused_and_change_nothing(pendulum):
    before = pendulum.settings
    with pytest.raises(periflex.InputError, match="unknown live setting") as caught:
        pendulum.set("flex_body.plate.material.youngs_modulus", 5.0)
    assert caught.value.key == "flex_body.plate.material.youngs_modulus"
    # the pendulum has no flexible body "plate": refused as the override would be
    with pytest.raises(periflex.InputError, match="plate"):
        pendulum.set("flex_body.plate.material.fracture_energy", 5.0)
    with pytest.raises(periflex.InputError, match="must not be negative"):
        pendulum.set("bond_damping", -1.0)
    assert pendulum.settings == before


def test_dt_above_the_stability_limit_is_refused(small_plate):
    critical = small_plate.check()["critical_time_step"]
    with pytest.raises(periflex.InputError, match="critical step") as caught:
        small_plate.set("solver.dt", 10 * critical)
    assert caught.value.key == "solver.dt"
