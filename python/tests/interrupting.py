"""Delivering Ctrl-C (SIGINT) to this process while a long vibrissa call runs, and timing its effect."""

import os
import signal
import threading
import time

import pytest


def _interrupt_once(call, delay, with_progress):
    """Runs `call(progress)` and sends SIGINT to this process `delay` s after the call started (with_progress:
    after its first progress report, and the report seen then must be short of the total). Returns the
    seconds from the moment the signal was due to the KeyboardInterrupt (a call holding the GIL would also
    hold up the timer thread, so the signal's own time stamp is not enough). Without a progress callback no
    Python code runs during the call, so only the binding's own signal check can raise it."""
    sent, seen, armed = {}, [], []

    def send():
        sent["seen"] = list(seen)
        sent["time"] = time.perf_counter()
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(delay, send)

    def progress(done, total):
        seen.append((done, total))
        if len(seen) == 1:
            armed.append(time.perf_counter())
            timer.start()

    try:
        if not with_progress:
            armed.append(time.perf_counter())
            timer.start()
        call(progress if with_progress else None)
    except KeyboardInterrupt:
        latency = time.perf_counter() - (armed[0] + delay)
        assert sent["time"] - armed[0] >= delay
        timer.join()
        if with_progress:
            done, total = sent["seen"][-1]
            assert done < total, "the call must still have been running when the signal came"
        return latency
    try:
        timer.cancel()
        timer.join()
        time.perf_counter()  # a signal sent meanwhile is raised here
    except KeyboardInterrupt:
        pass
    pytest.fail("the call ended before the signal: make it longer")


def interrupt(call, delay, with_progress, within=0.5, attempts=3):
    """_interrupt_once up to `attempts` times until the latency is below `within` s; returns the smallest. A loaded
    machine can keep this process off the cores for a while after the signal; a call that does not check for
    signals runs to its end every time, so retrying cannot make it pass."""
    best = float("inf")
    for _ in range(attempts):
        best = min(best, _interrupt_once(call, delay, with_progress))
        if best < within:
            break
    return best
