#!/usr/bin/env python3
"""CPU time of `vibrissa trial`'s figures, measured so that other work on the machine changes it little.

usage: figure_times.py FRAMES.h5 SUMMARY.json [--all] [--repeat N]

Wall time on a shared machine says more about the other processes than about the figures, so this reports CPU
times (user + sys):
  * each figure drawn and saved alone in this process (the best of --repeat runs, after one to warm up);
  * one run of figures/trial_figures.py as `vibrissa trial` runs it: the parent's start-up (interpreter,
    imports, data) and each forked figure process (from wait4), and their sum along the longest path: start-up
    plus the slowest figure process, which is what two idle cores would take (`vibrissa trial` overlaps the
    start-up with its solve, docs/trials.md).
docs/performance.md, "Figures and the viewer", gives the numbers and the commands.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

FIGURES = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "figures")

# One run of trial_figures.main() in a fresh interpreter, reporting the CPU of the parent up to the fork and of
# each figure process (os.waitpid is wrapped to read the children's rusage).
ONE_RUN = r"""
import json, os, sys, time
sys.path.insert(0, sys.argv[1])
import style, trial_figures
children, start = [], {}
def waitpid(pid, options):
    pid, status, usage = os.wait4(pid, options)
    children.append(usage.ru_utime + usage.ru_stime)
    return pid, status
os.waitpid = waitpid
save_all = style.save_all
def timed_save_all(*args, **kwargs):
    t = os.times()
    start["cpu"] = t.user + t.system
    return save_all(*args, **kwargs)
style.save_all = timed_save_all
trial_figures.main(sys.argv[2:])
print(json.dumps({"start_up": start["cpu"], "children": sorted(children)}))
"""


def per_figure(frames, summary, all_figures, repeat):
    sys.path.insert(0, FIGURES)
    import style  # noqa: E402
    import trial_figures  # noqa: E402
    style.apply()
    d = trial_figures.load(frames)
    with open(summary) as f:
        s = json.load(f)
    times = {}
    with tempfile.TemporaryDirectory() as out:
        for name, draw in trial_figures.builders(d, s, all_figures=all_figures).items():
            best = float("inf")
            for _ in range(repeat + 1):
                t = time.process_time()
                style.save(draw(), os.path.join(out, name))
                best = min(best, time.process_time() - t)
            times[name] = best
    return times


def main():
    p = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    p.add_argument("frames_h5")
    p.add_argument("summary_json")
    p.add_argument("--all", action="store_true", help="also the figures left out by default")
    p.add_argument("--repeat", type=int, default=3, help="runs per figure (the best counts)")
    args = p.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f}")
    times = per_figure(args.frames_h5, args.summary_json, args.all, args.repeat)
    for name, t in times.items():
        print(f"  {name:40s} {t:.3f} s")
    print(f"  {'all, one after the other':40s} {sum(times.values()):.3f} s")
    with tempfile.TemporaryDirectory() as out:
        run = subprocess.run([sys.executable, "-c", ONE_RUN, FIGURES, args.frames_h5, args.summary_json, out]
                             + (["--all"] if args.all else []), capture_output=True, text=True, check=True)
    r = json.loads(run.stdout.strip().splitlines()[-1])
    kids = ", ".join(f"{c:.3f}" for c in r["children"])
    print(f"trial_figures.py: start-up {r['start_up']:.3f} s, figure processes {kids} s, "
          f"longest path {r['start_up'] + max(r['children']):.3f} s CPU")


if __name__ == "__main__":
    main()
