"""sim.step(1000) from Python against `periflex run` on the notched plate at about 100k particles.

    PYTHONPATH=build/python python3 python/bench/step_vs_run.py [--repeats 3] [--steps 1000]

The same scene, overrides and steps both ways: the program's solver time (summary.json
solver_time: its stepping alone, rows and model building left out) against the time of one
sim.step(steps) call (after the initial conditions are made consistent, as the program does
before its loop). Runs alternate program / module so that a change of the machine's load falls
on both; prints each pair, the medians, their ratio and the load average.
"""

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

import periflex

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "notched_plate.toml"
# 0.2 mm: 500 x 200 particles; the step scaled with the spacing (the scene's 4e-7 s at 1 mm)
OVERRIDES = {"flex_body.plate.grid_spacing": 2e-4, "solver.dt": 8e-8}


def program():
    return os.environ.get("PERIFLEX_BINARY") or str(ROOT / "build" / "src" / "periflex")


def program_seconds(steps, folder):
    args = [program(), "run", str(SCENE), "--until", repr(steps * OVERRIDES["solver.dt"]), "--out", folder, "--quiet"]
    for key, value in OVERRIDES.items():
        args += ["--set", f"{key}={value!r}"]
    subprocess.run(args, check=True, capture_output=True)
    summary = json.loads((pathlib.Path(folder) / "summary.json").read_text())
    assert summary["steps"] == steps, summary["steps"]
    return summary["solver_time"]


def module_seconds(steps):
    sim = periflex.Simulation(SCENE, overrides=OVERRIDES)
    sim.check()  # the initial conditions made consistent, as the program does before stepping
    start = time.perf_counter()
    sim.step(steps)
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--steps", type=int, default=1000)
    args = parser.parse_args()
    runs, steps = [], []
    with tempfile.TemporaryDirectory() as folder:
        for k in range(args.repeats):
            a = program_seconds(args.steps, folder)
            b = module_seconds(args.steps)
            runs.append(a)
            steps.append(b)
            print(f"pair {k + 1}: periflex run {a:.3f} s, sim.step({args.steps}) {b:.3f} s, load {os.getloadavg()[0]:.1f}")
    a, b = statistics.median(runs), statistics.median(steps)
    print(f"medians: periflex run {a:.3f} s, sim.step {b:.3f} s: the module {100 * (b / a - 1):+.1f} %; "
          f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
