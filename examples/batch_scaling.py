#!/usr/bin/env python3
"""Measures how batch solves scale with threads (docs/python.md, "Performance").

    PYTHONPATH=build/python /usr/bin/python3 examples/batch_scaling.py [--frames 2000] [--repeats 3]

Workloads: contact-point mode on F independent frames (warm_start=False: frames in parallel), and on S
series of F/S frames with warm starts (series in parallel). Reports the best wall time of `--repeats` runs
for 1, 2, ... up to vibrissa.max_threads() threads, and checks that every thread count gives identical
results.
"""

import argparse
import os
import time

import numpy as np

import vibrissa


def best_time(fn, repeats):
    """Best wall time of `repeats` runs, with the process CPU time of that run (cpu/wall = cores kept busy)."""
    best, cpu, result = float("inf"), 0.0, None
    for _ in range(repeats):
        c0, t0 = time.process_time(), time.perf_counter()
        result = fn()
        wall = time.perf_counter() - t0
        if wall < best:
            best, cpu = wall, time.process_time() - c0
    return best, cpu, result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=2000)
    parser.add_argument("--series", type=int, default=16)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--max-threads", type=int, default=vibrissa.max_threads())
    args = parser.parse_args()

    whisker = vibrissa.Whisker.from_parabola(0.03, 20.0)  # 100 links, spec §2.1 defaults
    rng = np.random.default_rng(0)
    F = args.frames
    u = np.linspace(0.0, 1.0, F)
    points = np.column_stack([0.02 - 0.004 * u, 0.004 + 0.002 * u, 0.001 * np.sin(6 * u)])
    points += rng.normal(scale=1e-5, size=points.shape)
    series = points.reshape(args.series, F // args.series, 3)

    counts = sorted({1, 2, args.max_threads} | {2 ** k for k in range(0, 5) if 2 ** k <= args.max_threads})
    print(f"load average {os.getloadavg()[0]:.2f}; cpus={os.cpu_count()} OMP max_threads={vibrissa.max_threads()} frames={F} links={whisker.links}")
    for label, kwargs in (("independent frames (warm_start=False)", dict(points_W=points, warm_start=False)),
                          (f"{args.series} series, warm starts", dict(points_W=series, warm_start=True))):
        print(label)
        base_time, base = None, None
        for n in counts:
            t, cpu, r = best_time(lambda: vibrissa.solve_point_batch(whisker, threads=n, **kwargs), args.repeats)
            if base is None:
                base_time, base = t, r
            else:
                assert np.array_equal(base.force_W, r.force_W) and np.array_equal(base.status, r.status)
            print(f"  threads={n:2d}  {t * 1e3:8.1f} ms  {F / t:9.0f} frames/s  speed-up {base_time / t:4.2f}"
                  f"  cpu/wall {cpu / t:4.2f}")
    print(f"load average before the loop: {os.getloadavg()[0]:.2f}")
    loop_t, _, _ = best_time(lambda: [vibrissa.solve_point(whisker, p) for p in points], 1)
    print(f"python loop of solve_point: {loop_t * 1e3:8.1f} ms  {F / loop_t:9.0f} frames/s")


if __name__ == "__main__":
    main()
