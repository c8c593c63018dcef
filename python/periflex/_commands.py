"""periflex.run(), periflex.study(), periflex.sweep(): the program's commands in this process.

Each calls the command's own code (src/cli, src/study) as `periflex run|study|sweep` does, writes
the same files, and returns their tables; bad input raises InputError and a numerical failure
NumericalError with the program's text, Ctrl-C stops the command cleanly and raises
KeyboardInterrupt.
"""

import csv
import json
import os
import pathlib
import shutil

from . import _periflex


def _number(text):
    try:
        return float(text)
    except ValueError:
        return text


def read_series(path):
    """A series.csv as {column: float64 array} (empty arrays when it has no rows)."""
    import numpy as np  # here: `import periflex` stays quick (NumPy loads with the first array)

    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return {}
    header, values = rows[0], np.array(rows[1:], dtype=float).reshape(len(rows) - 1, len(rows[0]))
    return {name: values[:, k].copy() for k, name in enumerate(header)}


def read_table(path):
    """A CSV table (sweep.csv, study.csv) as a list of {column: value} rows, numbers as floats."""
    with open(path, newline="") as f:
        return [{k: _number(v) for k, v in row.items()} for row in csv.DictReader(f)]


def _path(value):
    return "" if value is None else os.fspath(value)


def run(scene, overrides=None, *, until=None, dt=None, integrator=None, out=None, threads=0, quiet=True,
        vtk_every=0, checkpoint_every=0.0, checkpoint_dir=None, restart=None, render=False, frames=None,
        movie=None, frame_every=0.0, size=None, samples=0, fps=30.0, snapshot_at=None, screenshot=None,
        field=None, colormap=None, camera=None, deform=None, draw_contacts=False, plot=None, plot_against=None):
    """Run a scene as `periflex run` does and return its tables.

    Every argument is the flag of the same name (`overrides` are --set key=value, written as
    TOML values; `restart` is --restart FILE; `size` "WxH" or (W, H)). Writes what the program
    writes (series.csv, summary.json, frames, movies, checkpoints) into `out` (default
    out/<scene name>). Returns {"series": {column: array}, "summary": dict, "out": folder}.

    Raises InputError for bad input (before or during the run), NumericalError for a numerical
    failure (the outputs written so far stay valid, summary.json says what happened), and
    KeyboardInterrupt after a Ctrl-C has stopped the run cleanly.
    """
    from . import _override_text

    o = _periflex._RunOptions()
    o.scene_path = _path(scene)
    o.overrides = [_override_text(k, v) for k, v in (overrides or {}).items()]
    o.until, o.dt, o.integrator = until, dt, integrator
    o.out_dir, o.threads, o.quiet, o.vtk_every = _path(out), int(threads), bool(quiet), int(vtk_every)
    o.checkpoint_every, o.checkpoint_dir, o.restart_path = float(checkpoint_every), _path(checkpoint_dir), _path(restart)
    o.render, o.frames_dir, o.movie_path, o.frame_every = bool(render), _path(frames), _path(movie), float(frame_every)
    o.size_text = "" if size is None else size if isinstance(size, str) else f"{size[0]}x{size[1]}"
    o.samples, o.fps, o.snapshot_at, o.screenshot_path = int(samples), float(fps), snapshot_at, _path(screenshot)
    o.field, o.colormap, o.deform = field or "", colormap or "", "" if deform is None else str(deform)
    o.camera = "" if camera is None else camera if isinstance(camera, str) else ",".join(repr(float(c)) for c in camera)
    o.draw_contacts, o.plot, o.plot_against = bool(draw_contacts), plot or "", plot_against or ""
    exit_code, folder = _periflex._run(o)
    if not folder:  # a checkpoint folder drawn, nothing simulated: frames only
        if exit_code != 0:
            raise RuntimeError(f"periflex run ended with exit code {exit_code}")
        return {"series": {}, "summary": {}, "out": ""}
    folder = pathlib.Path(folder)
    summary = json.loads((folder / "summary.json").read_text()) if (folder / "summary.json").exists() else {}
    if exit_code != 0:
        raise RuntimeError(summary.get("message", f"periflex run ended with exit code {exit_code}"))
    series_path = folder / "series.csv"
    return {"series": read_series(series_path) if series_path.exists() else {}, "summary": summary, "out": str(folder)}


def study(path, *, out=None, repeats=0, quiet=True):
    """Run a study file as `periflex study` does (study.csv, study.md, study.png into `out`,
    default out/study-<name>) and return its table.

    Returns {"name", "scene", "reference", "reference_error", "excursion", "times", "rows",
    "orders", "files", ...}: one row per run of the method grid (integrator, correction, dt, tol,
    error_max, error_rms (and _rel), energy_error, violation, wall_time, steps, status, ...) and
    the observed order of each series. Raises InputError for a bad study file.
    """
    return _periflex._study(os.fspath(path), _path(out), int(repeats), bool(quiet))


def _program():
    """The periflex program the runs of a sweep start: beside this package when installed
    (PREFIX/bin/periflex), in the build tree (build/src/periflex), or on the PATH."""
    here = pathlib.Path(__file__).resolve().parent
    for candidate in [*(p / "bin" / "periflex" for p in list(here.parents)[:5]), here.parents[1] / "src" / "periflex"]:
        if candidate.is_file() and os.access(candidate, os.X_OK):
            return str(candidate)
    found = shutil.which("periflex")
    if found:
        return found
    raise RuntimeError("sweep: the periflex program was not found beside this package or on the PATH; "
                       "give program=PATH")


def sweep(path=None, *, out=None, jobs=0, jobs_file=None, collect=None, quiet=True, program=None):
    """Run a sweep file as `periflex sweep` does and return sweep.csv as a list of rows.

    Each run is `periflex run` as a child process (the program beside this package, or
    `program`), `jobs` at once, with the sweep's time and memory limits; sweep.csv gathers their
    summaries and last series values (a row per run: run, the parameters, status, exit_code,
    simulated_time, steps, wall_time, solver_cpu_time, the series columns). jobs_file: write the
    command lines instead of running (returns []). collect: gather an existing sweep folder.
    Raises InputError for a bad sweep file; a failed run is a row whose status says so.
    """
    o = _periflex._SweepOptions()
    o.sweep_path, o.out_dir, o.jobs = _path(path), _path(out), int(jobs)
    o.jobs_file, o.collect_dir, o.quiet = _path(jobs_file), _path(collect), bool(quiet)
    o.program = os.fspath(program) if program is not None else _program()
    exit_code, folder = _periflex._sweep(o)
    table = pathlib.Path(folder) / "sweep.csv"
    if exit_code == 2:
        raise _periflex.InputError("sweep: give a sweep file, or collect=DIR")
    return read_table(table) if table.exists() and not jobs_file else []
