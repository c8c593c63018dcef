"""The grip rotation at which the notched plate's crack starts, found by bisection.

The grips of scenes/notched_plate.toml turn at 6 rad/s each. A run to the end time T turns them
by theta = 6 T; the crack has started when bonds at the notch tip have broken. Whether it has is
a yes/no question of one scene key (solver.end_time), answered by a fresh simulation each time:
bisection halves the bracket [0, theta_max] until it is narrower than the tolerance.

    PYTHONPATH=build/python python3 examples/critical_rotation.py           # the scene's grid
    PYTHONPATH=build/python python3 examples/critical_rotation.py --quick   # 2 mm grid: seconds

The check at the end (an independent answer): one run stepped through row by row finds the first
row with a broken bond; the bisection's bracket must hold the rotation at that instant.
"""

import argparse
import pathlib

import periflex

SCENE = pathlib.Path(__file__).resolve().parents[1] / "scenes" / "notched_plate.toml"
RATE = 6.0  # rad/s, each grip (the scene's drivers)


def overrides(quick):
    return {"flex_body.plate.grid_spacing": 2e-3} if quick else {}


def crack_started(theta, quick):
    """True when turning the grips to theta [rad] breaks a bond (one run of the scene)."""
    sim = periflex.Simulation(SCENE, overrides={**overrides(quick), "solver.end_time": theta / RATE})
    sim.advance_to(sim.end_time)
    return int(sim.broken_bonds.sum()) > 0


def bisect(lo, hi, tolerance, quick):
    """The bracket [lo, hi] of the critical rotation: no crack at lo, a crack at hi."""
    assert not crack_started(lo, quick) and crack_started(hi, quick), "the bracket does not hold the start"
    runs = 2
    while hi - lo > tolerance:
        mid = 0.5 * (lo + hi)
        if crack_started(mid, quick):
            hi = mid
        else:
            lo = mid
        runs += 1
        print(f"  [{lo * 1e3:.4f}, {hi * 1e3:.4f}] mrad")
    return lo, hi, runs


def first_break_by_rows(quick):
    """The rotation at the first output row with a broken bond, from one run (rows every 1e-5 s)."""
    sim = periflex.Simulation(SCENE, overrides=overrides(quick))
    interval = 1e-5
    k = 1
    while sim.time < sim.end_time:
        sim.advance_to(k * interval)
        if sim.broken_bonds.sum() > 0:
            return RATE * (sim.time - interval), RATE * sim.time
        k += 1
    raise AssertionError("the plate never cracked")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a 2 mm grid (about a thousand particles)")
    args = parser.parse_args(argv)
    lo, hi, runs = bisect(RATE * 1e-5, RATE * 1e-3, 0.02e-3, args.quick)
    print(f"critical grip rotation: {lo * 1e3:.4f} .. {hi * 1e3:.4f} mrad ({runs} runs; "
          f"the crack starts at t = {lo / RATE * 1e3:.4f} .. {hi / RATE * 1e3:.4f} ms)")
    row_lo, row_hi = first_break_by_rows(args.quick)
    print(f"one run, row by row: the first broken bond between {row_lo * 1e3:.4f} and {row_hi * 1e3:.4f} mrad")
    # the same event found more finely: no crack at lo, so lo is below the first cracked row;
    # a crack at hi, at most one tolerance above the critical rotation, itself below row_hi
    assert row_lo <= lo + 1e-12 and hi <= row_hi + 1e-12 + 0.02e-3, (lo, hi, row_lo, row_hi)
    return lo, hi


if __name__ == "__main__":
    main()
