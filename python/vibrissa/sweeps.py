"""Parameter sweeps on Dask: many array, trial or solve runs, one labelled xarray Dataset (docs/sweeps.md).

:func:`sweep` runs a grid (or a list) of runs of one kind, each the base configuration with some values
changed, as chunks of runs on a ``dask.distributed`` cluster: a ``LocalCluster`` of worker processes on this
machine by default, or any scheduler (``scheduler="tcp://host:8786"``). The client alone writes the results,
one file per finished chunk and an index (vibrissa.sweep_store), so an interrupted sweep resumes where it
stopped, a task computed twice is stored once, and a lost worker only costs its running chunk, which Dask
runs again elsewhere. Results are bit-identical to the same runs made one by one (``scheduler="serial"``
does exactly that, in this process). The CLI form is ``vibrissa sweep CONFIG`` (= ``python -m vibrissa sweep``).
"""

import itertools
import json
import logging
import math
import os
import pathlib
import signal
import sys
import tempfile
import threading
import time
import warnings

import numpy as np

from .sweep_runs import KINDS, build_id, configured, parameter_path, run_chunk
from .sweep_store import SweepStore

__all__ = ["sweep", "main"]

MAX_RUNS = 1_000_000  # index.json and the task graph stay small (docs/sweeps.md, "Scale")
CHUNKS_PER_WORKER = 16  # default chunking: a short tail when the last tasks finish, few enough to keep overhead small


def _base_config(kind, base, relative_to):
    """The base configuration as a dict: a dict, a JSON file, or None (array: the built-in default)."""
    if base is None:
        if kind == "array":
            from .pipeline import default_array_config
            return default_array_config()
        return {}
    if isinstance(base, (str, os.PathLike)):
        path = pathlib.Path(relative_to, base)
        try:
            base = json.loads(path.read_text())
        except (OSError, json.JSONDecodeError) as error:
            raise ValueError(f"base: cannot read {path}: {error}") from None
        relative_to = path.parent
    if not isinstance(base, dict):
        raise TypeError(f"base must be a dict, a path to a JSON file or None, got {type(base).__name__}")
    base = json.loads(json.dumps(base, default=_json_default))  # a plain copy
    if kind == "array":
        # Keys the base omits take the built-in default's values, as in `vibrissa array` (docs/array.md), so a
        # swept path such as objects.0.point_mm.0 finds the default's peg.
        from .pipeline import default_array_config
        base = _over(default_array_config(), base)
    # Files named in the configuration are found relative to the configuration's folder (the current one for a
    # dict), as the CLI's readers find them: the same C++ rule (io::resolve_input_paths: a morphology table,
    # meshes), so the runs find them from any worker's directory.
    if kind in ("array", "solve"):
        from . import _vibrissa
        base = json.loads(_vibrissa._resolve_input_paths(json.dumps(base), str(pathlib.Path(relative_to).resolve())))
    if kind == "trial" and isinstance(base.get("trial"), str):
        base["trial"] = str(pathlib.Path(relative_to, base["trial"]).resolve())
    return base


def _over(default, given):
    """`given` laid over `default`: objects merged key by key, anything else (lists too) taken from `given`."""
    if not isinstance(default, dict) or not isinstance(given, dict):
        return given
    return {**default, **{key: _over(default.get(key), value) for key, value in given.items()}}


def _json_default(value):
    import numpy as np
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"a value of type {type(value).__name__} is not JSON")


