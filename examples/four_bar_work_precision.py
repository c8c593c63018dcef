"""The four-bar's error against run time for every integrator, plotted (a work-precision chart).

periflex.study() runs `periflex study` in this process on a study written here: the IFToMM
benchmark A02, a double four-bar swinging under gravity (scenes/benchmarks/a02_double_four_bar
.toml; the driven crank-rocker of scenes/four_bar.toml follows its driver exactly with any
integrator, so it measures nothing), with every integrator this build offers
(periflex.integrator_names()) at a few steps (the adaptive ones at a few tolerances), against
the benchmark's published reference solution (scenes/studies/references). It returns the rows
of study.csv; Matplotlib draws the largest probe error of each run against its solver time, one
line per integrator.

    PYTHONPATH=build/python python3 examples/four_bar_work_precision.py --out four_bar.png
    PYTHONPATH=build/python python3 examples/four_bar_work_precision.py --quick   # 1 s simulated

Checked at the end: each fixed-step integrator converges at least at its theoretical order
(the slope of log error against log dt the study fits, less 0.5 for the noise of three points;
symplectic Euler shows 2 over this first second, the order of its phase error here), and the
adaptive one's error falls as its tolerance does.
"""

import argparse
import pathlib
import tempfile

import periflex

SCENES = pathlib.Path(__file__).resolve().parents[1] / "scenes"
SCENE = SCENES / "benchmarks" / "a02_double_four_bar.toml"
REFERENCE = SCENES / "studies" / "references" / "a02_double_four_bar.csv"
STEPS = {"symplectic_euler": [2e-3, 1e-3, 5e-4], "verlet": [2e-3, 1e-3, 5e-4], "rk4": [1e-2, 5e-3, 2.5e-3],
         "hht": [2e-3, 1e-3, 5e-4]}
TOLERANCES = [1e-5, 1e-6, 1e-7]


def study_text(end_time):
    lines = ["[study]", f'scene = "{SCENE}"', 'reference = "csv"', f'reference_file = "{REFERENCE}"',
             'columns = ["probe.b0.x", "probe.b0.y"]', f"end_time = {end_time}", "compare_interval = 0.05",
             "repeats = 1"]
    for name in periflex.integrator_names():
        lines += ["[[method]]", f'integrator = "{name}"', 'correction = ["projection"]']
        if name in STEPS:
            lines.append(f"dt = {STEPS[name]}")
        else:  # adaptive: the sampling step, then its tolerances
            lines += ["dt = [5e-2]", f"tol = {TOLERANCES}"]
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="1 s of motion instead of 3 s")
    parser.add_argument("--out", default="four_bar_work_precision.png", help="the figure (PNG)")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as folder:
        path = pathlib.Path(folder) / "four_bar_study.toml"
        path.write_text(study_text(1.0 if args.quick else 3.0))
        table = periflex.study(path, out=pathlib.Path(folder) / "out")
    rows = [r for r in table["rows"] if r["status"] == "ok"]

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(7, 5))
    for name in periflex.integrator_names():
        mine = [r for r in rows if r["integrator"] == name]
        axes.loglog([r["wall_time"] for r in mine], [r["error_max"] for r in mine], "o-", label=name)
    axes.set_xlabel("solver time [s]")
    axes.set_ylabel("largest probe error [m]")
    axes.set_title("double four-bar (IFToMM A02) against its reference solution")
    axes.legend()
    axes.grid(True, which="both", alpha=0.3)
    figure.tight_layout()
    figure.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")
    for order in table["orders"]:
        print(f"  {order['integrator']:>16}: observed order {order['slope']:.2f} (theory {order['theory']})")

    assert {r["integrator"] for r in rows} == set(periflex.integrator_names()), "every integrator ran"
    for order in table["orders"]:
        if not order["against_tolerance"]:
            assert order["slope"] > order["theory"] - 0.5, order
    adaptive = [r["error_max"] for r in rows if r["tol"] > 0]
    assert adaptive == sorted(adaptive, reverse=True), "a tighter tolerance gives a smaller error"
    return table


if __name__ == "__main__":
    main()
