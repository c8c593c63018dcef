"""sim.render(): the program's off-screen renderer in this process, the pixels of `run --snapshot-at`."""

import subprocess

import numpy as np
import periflex
import pytest

from conftest import SCENES, program

pytestmark = pytest.mark.skipif(not periflex.render_available(), reason="built without the off-screen renderer")

COARSE = {"flex_body.plate.grid_spacing": 2e-3}


def read_png_rgb(path):
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGB"))


def advance_as_the_run(sim, t, interval):
    """Step as `periflex run` steps: it lands on every row instant k * output_interval (and on t),
    shortening the step before each, so its state at t is reached by these same steps."""
    k = 1
    while k * interval < t * (1 - 1e-12):
        sim.advance_to(k * interval)
        k += 1
    sim.advance_to(t)


@pytest.mark.skipif(program() is None, reason="the program is not built")
@pytest.mark.parametrize("field,deform", [("damage", "auto"), ("displacement", "3")])
def test_render_gives_the_pixels_of_run_snapshot_at(tmp_path, field, deform):
    # a cracked plate at a time that is no whole number of steps (dt = 4e-7 s, rows every 1e-5 s)
    t, interval, width, height = 6.1234e-4, 1e-5, 320, 200
    shot = tmp_path / "shot.png"
    args = [program(), "run", str(SCENES / "notched_plate.toml"), "--set", "flex_body.plate.grid_spacing=2e-3",
            "--until", repr(t), "--snapshot-at", repr(t), "--screenshot", str(shot), "--size", f"{width}x{height}",
            "--field", field, "--deform", deform, "--out", str(tmp_path / "run"), "--quiet", "--threads", "1"]
    done = subprocess.run(args, capture_output=True, text=True, timeout=240)
    assert done.returncode == 0, done.stderr

    sim = periflex.Simulation(SCENES / "notched_plate.toml", overrides={**COARSE, "solver.threads": 1})
    advance_as_the_run(sim, t, interval)
    assert sim.damage.max() > 0.3  # the crack is in the picture
    picture = sim.render(width, height, field=field, deform=deform)
    assert picture.shape == (height, width, 3) and picture.dtype == np.uint8
    # exact: the same state (the same steps), the same renderer, camera and settings, and the
    # same software rasteriser in both processes
    np.testing.assert_array_equal(picture, read_png_rgb(shot))


def test_render_shows_the_crack_and_the_field_asked_for(small_plate):
    before = small_plate.render(200, 120)
    small_plate.advance_to(8e-4)
    after = small_plate.render(200, 120)
    speed = small_plate.render(200, 120, field="speed")
    assert before.shape == (120, 200, 3)
    assert np.abs(after.astype(int) - before.astype(int)).sum() > 0
    assert np.abs(after.astype(int) - speed.astype(int)).sum() > 0
    # the background colour (0.12, 0.12, 0.14) fills the corners
    assert tuple(after[-1, 0]) == (31, 31, 36)


def test_render_refuses_bad_arguments_naming_them(pendulum):
    with pytest.raises(periflex.InputError, match="field"):
        pendulum.render(100, 100, field="temperature")
    with pytest.raises(periflex.InputError, match="deform"):
        pendulum.render(100, 100, deform="-2")
    with pytest.raises(periflex.InputError, match="width, height"):
        pendulum.render(4, 100)
    with pytest.raises(periflex.InputError, match="camera"):
        pendulum.render(100, 100, camera=(0, 0, -1))


def test_render_runs_beside_other_threads(pendulum):
    import threading

    pictures = []
    thread = threading.Thread(target=lambda: pictures.append(pendulum.render(64, 48)))
    thread.start()
    thread.join()
    pictures.append(pendulum.render(64, 48))
    np.testing.assert_array_equal(pictures[0], pictures[1])