def _plan(grid, runs):
    """(parameters {path: values} or None, [{path: value} per run])."""
    if grid is not None and runs is not None:
        raise ValueError("give grid (every combination of the values) or runs (a list), not both")
    if runs is not None:
        runs = json.loads(json.dumps(list(runs), default=_json_default))
        if not runs or not all(isinstance(r, dict) for r in runs):
            raise ValueError("runs must be a non-empty list of {parameter path: value} objects")
        for run in runs:
            for path in run:
                parameter_path(path)
        return None, runs
    grid = json.loads(json.dumps(dict(grid or {}), default=_json_default))
    for path, values in grid.items():
        parameter_path(path)
        if not isinstance(values, list) or not values:
            raise ValueError(f"grid: parameter {path!r} needs a non-empty list of values, got {values!r}")
        if len(set(map(json.dumps, values))) != len(values):
            raise ValueError(f"grid: parameter {path!r} repeats a value: {values!r}")
    n = math.prod(len(v) for v in grid.values())
    if n > MAX_RUNS:
        raise ValueError(f"grid: {n} runs, more than the {MAX_RUNS} of one sweep (docs/sweeps.md, \"Scale\")")
    runs = [dict(zip(grid, combination)) for combination in itertools.product(*grid.values())]
    return grid, runs


def _check_configurations(kind, base, runs, on_error="raise"):
    """Every run's configuration is read before anything runs (array configs and cases by the C++ readers), so a
    bad value fails at once with the run and field named, not hours into the sweep. With on_error="record" the
    refused runs are returned ([(index, message)]; they fail again, recorded, when they run) and only a sweep
    whose every run is refused raises."""
    from . import _vibrissa
    from .case import load_case
    refused = []
    for index, overrides in enumerate(runs):
        try:
            config = configured(base, overrides)
            if kind == "array":
                _vibrissa._check_array_config(json.dumps(config))
            elif kind == "solve":
                load_case(config)
        except (ValueError, TypeError, KeyError) as error:
            where = ", ".join(f"{p}={v!r}" for p, v in overrides.items())
            message = f"sweep run {index} ({where or 'the base configuration'}): {error}"
            if on_error != "record":
                raise ValueError(message) from None
            refused.append((index, message))
    if refused and len(refused) == len(runs):
        raise ValueError(refused[0][1])
    return refused


def sweep(kind, base=None, *, grid=None, runs=None, out=None, variables=None, scheduler=None, workers=None,
          chunk_size=None, progress=None, client=None, on_error="record"):
    """Runs every combination of `grid` (or each of `runs`) of `kind` and returns the results as an
    ``xarray.Dataset`` with the swept parameters as dimensions (docs/sweeps.md).

    kind: "array" (``simulate_array``; `base` an array config), "trial" (`base` {"synth": synthesize_trial
    options} or {"trial": path}, plus {"analysis": analyze_trial options}) or "solve" (`base` a case of
    ``vibrissa solve``). base: a dict, a JSON file or None (array: the built-in default).
    grid: {path: [values]}, a path naming a value of the configuration ("head.pitch_deg",
    "objects.0.point_mm.1", "analysis.mu"); the result has one dimension per path (first path slowest).
    runs: instead, a list of {path: value}: dimension "run", each path a coordinate along it.
    out: folder of the results (sweep.json, chunks/, index.json, sweep.nc); rerunning the same sweep into it
    resumes it. None: a temporary folder, removed after loading the results into memory.
    variables: names of the outputs to keep (default: all; array runs: 27 per pitch, whisker and frame).
    scheduler: None (a LocalCluster of `workers` processes, default os.cpu_count()), a scheduler address
    ("tcp://host:8786"; its workers need this vibrissa build) or "serial" (this process, no Dask).
    client: an existing ``dask.distributed.Client`` (then `scheduler` and `workers` are not used).
    chunk_size: runs per task (default: about 16 tasks per worker). progress(done, total) counts runs.

    Returns ``xarray.open_dataset(out/"sweep.nc")`` (lazy; ``.load()`` reads it into memory). Ctrl-C stops
    the sweep (the cluster it started is shut down, the finished chunks stay in `out`) and raises
    KeyboardInterrupt.
    on_error: "record" (default) goes on after a run that fails or whose configuration is refused: its values
    are NaN (integer outputs then read as float), the variable ``error`` says why ("" for the runs that ran) and one UserWarning
    gives the count; a sweep whose every run fails raises. "raise" stops at the first such run with its error,
    naming the run and its parameters (the behaviour before issue 23).
    """
    if on_error not in ("record", "raise"):
        raise ValueError(f"on_error must be one of ['record', 'raise'], got {on_error!r}")
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {list(KINDS)}, got {kind!r}")
    if variables is not None:
        variables = [str(v) for v in variables]
    relative_to = pathlib.Path.cwd()
    base = _base_config(kind, base, relative_to)
    parameters, run_list = _plan(grid, runs)
    _check_configurations(kind, base, run_list, on_error)
    if out is None:
        with tempfile.TemporaryDirectory(prefix="vibrissa-sweep-") as folder, \
                _sweep(kind, base, parameters, run_list, folder, variables, scheduler, workers, chunk_size,
                       progress, client, on_error) as result:
            return _warn_failed(result.load())
    return _warn_failed(_sweep(kind, base, parameters, run_list, out, variables, scheduler, workers, chunk_size,
                               progress, client, on_error))


