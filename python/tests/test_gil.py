"""Solves release the GIL: two Python threads are inside the C++ solver at the same time, and a pure-Python
loop keeps running while a long batch solves."""

import threading
import time

import numpy as np

import vibrissa
from vibrissa import WhiskerProperties


def long_batch_args():
    w = vibrissa.Whisker.from_parabola(0.03, 20.0, properties=WhiskerProperties(links=200))
    f = np.linspace(0.0, 1.0, 400)
    points = np.column_stack([0.02 - 0.002 * f, 0.004 + 0.002 * f, 0.001 * f])
    return w, points


def test_two_threads_are_inside_the_solver_together():
    w, points = long_batch_args()
    long_points = np.tile(points, (10, 1))  # ~4000 frames: long enough to still be running below
    a_done = threading.Event()

    def long_call():
        vibrissa.solve_point_batch(w, long_points, warm_start=False, threads=1)
        a_done.set()

    a = threading.Thread(target=long_call)
    a.start()
    time.sleep(0.05)  # with the GIL held by thread a, this thread could not wake before a returns
    woke_while_a_runs = not a_done.is_set()
    b_result = {}

    def short_call():
        b_result["r"] = vibrissa.solve_point_batch(w, points[:5], warm_start=False, threads=1)
        b_result["a_still_running"] = not a_done.is_set()

    b = threading.Thread(target=short_call)
    b.start()
    b.join()
    a.join()
    assert woke_while_a_runs
    # b entered and left the solver while a was inside it: the two calls overlapped.
    assert b_result["a_still_running"] and b_result["r"].converged.all()


def test_python_keeps_running_during_a_batch():
    w, points = long_batch_args()
    done = threading.Event()
    elapsed = {}

    def work():
        t0 = time.perf_counter()
        vibrissa.solve_point_batch(w, points, warm_start=False, threads=1)
        elapsed["batch"] = time.perf_counter() - t0
        done.set()

    t = threading.Thread(target=work)
    ticks = 0
    t.start()
    while not done.is_set():
        ticks += 1
    t.join()
    # A held GIL would freeze this loop for the whole batch; released, it spins freely meanwhile.
    assert ticks > 1000, (ticks, elapsed)


def test_single_solve_releases_the_gil():
    w = vibrissa.Whisker.from_parabola(0.03, 20.0, properties=WhiskerProperties(links=20000))
    done = threading.Event()
    ticks = 0

    def work():
        for _ in range(3):
            vibrissa.solve_point(w, [0.02, 0.004, 0.001])
        done.set()

    t = threading.Thread(target=work)
    t.start()
    while not done.is_set():
        ticks += 1
    t.join()
    assert ticks > 1000
