#!/usr/bin/env python3
"""Ratios of every benchmark to BM_Forward from one run of a Google Benchmark program (issue 13: the engine's
targets are ratios to the forward evaluation, so they hold on a loaded machine as long as they come from one
run). Usage: build/bench/bench_solve --benchmark_format=json [--benchmark_repetitions=5] | bench/ratios.py
With repetitions, the medians are used."""
import json
import sys


def main() -> int:
    data = json.load(sys.stdin)
    times = {}
    for b in data["benchmarks"]:
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        name = b.get("run_name", b["name"])
        if b.get("run_type") == "aggregate" or name not in times:
            times[name] = b["cpu_time"] * {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b["time_unit"]]
    if "BM_Forward" not in times:
        print("BM_Forward is not in the run", file=sys.stderr)
        return 1
    forward = times["BM_Forward"]
    print(f"{'benchmark':32s} {'time [us]':>10s} {'/ forward':>10s}")
    for name, t in times.items():
        print(f"{name:32s} {t / 1e3:10.2f} {t / forward:10.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
