"""Stepping from Python: counts and times, the GIL released, Ctrl-C between steps."""

import os
import signal
import threading
import time

import periflex
import pytest

from conftest import SCENES


def test_step_counts_and_times(pendulum):
    pendulum.step()
    pendulum.step(9)
    assert pendulum.steps == 10
    assert pendulum.time == pytest.approx(10 * 1e-3, rel=1e-12)  # the clock: origin + steps * dt


def test_step_takes_its_count_as_pybind11_methods_take_theirs(pendulum):
    # step is a method of the fast calling convention: the same signature, keyword and refusals
    # as the module's other methods
    import inspect
    assert str(inspect.signature(pendulum.step)) == "(n=1)"
    assert "Take n steps of dt" in periflex.Simulation.step.__doc__
    pendulum.step(n=3)
    pendulum.step(True)  # an int, as Python counts it
    assert pendulum.steps == 4
    for args, kwargs, error in [((1.5,), {}, TypeError), (("2",), {}, TypeError), ((1, 2), {}, TypeError),
                                ((), {"m": 1}, TypeError), ((1,), {"n": 1}, TypeError), ((-1,), {}, ValueError),
                                ((2**70,), {}, OverflowError)]:
        with pytest.raises(error):
            pendulum.step(*args, **kwargs)
    assert pendulum.steps == 4
    with pytest.raises(TypeError):
        periflex.Simulation.step(3)  # not a simulation


def test_advance_to_lands_exactly_on_a_time_the_step_does_not_divide(pendulum):
    pendulum.advance_to(0.0105)  # 10.5 steps of 1 ms
    assert pendulum.time == 0.0105
    assert pendulum.steps == 11
    with pytest.raises(ValueError):
        pendulum.advance_to(0.001)


def test_other_threads_run_while_stepping():
    sim = periflex.Simulation(SCENES / "pendulum.toml", overrides={"solver.dt": 1e-6, "solver.end_time": 100.0})
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    worker = threading.Thread(target=count)
    worker.start()
    try:
        start = time.monotonic()
        sim.step(200000)
        elapsed = time.monotonic() - start
    finally:
        stop.set()
        worker.join()
    # a thread that needs the GIL every millisecond kept running during the steps (with the GIL
    # held it would get it only at the look for Ctrl-C, every 50 ms)
    assert elapsed > 0.2, "too few steps to tell"
    assert len(ticks) > elapsed / 0.001 / 4


def test_ctrl_c_stops_between_steps_and_leaves_the_simulation_usable():
    sim = periflex.Simulation(SCENES / "pendulum.toml", overrides={"solver.dt": 1e-6, "solver.end_time": 100.0})
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        sim.step(10**9)  # hours of steps without the interrupt
    timer.join()
    assert time.monotonic() - start < 5.0
    stopped_at = sim.steps
    assert 0 < stopped_at < 10**9
    assert sim.time == pytest.approx(stopped_at * 1e-6, rel=1e-9)
    sim.step(5)
    assert sim.steps == stopped_at + 5