def _warn_failed(result):
    if "error" in result.variables:
        messages = [m for m in np.asarray(result["error"].values).ravel().tolist() if m]
        if messages:
            warnings.warn(f"sweep: {len(messages)} of {result['error'].size} runs failed (their values are NaN; "
                          f"the variable 'error' says why); the first: {messages[0]}", UserWarning, stacklevel=3)
    return result


def _sweep(kind, base, parameters, runs, out, variables, scheduler, workers, chunk_size, progress, client,
           on_error="raise"):
    import xarray as xr

    spec = {"kind": kind, "base": base, "grid": parameters, "runs": None if parameters is not None else runs,
            "variables": variables}
    if on_error == "record":  # part of what the folder holds (the error variable); absent: as before issue 23
        spec["on_error"] = "record"
    out = pathlib.Path(out)
    stored = _stored_chunk_size(out)
    if chunk_size is None:
        chunk_size = stored
    with _Cluster(scheduler, workers, client) as cluster:
        if chunk_size is None:
            chunk_size = max(1, math.ceil(len(runs) / (CHUNKS_PER_WORKER * cluster.workers)))
        if not isinstance(chunk_size, int) or chunk_size < 1:
            raise ValueError(f"chunk_size must be a positive integer, got {chunk_size!r}")
        store = SweepStore(out, dict(spec, chunk_size=chunk_size))
        chunks = [list(enumerate(runs))[i:i + chunk_size] for i in range(0, len(runs), chunk_size)]
        todo = [c for c in range(len(chunks)) if c not in store.finished()]
        done_runs = sum(len(chunks[c]) for c in store.finished() if c < len(chunks))
        if progress is not None:
            progress(done_runs, len(runs))
        if todo or not store.result_path.is_file():
            for chunk, result in cluster.results(kind, base, chunks, todo, variables, _digest(spec, chunk_size),
                                                 on_error):
                if result["build"] != build_id():
                    raise RuntimeError(f"a worker runs vibrissa {result['build']}, this process {build_id()}: "
                                       "install the same build on every worker (results must be bit-identical)")
                store.add(chunk, result)
                done_runs += len(chunks[chunk])
                if progress is not None:
                    progress(done_runs, len(runs))
            store.assemble(parameters, runs, {"format": "vibrissa-sweep", "kind": kind, "vibrissa": build_id(),
                                              "sweep": json.dumps(dict(spec, chunk_size=chunk_size))})
    from .viewer import _register_accessor
    _register_accessor()  # result.vibrissa.view(): the viewer of the sweep (docs/viewer.md)
    return xr.open_dataset(store.result_path, engine="h5netcdf")


def _stored_chunk_size(out):
    try:
        return json.loads((pathlib.Path(out) / "sweep.json").read_text()).get("chunk_size")
    except (OSError, ValueError):
        return None


