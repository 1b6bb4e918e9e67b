"""Workloads sized to the machine: tests that need a call to last long enough (to see the GIL released, to
interrupt it) double the work until it does, so they hold at any engine speed."""

import time


def lasting(make, run, size, seconds):
    """`make(size)` with `size` doubled until `run(make(size))` takes at least `seconds` here; returns what
    `make` made then."""
    while True:
        work = make(size)
        start = time.perf_counter()
        run(work)
        if time.perf_counter() - start >= seconds:
            return work
        size *= 2
