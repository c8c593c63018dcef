"""Cost of reading sim.positions (a read-only view, no copy) of a body of about a million particles.

    PYTHONPATH=build/python python3 python/bench/positions_view.py

The notched plate at a 0.063 mm grid (1587 x 635 particles) is built (not stepped); then
sim.positions is read many times and the median time per read printed, beside that of a copy
(np.array(sim.positions)), which shows what a view saves.
"""

import pathlib
import statistics
import time

import numpy as np
import periflex

SCENE = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "notched_plate.toml"


def per_call(function, calls):
    start = time.perf_counter()
    for _ in range(calls):
        function()
    return (time.perf_counter() - start) / calls


def main():
    sim = periflex.Simulation(SCENE, overrides={"flex_body.plate.grid_spacing": 6.3e-5, "solver.dt": 2.5e-8})
    view = sim.positions
    assert view.shape[0] > 1_000_000 and not view.flags.writeable and not view.flags.owndata
    reads = [per_call(lambda: sim.positions, 10000) for _ in range(7)]
    copies = [per_call(lambda: np.array(sim.positions), 5) for _ in range(7)]
    print(f"{view.shape[0]} particles: sim.positions {statistics.median(reads) * 1e6:.2f} us per read "
          f"(a copy: {statistics.median(copies) * 1e3:.2f} ms)")


if __name__ == "__main__":
    main()