def _digest(spec, chunk_size):
    import hashlib
    return hashlib.sha256(json.dumps(dict(spec, chunk_size=chunk_size), sort_keys=True).encode()).hexdigest()[:12]


class _Cluster:
    """Where the chunks run: this process ("serial"), a LocalCluster started here (and shut down on leaving, also
    on Ctrl-C), a scheduler address, or a caller's Client."""

    def __init__(self, scheduler, workers, client):
        self.scheduler, self.requested, self.client, self._own = scheduler, workers, client, []
        self._scratch = None  # the workers' local directory, removed with the cluster
        if workers is not None and (not isinstance(workers, int) or workers < 1):
            raise ValueError(f"workers must be a positive integer, got {workers!r}")

    def __enter__(self):
        if self.client is None and self.scheduler != "serial":
            from dask.distributed import Client, LocalCluster
            if self.scheduler is None:
                # Workers ignore SIGINT: Ctrl-C reaches the whole process group, and it is the client that
                # stops the sweep and shuts the cluster down.
                self._scratch = tempfile.TemporaryDirectory(prefix="vibrissa-dask-")
                main = threading.current_thread() is threading.main_thread()  # signals are the main thread's
                previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
                try:
                    cluster = LocalCluster(n_workers=self.requested or os.cpu_count() or 1, threads_per_worker=1,
                                           processes=True, dashboard_address=None, silence_logs=logging.ERROR,
                                           local_directory=self._scratch.name)
                finally:
                    if main:
                        signal.signal(signal.SIGINT, previous)
                self._own.append(cluster)
                self.client = Client(cluster)
            else:
                self.client = Client(self.scheduler, timeout=30)
            self._own.insert(0, self.client)
        return self

    def __exit__(self, *exc):
        for thing in self._own:  # the client first, then the cluster it talks to
            try:
                thing.close()
            except Exception:  # shutting down after an error: report that error, not this one
                pass
        if self._scratch is not None:
            self._scratch.cleanup()
        return False

    @property
    def workers(self):
        if self.client is None:
            return 1
        return max(1, len(self.client.scheduler_info()["workers"]))

    def results(self, kind, base, chunks, todo, variables, digest, on_error="raise"):
        """Yields (chunk, result) as chunks finish; on leaving early (an error, Ctrl-C) cancels the rest."""
        if self.client is None:
            for chunk in todo:
                yield chunk, run_chunk(kind, base, chunks[chunk], variables, on_error)
            return
        from dask.distributed import as_completed
        futures = {self.client.submit(run_chunk, kind, base, chunks[c], variables, on_error,
                                      key=f"vibrissa-sweep-{digest}-{c}", pure=False): c for c in todo}
        try:
            for future in as_completed(futures):
                result = future.result()  # raises the run's error, if it failed
                yield futures[future], result
                future.release()  # the worker may forget it
        finally:
            self.client.cancel([f for f in futures if not f.done()])


# --- command line: vibrissa sweep CONFIG ------------------------------------------------------------------

def _progress_bar(stream):
    start = time.monotonic()

    def show(done, total):
        if not stream.isatty():
            return
        width = 30
        filled = width * done // max(total, 1)
        stream.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} runs, "
                     f"{time.monotonic() - start:.0f} s")
        stream.flush()
    return show


def _newline_after_bar():  # the progress bar is drawn on a terminal only: end its line there
    return "\n" if sys.stderr.isatty() else ""


