"""Crack length and crack-tip speed of the notched plate against time, from the damage field.

The plate of scenes/notched_plate.toml is stepped from Python; at every output instant the damage
of each particle (sim.damage) and where the particles started (sim.reference_positions) give the
crack: the damaged particles (damage >= 0.35, about a third of a particle's bonds broken) above
the notch, the highest of them its tip. The crack length is the tip's height above the notch tip;
its speed the time derivative (NumPy's gradient). Matplotlib draws both against time.

    PYTHONPATH=build/python python3 examples/crack_analysis.py --out crack.png
    PYTHONPATH=build/python python3 examples/crack_analysis.py --quick   # 2 mm grid: seconds

Checked at the end: the crack only grows, it crosses most of the ligament, and its tip never
runs faster than the Rayleigh wave speed of PMMA, the bound of a running crack's speed in
linear elastic fracture mechanics (computed here from the scene's E, rho and nu = 1/3 of the
bond-based model).
"""

import argparse
import math
import pathlib

import numpy as np
import periflex

SCENE = pathlib.Path(__file__).resolve().parents[1] / "scenes" / "notched_plate.toml"
NOTCH_TIP_Y = -0.012  # m, the notch runs up from the lower edge (-0.02) to here
TOP_Y = 0.02          # m, the upper edge: the ligament is 32 mm
DAMAGED = 0.35


def crack_history(sim, interval):
    """Times [s] and crack lengths [m] at every instant k * interval to the end."""
    reference = sim.reference_positions
    above_notch = (np.abs(reference[:, 0]) < 0.01) & (reference[:, 1] > NOTCH_TIP_Y)
    times, lengths = [], []
    k = 1
    while sim.time < sim.end_time * (1 - 1e-12):
        sim.advance_to(min(k * interval, sim.end_time))
        cracked = above_notch & (sim.damage >= DAMAGED)
        times.append(sim.time)
        lengths.append(reference[cracked, 1].max() - NOTCH_TIP_Y if cracked.any() else 0.0)
        k += 1
    return np.array(times), np.array(lengths)


def rayleigh_speed(youngs_modulus, density, poisson):
    """Rayleigh wave speed (Viktorov's approximation, within 0.5 % for 0 <= nu <= 0.5)."""
    shear = youngs_modulus / (2 * (1 + poisson))
    return (0.862 + 1.14 * poisson) / (1 + poisson) * math.sqrt(shear / density)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a 2 mm grid (about a thousand particles)")
    parser.add_argument("--out", default="crack_analysis.png", help="the figure (PNG)")
    args = parser.parse_args(argv)
    sim = periflex.Simulation(SCENE, overrides={"flex_body.plate.grid_spacing": 2e-3} if args.quick else {})
    times, lengths = crack_history(sim, interval=1e-5)
    # the tip moves by whole particles: the speed over a window of a few rows
    window = 5
    speed = np.gradient(lengths, times)
    smooth_speed = np.convolve(speed, np.ones(window) / window, mode="same")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    top.plot(times * 1e3, lengths * 1e3)
    top.axhline((TOP_Y - NOTCH_TIP_Y) * 1e3, color="gray", linestyle="--", label="ligament")
    top.set_ylabel("crack length [mm]")
    top.legend()
    bottom.plot(times * 1e3, smooth_speed)
    c_r = rayleigh_speed(3.2e9, 1190.0, 1.0 / 3.0)
    bottom.axhline(c_r, color="gray", linestyle="--", label="Rayleigh wave speed")
    bottom.set_xlabel("t [ms]")
    bottom.set_ylabel("tip speed [m/s]")
    bottom.legend()
    figure.tight_layout()
    figure.savefig(args.out, dpi=100)
    print(f"wrote {args.out}: crack from t = {times[np.argmax(lengths > 0)] * 1e3:.3f} ms, "
          f"{lengths[-1] * 1e3:.1f} mm at the end, fastest {smooth_speed.max():.0f} m/s (c_R = {c_r:.0f} m/s)")

    assert np.all(np.diff(lengths) >= 0), "a crack does not heal"
    assert lengths[-1] > 0.5 * (TOP_Y - NOTCH_TIP_Y), "the crack crosses most of the ligament"
    assert 0 < smooth_speed.max() < c_r, "a crack runs slower than Rayleigh waves"
    return times, lengths, smooth_speed


if __name__ == "__main__":
    main()
