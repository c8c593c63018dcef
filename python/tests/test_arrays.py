"""NumPy arrays of the state: views without copies, read-only, consistent with the series."""

import numpy as np
import periflex
import pytest


def test_positions_are_a_read_only_view_that_follows_the_steps(small_plate):
    positions = small_plate.positions
    assert positions.shape == (small_plate.check()["particles"], 2)
    assert positions.dtype == np.float64
    assert not positions.flags.writeable
    with pytest.raises(ValueError):
        positions[0, 0] = 1.0
    before = positions.copy()
    again = small_plate.positions
    assert np.shares_memory(positions, again)  # the same memory, not a copy per read
    small_plate.step(20)
    assert not np.array_equal(positions, before)  # the view shows the state now


def test_displacement_damage_and_broken_bonds_agree(small_plate):
    small_plate.advance_to(1.5e-3)
    np.testing.assert_array_equal(small_plate.displacement,
                                  small_plate.positions - small_plate.reference_positions)
    damage = small_plate.damage
    assert damage.min() >= 0.0 and damage.max() <= 1.0
    broken = small_plate.broken_bonds
    row = small_plate.series_row()
    # every broken bond is counted at both its particles
    assert broken.sum() == 2 * row["broken_bonds"]
    assert row["broken_bonds"] > 0, "the plate did not crack: the test shows nothing"
    assert damage.max() == pytest.approx(row["max_damage"], rel=1e-6)  # float32 damage
    for array in (damage, broken, small_plate.displacement):
        assert not array.flags.writeable


def test_body_poses_are_the_rigid_coordinates(pendulum):
    pendulum.step(100)
    poses = pendulum.body_poses
    assert pendulum.body_names == ["bob"]
    assert poses.shape == (1, 3)
    assert not poses.flags.writeable
    row = pendulum.series_row()
    assert poses[0, 0] == row["probe.bob.x"] and poses[0, 1] == row["probe.bob.y"]
    # the rod keeps the bob 1 m from the pivot (Baumgarte correction: to about 1e-6)
    assert np.hypot(poses[0, 0], poses[0, 1]) == pytest.approx(1.0, abs=1e-5)


def test_series_row_has_the_file_columns_and_units(pendulum):
    pendulum.step(10)
    row = pendulum.series_row()
    units = pendulum.series_units()
    assert list(row)[0] == "t" and row["t"] == pendulum.time
    assert set(units) == set(row)
    assert units["t"] == "s"
    assert periflex.series_units(pendulum) == units
