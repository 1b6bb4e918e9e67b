"""Holding a Dask worker inside a sweep's chunk, so a test can kill it while it is certainly running one.

`hold_chunks(folder)` runs on every worker (Client.run; this module is pickled by value, so workers need not
import it): it wraps vibrissa.sweep_runs.run_chunk, which the sweep's tasks look up there when they are
unpickled on the worker. A wrapped chunk writes `started-<pid>` into `folder`, then waits while
`folder/hold` exists (at most HOLD_S), then runs the real run_chunk unchanged, so results stay those of the
runs. A worker started later (the Nanny's replacement of a killed one) is not wrapped."""

import os
import pathlib
import time

HOLD_S = 60.0


def hold_chunks(folder):
    import vibrissa.sweep_runs as sweep_runs
    original = sweep_runs.run_chunk
    folder = pathlib.Path(folder)

    def held(*args, **kwargs):
        (folder / f"started-{os.getpid()}").touch()
        stop = time.monotonic() + HOLD_S
        while (folder / "hold").exists() and time.monotonic() < stop:
            time.sleep(0.01)
        return original(*args, **kwargs)

    sweep_runs.run_chunk = held
    return os.getpid()
