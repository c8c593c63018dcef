"""Cost of a call of sim.step(1) from Python on the pendulum, against steps taken in one call.

    PYTHONPATH=build/python python3 python/bench/step_overhead.py

Prints the median over repeats of the time per step both ways and their difference: the
overhead of one call (the call itself, the look for Ctrl-C); and the cost of a call of
sim.step(0), which takes no step: the call alone. Repeats alternate the two ways, so that a
change of the machine's load falls on both.
"""

import pathlib
import statistics
import time

import periflex

SCENE = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "pendulum.toml"
STEPS = 20000


def per_step(sim, one_call):
    start = time.perf_counter()
    if one_call:
        sim.step(STEPS)
    else:
        for _ in range(STEPS):
            sim.step(1)
    return (time.perf_counter() - start) / STEPS


def call_alone(sim):
    start = time.perf_counter()
    for _ in range(STEPS):
        sim.step(0)
    return (time.perf_counter() - start) / STEPS


def main():
    sim = periflex.Simulation(SCENE, overrides={"solver.end_time": 1e3})
    sim.step(100)
    batched, single, empty = [], [], []
    for _ in range(15):
        batched.append(per_step(sim, True))
        single.append(per_step(sim, False))
        empty.append(call_alone(sim))
    b, s, e = statistics.median(batched), statistics.median(single), statistics.median(empty)
    print(f"step(n): {b * 1e6:.3f} us/step, step(1): {s * 1e6:.3f} us/step, overhead {(s - b) * 1e6:.3f} us/call, "
          f"step(0): {e * 1e6:.3f} us/call")


if __name__ == "__main__":
    main()
