"""Scenes from a path, TOML text or a dict, with overrides; check() against the scene's facts."""

import subprocess

import periflex
import pytest

from conftest import SCENES, program


def test_import_names_the_version_and_errors():
    assert periflex.__version__
    assert issubclass(periflex.InputError, ValueError)
    assert issubclass(periflex.NumericalError, RuntimeError)
    assert "rk4" in periflex.integrator_names()


def test_pendulum_check_counts_what_the_scene_declares(pendulum):
    # the scene's comment: one body (x, y, phi), one link equation, two degrees of freedom
    report = pendulum.check()
    assert report["scene"] == "pendulum"
    assert report["rigid_bodies"] == 1
    assert report["joints"] == 1
    assert report["coordinates"] == 3
    assert report["constraint_equations"] == 1
    assert report["degrees_of_freedom"] == 2
    assert report["integrator"] == "rk4"
    assert report["dt"] == 1e-3
    assert report["particles"] == 0
    assert report["critical_time_step"] is None


def test_overrides_dict_is_applied_like_set(pendulum):
    sim = periflex.Simulation(SCENES / "pendulum.toml", overrides={"solver.dt": 2.5e-4, "solver.integrator": "rk4"})
    assert sim.check()["dt"] == 2.5e-4
    assert sim.settings["dt"] == 2.5e-4


def test_text_and_dict_scenes_load_as_the_file_does(pendulum):
    text = (SCENES / "pendulum.toml").read_text()
    from_text = periflex.Simulation(text)
    scene = {
        "scene": {"name": "dict_pendulum", "gravity": [0.0, -9.81]},
        "solver": {"integrator": "rk4", "dt": 1e-3, "end_time": 1.0},
        "body": [{"name": "bob", "mass": 1.0, "inertia": 1.25e-3, "position": [0.8660254037844386, -0.5],
                  "shape": {"type": "circle", "center": [0.0, 0.0], "radius": 0.05}}],
        "joint": [{"name": "rod", "type": "revolute_revolute", "body_i": "ground", "body_j": "bob",
                   "point_i": [0.0, 0.0], "point_j": [0.0, 0.0], "length": 1.0}],
    }
    from_dict = periflex.Simulation(scene)
    for sim in (from_text, from_dict):
        report = sim.check()
        assert (report["coordinates"], report["constraint_equations"], report["degrees_of_freedom"]) == (3, 1, 2)
    assert from_dict.scene_name == "dict_pendulum"
    # the same model stepped the same way: the same positions, bit for bit
    pendulum.step(100)
    from_text.step(100)
    assert (pendulum.body_poses == from_text.body_poses).all()


def test_bad_override_names_the_override():
    with pytest.raises(periflex.InputError) as caught:
        periflex.Simulation(SCENES / "pendulum.toml", overrides={"solver.dt": -1.0})
    assert "--set" in str(caught.value)
    assert caught.value.key == "solver.dt"


def test_bad_text_names_line_and_column():
    with pytest.raises(periflex.InputError) as caught:
        periflex.Simulation("[scene]\nname = \"x\"\n[solver]\ndt = \"fast\"\n")
    error = caught.value
    assert error.file == "<string>"
    assert error.line == 4
    assert error.column > 0
    assert error.key == "solver.dt"
    assert str(error).startswith("<string>:4:")


@pytest.mark.skipif(program() is None, reason="the program is not built")
def test_check_agrees_with_the_program():
    path = str(SCENES / "notched_plate.toml")
    printed = subprocess.run([program(), "check", path], capture_output=True, text=True, check=True).stdout
    report = periflex.Simulation(path).check()
    assert f"{report['particles']} particles, {report['bonds']} bonds" in printed
    assert f"degrees of freedom    {report['degrees_of_freedom']}" in printed
    assert f"{report['critical_time_step']:g} s" in printed


def test_scenes_folder_holds_the_shipped_scenes():
    import periflex

    assert (periflex.scenes_folder() / "notched_plate.toml").is_file()
