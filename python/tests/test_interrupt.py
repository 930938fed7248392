"""Ctrl-C during a long run: SIGINT from a timer thread stops the run at its next step and
raises KeyboardInterrupt promptly; the GIL is free while it integrates."""

import os
import signal
import threading
import time

import pytest

import tumble

# A run of 10^8 steps (minutes) that keeps only its first and last rows.
LONG = dict(t_end=1e6, dt=0.01, every=10**9)


@pytest.fixture(autouse=True)
def sigint_raises_keyboard_interrupt():
    """Python's own SIGINT handler for each test. A process that starts with SIGINT ignored (a
    background job of a non-interactive shell, as some CI runners start their steps) keeps it
    ignored: the signal would never reach the run, and a 10^8-step run would go on for minutes."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def interrupt_after(seconds):
    timer = threading.Timer(seconds, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_sigint_during_a_long_simulation_raises_keyboard_interrupt_within_a_fraction_of_a_second():
    timer = interrupt_after(0.5)
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        tumble.simulate("free-hoop", **LONG)
    elapsed = time.monotonic() - start
    timer.join()
    # The signal arrives at 0.5 s; the run must be gone well within 0.5 s more.
    assert elapsed < 1.0, elapsed


def test_other_python_threads_run_while_a_simulation_integrates():
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.01)

    counter = threading.Thread(target=count)
    counter.start()
    timer = interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt):
        tumble.simulate("free-hoop", **LONG)
    stop.set()
    counter.join()
    timer.join()
    # With the GIL held for the whole run the counter would stall: it ticks every ~10 ms.
    assert len(ticks) > 20, len(ticks)


def test_sigint_during_a_sweep_raises_keyboard_interrupt_and_keeps_finished_points(tmp_path):
    sweep = {
        "scene": "free-hoop",
        "run": {"integrator": "gauss8", "dt": 0.01, "t_end": 1e5},
        "axes": [{"parameter": "omega0", "range": [1.0, 2.0], "count": 4}],
        "metrics": {"record": ["max_tilt"]},
    }
    timer = interrupt_after(0.5)
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        tumble.sweep(sweep, threads=2, output=tmp_path / "out", progress=False)
    assert time.monotonic() - start < 1.0
    timer.join()
    assert (tmp_path / "out" / "journal.csv").is_file()
