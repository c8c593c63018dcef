"""The examples (examples/) and the teaching notebook run as a user runs them, each asserting what
it shows. Each runs on a coarse grid or a short time (--quick) so that CI takes seconds."""

import os
import pathlib
import shutil
import subprocess
import sys

import pytest

from conftest import ROOT

EXAMPLES = ROOT / "examples"


def environment():
    env = dict(os.environ)
    env["MPLBACKEND"] = "Agg"
    return env


def run_example(name, *args):
    done = subprocess.run([sys.executable, str(EXAMPLES / name), "--quick", *args], capture_output=True, text=True,
                          timeout=280, env=environment())
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def test_critical_rotation_bisection_brackets_the_first_broken_bond():
    out = run_example("critical_rotation.py")
    assert "critical grip rotation" in out


def test_crack_analysis_plots_length_and_speed(tmp_path):
    out = run_example("crack_analysis.py", "--out", str(tmp_path / "crack.png"))
    assert (tmp_path / "crack.png").stat().st_size > 1000, out


def test_four_bar_work_precision_for_every_integrator(tmp_path):
    out = run_example("four_bar_work_precision.py", "--out", str(tmp_path / "wp.png"))
    assert (tmp_path / "wp.png").stat().st_size > 1000, out


@pytest.mark.skipif(shutil.which("jupyter-nbconvert") is None and shutil.which("jupyter") is None,
                    reason="jupyter-nbconvert is not installed (scripts/install-deps.sh installs it)")
def test_crack_in_a_plate_notebook_executes(tmp_path):
    notebook = EXAMPLES / "notebooks" / "crack_in_a_plate.ipynb"
    done = subprocess.run(["jupyter", "nbconvert", "--to", "notebook", "--execute", str(notebook), "--output-dir",
                           str(tmp_path), "--ExecutePreprocessor.timeout=240"], capture_output=True, text=True,
                          timeout=290, env=environment())
    assert done.returncode == 0, done.stderr[-4000:]
    assert (tmp_path / "crack_in_a_plate.ipynb").exists()
