"""Refusals and failures as Python exceptions with the program's text; the hostile corpus."""

import pathlib
import re
import subprocess

import periflex
import pytest

from conftest import HOSTILE, SCENES, program

HOSTILE_SCENES = sorted((HOSTILE / "scenes").glob("*.toml"))


def expectation(path):
    """The exit code and text a hostile scene's header expects of `periflex check`."""
    for line in path.read_bytes().decode("utf-8", "replace").splitlines():
        match = re.match(r"# expect: (\d+)\*? (.*)", line)
        if match:
            return int(match.group(1)), match.group(2).strip()
    raise AssertionError(f"{path.name}: no '# expect:' line")


def check_through_module(path):
    """Exit code as the program would give it, and the text it would print."""
    try:
        sim = periflex.Simulation(path)
        report = sim.check()
    except periflex.InputError as error:
        return 2, str(error)
    except periflex.NumericalError as error:
        return 3, str(error)
    return 0, "\n".join(report["warnings"])


@pytest.mark.parametrize("path", HOSTILE_SCENES, ids=lambda p: p.name)
def test_hostile_scene_is_refused_with_the_program_text(path):
    code, text = expectation(path)
    got_code, got_text = check_through_module(str(path))
    assert got_code == code, got_text
    assert text in got_text


@pytest.mark.skipif(program() is None, reason="the program is not built")
@pytest.mark.parametrize("name", ["binary_garbage.toml", "nul_bytes.toml", "deep_nesting.toml",
                                  "density_1e300.toml", "attachment_missing_body.toml"])
def test_message_is_the_program_stderr(name):
    path = str(HOSTILE / "scenes" / name)
    result = subprocess.run([program(), "check", path], capture_output=True)
    assert result.returncode == 2
    _, text = check_through_module(path)
    assert f"periflex: error: {text}".encode() in result.stderr


def test_numerical_failure_carries_the_diagnostic():
    # HHT far above the step its Newton iterations can take on the flexible slider-crank (the
    # program exits 3 on it: tests/cli/run_command_test.cpp)
    sim = periflex.Simulation(SCENES / "flexible_slider_crank.toml",
                              overrides={"solver.integrator": "hht", "solver.dt": 2e-3})
    with pytest.raises(periflex.NumericalError) as caught:
        sim.advance_to(sim.end_time)
    error = caught.value
    assert error.quantity and error.time > 0 and error.remedy
    assert str(error).startswith(error.quantity)
    assert error.remedy in str(error)
    assert "Newton iterate (a trial, not a state of the run)" in str(error)
