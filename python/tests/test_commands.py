"""periflex.run(), study(), sweep(): the commands' own code in this process, their tables."""

import os
import signal
import subprocess
import threading

import numpy as np
import periflex
import pytest

from conftest import ROOT, SCENES, program

COARSE_PLATE = {"flex_body.plate.grid_spacing": 2e-3}


def program_run(tmp_path, *args):
    done = subprocess.run([program(), "run", *args, "--quiet"], capture_output=True, text=True, timeout=240)
    return done


@pytest.mark.skipif(program() is None, reason="the program is not built")
def test_run_writes_what_the_program_writes_and_returns_its_series(tmp_path):
    # until a time no whole number of steps reaches (dt = 4e-7 s)
    args = [str(SCENES / "notched_plate.toml"), "--set", "flex_body.plate.grid_spacing=2e-3", "--until", "2.3e-4"]
    done = program_run(tmp_path, *args, "--out", str(tmp_path / "program"))
    assert done.returncode == 0, done.stderr
    result = periflex.run(SCENES / "notched_plate.toml", overrides=COARSE_PLATE, until=2.3e-4, out=tmp_path / "module")
    assert result["out"] == str(tmp_path / "module")
    assert (tmp_path / "module" / "series.csv").read_bytes() == (tmp_path / "program" / "series.csv").read_bytes()
    summary = result["summary"]
    assert summary["status"] == "ok" and summary["exit_code"] == 0
    series = result["series"]
    assert series["t"][-1] == pytest.approx(2.3e-4, rel=1e-12)
    assert len(series["t"]) == summary["rows_written"]
    assert series["broken_bonds"].dtype == np.float64


@pytest.mark.skipif(program() is None, reason="the program is not built")
def test_run_refuses_bad_input_with_the_program_text(tmp_path):
    with pytest.raises(periflex.InputError) as caught:
        periflex.run(SCENES / "pendulum.toml", overrides={"solver.dt": -1.0}, out=tmp_path / "a")
    done = program_run(tmp_path, str(SCENES / "pendulum.toml"), "--set", "solver.dt=-1.0", "--out", str(tmp_path / "b"))
    assert done.returncode == 2
    assert f"periflex: error: {caught.value}" in done.stderr
    assert caught.value.key == "solver.dt"


def test_run_numerical_failure_raises_with_the_diagnostic_and_a_true_summary(tmp_path):
    # the flexible slider-crank with HHT at a step far too long (tests/cli/run_command_test.cpp)
    with pytest.raises(periflex.NumericalError) as caught:
        periflex.run(SCENES / "flexible_slider_crank.toml", overrides={"solver.integrator": "hht", "solver.dt": 2e-3},
                     out=tmp_path)
    assert caught.value.remedy and caught.value.time > 0
    summary = (tmp_path / "summary.json").read_text()
    assert '"numerical_failure"' in summary and '"exit_code": 3' in summary


def test_ctrl_c_stops_run_cleanly_and_gives_the_interpreter_its_handler_back(tmp_path):
    handler = signal.getsignal(signal.SIGINT)
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            periflex.run(SCENES / "notched_plate.toml", out=tmp_path, threads=1)
    finally:
        timer.cancel()
    assert signal.getsignal(signal.SIGINT) is handler
    summary = (tmp_path / "summary.json").read_text()
    assert '"interrupted"' in summary and '"exit_code": 130' in summary


STUDY = """
[study]
scene = "{scene}"
reference = "pendulum_exact"
end_time = 0.5
compare_interval = 0.05
repeats = 1

[[method]]
integrator = "rk4"
dt = [1e-2, 5e-3, 2.5e-3]
correction = ["projection"]

[[method]]
integrator = "verlet"
dt = [5e-3, 2.5e-3]
correction = ["projection"]
"""


def test_study_returns_the_rows_of_study_csv(tmp_path):
    path = tmp_path / "study.toml"
    path.write_text(STUDY.format(scene=SCENES / "studies" / "models" / "pendulum.toml"))
    table = periflex.study(path, out=tmp_path / "out")
    rows = table["rows"]
    assert [(r["integrator"], r["dt"]) for r in rows] == [("rk4", 1e-2), ("rk4", 5e-3), ("rk4", 2.5e-3),
                                                        ("verlet", 5e-3), ("verlet", 2.5e-3)]
    written = periflex._commands.read_table(table["files"]["csv"])
    assert len(written) == len(rows)
    for row, line in zip(rows, written):
        assert line["integrator"] == row["integrator"]
        assert float(line["error_max"]) == pytest.approx(row["error_max"], rel=1e-5)  # study.csv: 6 digits
    # the observed orders are the methods' (rk4: 4, verlet: 2), as the program prints them
    orders = {o["integrator"]: o["slope"] for o in table["orders"]}
    assert orders["rk4"] == pytest.approx(4, abs=0.5) and orders["verlet"] == pytest.approx(2, abs=0.5)


def test_study_refuses_a_bad_file_naming_the_key(tmp_path):
    path = tmp_path / "study.toml"
    path.write_text(STUDY.format(scene=SCENES / "studies" / "models" / "pendulum.toml").replace("0.05", "-1"))
    with pytest.raises(periflex.InputError) as caught:
        periflex.study(path, out=tmp_path / "out")
    assert caught.value.file == str(path) and "compare_interval" in caught.value.key


SWEEP = """
[sweep]
scene = "{scene}"
set = ["solver.end_time=0.2"]
jobs = 2
series = ["probe.bob.x"]

[[parameter]]
key = "solver.dt"
values = [1e-3, 2e-3]
"""


@pytest.mark.skipif(program() is None and periflex._commands.shutil.which("periflex") is None,
                    reason="the program is not built")
def test_sweep_runs_the_grid_and_returns_sweep_csv(tmp_path):
    path = tmp_path / "sweep.toml"
    path.write_text(SWEEP.format(scene=SCENES / "pendulum.toml"))
    rows = periflex.sweep(path, out=tmp_path / "out", program=program())
    assert [r["solver.dt"] for r in rows] == [1e-3, 2e-3]
    for row in rows:
        assert row["status"] == "ok" and row["simulated_time"] == pytest.approx(0.2)
        # each run's own last series row, as the program wrote it
        series = periflex.read_series(tmp_path / "out" / row["run"] / "series.csv")
        assert row["probe.bob.x"] == pytest.approx(series["probe.bob.x"][-1], rel=1e-9)
    with pytest.raises(periflex.InputError):
        path.write_text(SWEEP.format(scene=SCENES / "pendulum.toml").replace("solver.dt", "solver.nothing"))
        periflex.sweep(path, out=tmp_path / "bad", program=program())


HOSTILE_REFUSED = [p for p in sorted((ROOT / "tests" / "data" / "hostile" / "scenes").glob("*.toml"))
                   if b"# expect: 2 " in p.read_bytes()]


@pytest.mark.skipif(program() is None, reason="the program is not built")
@pytest.mark.parametrize("path", HOSTILE_REFUSED, ids=lambda p: p.name)
def test_run_refuses_hostile_scenes_with_the_program_text(tmp_path, path):
    # every scene of the corpus the program refuses: periflex.run refuses it with an InputError
    # whose text is what `periflex run` prints
    with pytest.raises(periflex.InputError) as caught:
        periflex.run(path, out=tmp_path / "module")
    done = subprocess.run([program(), "run", str(path), "--out", str(tmp_path / "program"), "--quiet"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert f"periflex: error: {caught.value}" in done.stderr