def main(argv=None):
    """`vibrissa sweep CONFIG [--out DIR] [--scheduler ADDRESS|serial] [--workers N] [--chunk-size N]`."""
    import argparse
    parser = argparse.ArgumentParser(
        prog="vibrissa sweep",
        description="Parameter sweeps of array, trial or solve runs on Dask: a LocalCluster of worker processes "
                    "by default, any scheduler with --scheduler. The results go to OUT/sweep.nc (netCDF-4, "
                    "xarray.open_dataset) chunk by chunk; rerunning an interrupted sweep resumes it "
                    "(docs/sweeps.md).")
    parser.add_argument("config", help="sweep configuration (JSON): kind, base, grid or runs, variables, chunk_size")
    parser.add_argument("--out", help="output folder (default: the config's 'out', else sweep_results)")
    parser.add_argument("--scheduler", help="scheduler address (tcp://host:8786) or 'serial' (this process)")
    parser.add_argument("--workers", type=int, help="worker processes of the local cluster (default: all cores)")
    parser.add_argument("--chunk-size", type=int, help="runs per task (default: about 16 tasks per worker)")
    args = parser.parse_args(argv)

    def stop(signum, _frame):  # SIGTERM/SIGHUP: unwind like Ctrl-C, so the cluster is shut down
        raise KeyboardInterrupt
    for sig in (signal.SIGTERM, signal.SIGHUP):
        if signal.getsignal(sig) is not signal.SIG_IGN:
            signal.signal(sig, stop)

    path = pathlib.Path(args.config)
    try:
        try:
            config = json.loads(path.read_text())
        except json.JSONDecodeError as error:
            raise ValueError(f"{path}: not valid JSON: {error}") from None
        if not isinstance(config, dict):
            raise ValueError("the sweep configuration must be a JSON object")
        known = {"kind", "base", "grid", "runs", "variables", "chunk_size", "out", "workers", "scheduler", "on_error"}
        unknown = sorted(set(config) - known)
        if unknown:
            raise ValueError(f"unknown key(s) {unknown} (expected {sorted(known)})")
        if "kind" not in config:
            raise ValueError("missing key 'kind' (array, trial or solve)")
        if config["kind"] not in KINDS:
            raise ValueError(f"kind must be one of {list(KINDS)}, got {config['kind']!r}")
        base = config.get("base")
        if isinstance(base, str):
            base = path.parent / base
        elif isinstance(base, dict) and config["kind"] in ("array", "trial"):
            base = _base_config(config["kind"], base, path.parent)
        out = args.out or config.get("out") or "sweep_results"
        if args.out is None and config.get("out"):
            out = path.parent / config["out"]
        scheduler = args.scheduler or config.get("scheduler")
        chunk_size = args.chunk_size if args.chunk_size is not None else config.get("chunk_size")
        workers = args.workers if args.workers is not None else config.get("workers")
        for name, value in (("workers", workers), ("chunk_size", chunk_size)):
            if value is not None and (not isinstance(value, int) or isinstance(value, bool) or value < 1):
                raise ValueError(f"{name} must be a positive integer, got {value!r}")
        total = len(_plan(config.get("grid"), config.get("runs"))[1])
        where = ("this process" if scheduler == "serial" else f"scheduler {scheduler}" if scheduler
                 else f"a local cluster of {workers or os.cpu_count()} worker processes")
        print(f"vibrissa sweep: {total} {config['kind']} runs on {where} -> {out}", flush=True)
        started = time.monotonic()
        result = sweep(config["kind"], base, grid=config.get("grid"), runs=config.get("runs"), out=out,
                       variables=config.get("variables"), scheduler=scheduler, workers=workers,
                       chunk_size=chunk_size, progress=_progress_bar(sys.stderr),
                       on_error=config.get("on_error", "record"))
    except KeyboardInterrupt:
        print(f"\nvibrissa sweep: interrupted; the finished chunks are in {out}: run the same command to resume",
              file=sys.stderr)
        return 130
    except (OSError, ValueError, TypeError, RuntimeError) as error:
        print(f"{_newline_after_bar()}vibrissa sweep: error: {error}", file=sys.stderr)
        return 1
    if sys.stderr.isatty():
        sys.stderr.write("\n")
    dims = ", ".join(f"{d} {n}" for d, n in result.sizes.items())
    print(f"wrote {pathlib.Path(out) / 'sweep.nc'} ({dims}) in {time.monotonic() - started:.1f} s")
    result.close()
    return 0
