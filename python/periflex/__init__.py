"""periflex from Python: flexible multibody dynamics in 2D with peridynamic bodies that crack.

    import periflex
    sim = periflex.Simulation("scenes/notched_plate.toml", overrides={"solver.dt": 2e-7})
    sim.advance_to(1e-4)
    print(sim.time, sim.damage.max(), sim.series_row()["fracture"])

The scene is loaded, checked and stepped by the program's own code in this process; errors are
raised with the program's messages (InputError, a ValueError; NumericalError, a RuntimeError).
"""

import os as _os
import pathlib as _pathlib

from . import _toml
from ._periflex import InputError, NumericalError, integrator_names, render_available, __version__  # noqa: F401
from ._periflex import _Simulation
from . import _periflex as _periflex_core

__all__ = ["Simulation", "InputError", "NumericalError", "integrator_names", "render_available", "series_units",
           "scenes_folder", "run", "study", "sweep", "read_series", "__version__"]


def _installed_resource_root():
    """share/periflex of the prefix this package is installed under ("" in the build tree).

    The package sits in PREFIX/lib/python3/dist-packages/periflex, the shaders and colour maps
    in PREFIX/share/periflex, as the program finds them beside its bin/ folder.
    """
    here = _pathlib.Path(__file__).resolve().parent
    for prefix in list(here.parents)[:5]:
        if (prefix / "share" / "periflex" / "shaders").is_dir():
            return str(prefix / "share" / "periflex")
    return ""


def _override_text(key, value):
    """One "key.path=value" override as `periflex run --set` takes it (the value as TOML)."""
    return f"{key}={_toml.value(value, key)}"


def _setting_text(value):
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, float):
        return repr(value)
    return str(value)


class Simulation(_Simulation):
    """A periflex simulation in this process.

    Simulation(scene, overrides=None)

    scene: a path to a scene file (str or os.PathLike), TOML text (a str holding a newline), or
        a dict of the scene's tables (lists of dicts for [[body]], [[flex_body]], ...).
    overrides: {"solver.dt": 2e-7, "flex_body.plate.material.fracture_energy": 5.0}: scene keys
        set as `periflex run --set key=value` sets them, validated like the file's own values.

    Raises InputError (a ValueError) with the program's message, naming file, line, column and
    key, for a scene the program would refuse.

    The particle arrays (positions, velocities) and the rigid body arrays (body_poses,
    body_velocities) are read-only views of the simulation's state, without copies; damage,
    broken_bonds, displacement and reference_positions are copies made when read.
    """

    def __init__(self, scene, overrides=None):
        if isinstance(overrides, (list, tuple)):
            texts = [str(t) for t in overrides]  # "key=value" as --set takes it
        else:
            texts = [_override_text(k, v) for k, v in (overrides or {}).items()]
        if isinstance(scene, dict):
            super().__init__("", _toml.dumps(scene), "<dict>", texts)
        elif isinstance(scene, _os.PathLike) or (isinstance(scene, str) and "\n" not in scene):
            super().__init__(_os.fspath(scene), "", "", texts)
        elif isinstance(scene, str):
            super().__init__("", scene, "<string>", texts)
        else:
            raise TypeError(f"scene: expected a path, TOML text or a dict, not {type(scene).__name__}")

    @classmethod
    def from_checkpoint(cls, path, scene=None, overrides=None):
        """A simulation continued from the checkpoint file `path`.

        Without `scene`, the scene file and overrides recorded beside the checkpoint (run.json,
        written by `periflex run --checkpoint-every` and by write_checkpoint() of a scene read
        from a file); InputError when its folder records none (a scene given as text or a dict:
        pass it). With `scene` (and `overrides`), that scene: the file must have been written
        for the same scene text and overrides; InputError otherwise.
        """
        if scene is None:
            if overrides is not None:
                raise TypeError("from_checkpoint: overrides without scene; the recorded ones are used")
            scene, overrides = _periflex_core._recorded_scene(_os.fspath(path))
        sim = cls(scene, overrides)
        sim.restore_checkpoint(_os.fspath(path))
        return sim

    def write_checkpoint(self, path):
        """Write the state to a checkpoint file (the format of `periflex run --checkpoint-every`)."""
        super().write_checkpoint(_os.fspath(path))

    def restore_checkpoint(self, path):
        """Put back the state of a checkpoint file written for this scene and overrides."""
        super().restore_checkpoint(_os.fspath(path))

    def set(self, key, value):
        """Change a live setting between steps, as the window's parameter panel does.

        Keys: dt, integrator, correction (none, baumgarte, projection), alpha, beta, tolerance,
        max_iterations, bond_damping, global_damping, fracture (True/False), also spelled as
        scene keys (solver.dt, solver.integrator, solver.correction.method,
        solver.correction.alpha, flex_body.bond_damping, ...; the damping and fracture switch
        apply to every flexible body, as in the window).

        Also a flexible body's constants of breaking, flex_body.NAME.material.fracture_energy
        (G0) or .critical_stretch: the model is built again with the value (as an override) and
        continues from the state now, so the bonds broken so far stay broken and the next ones
        break by the new value. The array views taken before keep showing the old model's
        state; read them again.

        Anything else, or a refused value (a dt above the explicit stability limit, a G0 out of
        range), raises InputError naming the key; nothing changes then.
        """
        if key.startswith("flex_body.") and ".material." in key:
            self._set(key, _toml.value(value, key))
        else:
            self._set(key, _setting_text(value))

    def render(self, width=1280, height=720, field="damage", deform="auto", *, colormap=None, samples=None,
               overlay=True, camera=None):
        """The state now as a picture: a (height, width, 3) uint8 RGB array, rows top to bottom.

        Drawn by the program's off-screen renderer (EGL, no display needed) in this process, as
        `periflex run --snapshot-at T --size WxH` draws its screenshot: the same pixels for the
        same state. field: damage, displacement, speed or strain. deform: "auto" (the
        magnification chosen from this picture, as a screenshot's) or a factor K >= 0 (1: true
        scale, 0: undeformed). colormap: a name of assets/colormaps (default "ember"). samples:
        multisamples per pixel (default: 4, or 1 from 100k particles on). overlay: the time,
        scene name, legend and scale bar. camera: (x, y, view height) in metres (default: fitted
        to the scene). Bad arguments raise InputError naming them; RuntimeError when EGL cannot
        make a context.
        """
        return self._render(int(width), int(height), str(field), str(deform), colormap or "", int(samples or 0),
                            bool(overlay), [float(c) for c in camera] if camera is not None else [],
                            _installed_resource_root())

    def __repr__(self):
        return f"<periflex.Simulation '{self.scene_name}' t={self.time:.6g} s, {self.steps} steps>"


def scenes_folder():
    """The folder of the scenes shipped with periflex (notched_plate.toml, pendulum.toml, ...): the
    installed share/periflex/scenes, else where the program finds them ($PERIFLEX_ROOT, then the
    source tree the module was built from)."""
    return _pathlib.Path(_installed_resource_root() or _periflex_core._program_resource_root()) / "scenes"


def series_units(sim):
    """The unit of each series.csv column of `sim` (as sim.series_units())."""
    return sim.series_units()


# the commands, after _override_text which run() uses
from ._commands import read_series, run, study, sweep  # noqa: F401
