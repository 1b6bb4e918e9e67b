"""Long C++ calls release the GIL: while one runs, other Python threads keep running and can enter C++ too.

Method (no sleeps, no races on thread start-up): a second thread repeats a short call (pure Python, or a
short C++ solve) and records the start and end time of each repetition; the main thread records the start and
end of one long C++ call. Repetitions that started and ended inside the middle half of the long call can only
exist if the long call let go of the GIL: a call that holds it stops every other thread from its first to its
last instruction (apart from a switch interval, 5 ms, at each end, far shorter than the quarter call trimmed
off each side). `test_the_method_detects_a_call_that_holds_the_gil` shows the measure reads zero for such a
call, so each test below can fail.
"""

import ctypes
import threading
import time

import numpy as np

import vibrissa
from calibrated import lasting
from vibrissa import WhiskerProperties

MIN_CALL_SECONDS = 0.1  # long calls must last this long for the middle half to dwarf the switch interval


def repetitions_inside(long_call, short_call):
    """Runs `long_call()` here while another thread repeats `short_call()`. Returns the long call's duration
    [s] and how many repetitions started and ended inside its middle half."""
    stop, running = threading.Event(), threading.Event()
    spans = []

    def repeat():
        running.set()
        while not stop.is_set():
            start = time.perf_counter()
            short_call()
            spans.append((start, time.perf_counter()))

    other = threading.Thread(target=repeat)
    other.start()
    running.wait()
    t0 = time.perf_counter()
    long_call()
    t1 = time.perf_counter()
    stop.set()
    other.join()
    quarter = 0.25 * (t1 - t0)
    inside = sum(1 for start, end in spans if t0 + quarter < start and end < t1 - quarter)
    return t1 - t0, inside


def pure_python():
    sum(range(50))


def batch_args(links=200):
    w = vibrissa.Whisker.from_parabola(0.03, 20.0, properties=WhiskerProperties(links=links))
    f = np.linspace(0.0, 1.0, 400)
    points = np.column_stack([0.02 - 0.002 * f, 0.004 + 0.002 * f, 0.001 * f])
    return w, points


def long_batch(w, points):
    """The points tiled until one batch solve of them (threads=1, cold) lasts at least twice MIN_CALL_SECONDS."""
    return lasting(lambda tiles: np.tile(points, (tiles, 1)),
                   lambda batch: vibrissa.solve_point_batch(w, batch, warm_start=False, threads=1),
                   1, 2 * MIN_CALL_SECONDS)


def undisturbed(measure, nominal_seconds, attempts=10):
    """`measure()` -> (seconds, count), repeated until the call took less than 1.5x its nominal time: on a
    loaded machine the OS may hold back the calling thread between taking its start time and entering the
    call, and then the middle half of [start, end] is not the middle half of the call."""
    for _ in range(attempts):
        seconds, inside = measure()
        if seconds < 1.5 * nominal_seconds:
            break
    return seconds, inside


def overlapping(measure, needed, attempts=5):
    """`measure()` -> (seconds, count), repeated until count >= `needed` (at most `attempts` times); returns the
    last. On a loaded machine the OS may keep the other thread off the cores for most of one long call; a call
    that holds the GIL gives 0 every time, so retrying cannot make a failing call pass."""
    for _ in range(attempts):
        seconds, inside = measure()
        if inside >= needed:
            break
    return seconds, inside


def test_the_method_detects_a_call_that_holds_the_gil():
    libc_holding = ctypes.PyDLL(None)   # PyDLL: the GIL stays held during foreign calls
    libc_releasing = ctypes.CDLL(None)  # CDLL: released
    w, points = batch_args()
    for short in (pure_python, lambda: vibrissa.solve_point_batch(w, points[:5], warm_start=False, threads=1)):
        seconds, inside = undisturbed(lambda: repetitions_inside(lambda: libc_holding.usleep(200_000), short), 0.2)
        assert seconds >= MIN_CALL_SECONDS and inside == 0
        seconds, inside = overlapping(lambda: repetitions_inside(lambda: libc_releasing.usleep(200_000), short), 1)
        assert seconds >= MIN_CALL_SECONDS and inside > 0


def test_python_keeps_running_during_a_batch():
    w, points = batch_args()
    batch = long_batch(w, points)
    seconds, inside = overlapping(lambda: repetitions_inside(
        lambda: vibrissa.solve_point_batch(w, batch, warm_start=False, threads=1), pure_python), 10)
    assert seconds >= MIN_CALL_SECONDS
    assert inside >= 10, (seconds, inside)


def test_two_threads_are_inside_the_solver_together():
    w, points = batch_args()
    batch = long_batch(w, points)
    seconds, inside = overlapping(lambda: repetitions_inside(
        lambda: vibrissa.solve_point_batch(w, batch, warm_start=False, threads=1),
        lambda: vibrissa.solve_point_batch(w, points[:5], warm_start=False, threads=1)), 3)
    assert seconds >= MIN_CALL_SECONDS
    # Short solves started and finished while the long batch was inside the solver: the calls overlapped.
    assert inside >= 3, (seconds, inside)


def test_single_solve_releases_the_gil():
    w = vibrissa.Whisker.from_parabola(0.03, 20.0, properties=WhiskerProperties(links=200_000))
    probing = vibrissa.SolveOptions(find_other_roots=True)  # a root scan: long enough at any engine speed
    seconds, inside = overlapping(lambda: repetitions_inside(
        lambda: vibrissa.solve_point(w, [0.02, 0.004, 0.001], options=probing), pure_python), 10)
    assert seconds >= MIN_CALL_SECONDS
    assert inside >= 10, (seconds, inside)


def test_pipeline_calls_release_the_gil():
    """synthesize_trial / analyze_trial / simulate_array run on a worker thread; the caller waits with the GIL
    released (python/src/interruptible.hpp)."""
    synthesis = lasting(lambda d: d, lambda d: vibrissa.synthesize_trial(duration=d), 2.0, 2 * MIN_CALL_SECONDS)
    seconds, inside = overlapping(
        lambda: repetitions_inside(lambda: vibrissa.synthesize_trial(duration=synthesis), pure_python), 10)
    assert seconds >= MIN_CALL_SECONDS and inside >= 10, (seconds, inside)
    trial = lasting(lambda d: vibrissa.synthesize_trial(duration=d), lambda t: vibrissa.analyze_trial(t, mu=0.48),
                    2.0, 2 * MIN_CALL_SECONDS)
    seconds, inside = overlapping(
        lambda: repetitions_inside(lambda: vibrissa.analyze_trial(trial, mu=0.48), pure_python), 10)
    assert seconds >= MIN_CALL_SECONDS and inside >= 10, (seconds, inside)
