"""Sweep scaling (docs/sweeps.md, "Scale"): the same array sweep serially and on a LocalCluster of worker
processes; speed-up, Dask's overhead per task, memory of the client and the workers over the sweep, and the
sweep again with one worker killed mid-run (its results must be bit-identical to the serial ones).

    PYTHONPATH=build/python /usr/bin/python3 examples/sweep_scaling.py --runs 1000 --frames 200 --workers 2

Each run is the default array (31 right whiskers, a peg) with the peg moved and the whisking amplitude changed.
Measure on a quiet machine: the script prints the load average before and after, and cpu/wall of each phase.
"""

import argparse
import contextlib
import logging
import math
import os
import signal
import tempfile
import threading
import time

import numpy as np

import vibrissa


def grid_of(runs):
    """About `runs` runs: peg x [mm] × peg y [mm] × whisking amplitude [deg]."""
    side = max(1, round(runs ** (1 / 3)))
    last = math.ceil(runs / side / side)
    return {"objects.0.point_mm.0": [float(v) for v in np.linspace(16, 24, side)],
            "objects.0.point_mm.1": [float(v) for v in np.linspace(-10, -6, side)],
            "whisking.amplitude_deg": [float(v) for v in np.linspace(20, 40, last)]}


class Memory:
    """RSS of this process and of its child processes (the workers), sampled every `period` s."""

    def __init__(self, period=0.25):
        import psutil
        self.me, self.samples, self.period, self._stop = psutil.Process(), [], period, threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        import psutil
        while not self._stop.is_set():
            workers = []
            for child in self.me.children(recursive=True):
                with contextlib.suppress(psutil.NoSuchProcess):
                    workers.append(child.memory_info().rss)
            self.samples.append((time.monotonic(), self.me.memory_info().rss, workers))
            self._stop.wait(self.period)

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self.thread.join()

    def report(self):
        client = np.array([s[1] for s in self.samples]) / 2**20
        worker = [max(s[2]) / 2**20 for s in self.samples if s[2]]
        third = max(1, len(client) // 3)
        return (f"client RSS {client[:third].mean():.0f} MB (first third) -> {client[-third:].mean():.0f} MB (last "
                f"third), peak {client.max():.0f} MB; largest worker RSS {np.mean(worker[:third]):.0f} -> "
                f"{np.mean(worker[-third:]):.0f} MB, peak {max(worker):.0f} MB ({len(client)} samples)")


def timed(label, call):
    wall, cpu = time.perf_counter(), time.process_time()
    out = call()
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    print(f"{label}: {wall:.2f} s (client cpu {cpu:.2f} s)", flush=True)
    return out, wall


def same_bits(a, b):
    for name in a.variables:
        x, y = a[name].values, b[name].values
        if x.dtype.kind == "f":
            x, y = x.view(np.uint64), y.view(np.uint64)
        if x.shape != y.shape or not np.array_equal(x, y):
            return False
    return set(a.variables) == set(b.variables)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=1000)
    parser.add_argument("--frames", type=int, default=200)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--chunk-size", type=int)
    parser.add_argument("--variables", nargs="*", default=None, help="outputs to keep (default: all 27)")
    parser.add_argument("--overhead-tasks", type=int, default=400, help="tasks of the overhead measurement")
    args = parser.parse_args()
    from dask.distributed import Client, LocalCluster

    base = vibrissa.default_array_config()
    base["time"]["frames"] = args.frames
    grid = grid_of(args.runs)
    runs = math.prod(len(v) for v in grid.values())
    whiskers = len(vibrissa.simulate_array(dict(base, time=dict(base["time"], frames=2))).whisker)
    print(f"load average {os.getloadavg()}; {os.cpu_count()} CPUs; {runs} array runs of {whiskers} whiskers x "
          f"{args.frames} frames; variables: {args.variables or 'all'}", flush=True)
    options = dict(grid=grid, variables=args.variables, chunk_size=args.chunk_size)
    with tempfile.TemporaryDirectory() as scratch:
        serial, serial_wall = timed("serial (this process, one core)", lambda: vibrissa.sweep(
            "array", base, out=f"{scratch}/serial", scheduler="serial", **options))

        def cluster():
            return LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None,
                                silence_logs=logging.ERROR, local_directory=scratch)
        (local, client), start = timed(f"LocalCluster of {args.workers} worker processes: start",
                                       lambda: (lambda c: (c, Client(c)))(cluster()))
        with Memory() as memory:
            parallel, wall = timed(f"the sweep on it", lambda: vibrissa.sweep(
                "array", base, out=f"{scratch}/dask", client=client, **options))
        print(f"speed-up {serial_wall / wall:.2f} (with the cluster's start: {serial_wall / (wall + start):.2f}); "
              f"bit-identical to serial: {same_bits(serial, parallel)}", flush=True)
        print(memory.report(), flush=True)
        chunks = len(list((__import__("pathlib").Path(scratch) / "dask" / "chunks").iterdir()))
        print(f"{chunks} tasks of {math.ceil(runs / chunks)} runs", flush=True)

        # One worker killed (SIGKILL) once a third of the runs are done; its chunk runs again elsewhere.
        pids = client.run(os.getpid)
        killed = []

        def kill(done, total):
            if not killed and done >= total // 3:
                busy = [a for a, keys in client.processing().items() if keys and a in pids]
                if busy:
                    killed.append(pids[busy[0]])
                    os.kill(pids[busy[0]], signal.SIGKILL)
        again, _ = timed("the sweep with a worker killed mid-run", lambda: vibrissa.sweep(
            "array", base, out=f"{scratch}/killed", client=client, progress=kill, **options))
        print(f"killed worker pid {killed}; results bit-identical to serial: {same_bits(serial, again)}", flush=True)

        # Dask's cost per task: near-empty tasks (one cold solve each) against the same solves in this process.
        case = {"whisker": {"length": 0.03, "curvature": 20.0},
                "load": {"mode": "point", "point": [0.02, 0.005, 0.0]}}
        tiny = {"load.point.1": [float(v) for v in np.linspace(0.004, 0.006, args.overhead_tasks)]}
        _, alone = timed(f"{args.overhead_tasks} solve runs, serial", lambda: vibrissa.sweep(
            "solve", case, grid=tiny, scheduler="serial", chunk_size=1))
        _, tasks = timed(f"the same as {args.overhead_tasks} tasks", lambda: vibrissa.sweep(
            "solve", case, grid=tiny, client=client, chunk_size=1))
        print(f"overhead per task: {1e3 * (tasks * args.workers - alone) / args.overhead_tasks:.1f} ms of worker "
              f"time ({1e3 * tasks / args.overhead_tasks:.1f} ms of wall time per task with {args.workers} workers)")
        client.close()
        local.close()
    print(f"load average {os.getloadavg()}")


if __name__ == "__main__":
    main()
