"""The runs of a sweep (docs/sweeps.md): one configuration in, labelled arrays out, on any worker.

A task of a sweep is a chunk of runs, :func:`run_chunk`, executed by a Dask worker (or in the calling process
for ``scheduler="serial"``). Each run applies its parameter values to the base configuration
(:func:`configured`) and calls the package's own API, single-threaded, exactly as a user would:
``simulate_array`` (kind ``"array"``), ``synthesize_trial``/``read_trial`` + ``analyze_trial`` (``"trial"``) or
``load_case(...).solve()`` (``"solve"``), so a sweep gives the numbers of the same calls made one by one.
"""

import copy
import functools
import hashlib
import math
import pathlib
import zlib

import numpy as np

from . import _vibrissa

__all__ = ["KINDS", "configured", "parameter_path", "run_chunk"]

KINDS = ("array", "trial", "solve")

# Wall-clock numbers differ between two runs of the same configuration; a sweep leaves them out.
_WALL_CLOCK = {"pipeline_seconds", "simulation_seconds"}


def parameter_path(path):
    """'objects.0.point_mm.1' -> ['objects', 0, 'point_mm', 1] (an integer part indexes a list)."""
    if not isinstance(path, str) or not path or any(not part for part in path.split(".")):
        raise ValueError(f"a swept parameter is a dotted path into the configuration, such as "
                         f"'head.pitch_deg' or 'objects.0.point_mm.1', got {path!r}")
    return [int(part) if part.isdigit() else part for part in path.split(".")]


def configured(base, overrides):
    """A copy of `base` with each `overrides` path set to its value (missing objects on the way are created;
    list indices must exist). ValueError names the path."""
    config = copy.deepcopy(base)
    for path, value in overrides.items():
        parts = parameter_path(path)
        node = config
        for depth, part in enumerate(parts):
            last = depth == len(parts) - 1
            where = ".".join(map(str, parts[:depth])) or "the configuration"
            if isinstance(part, int):
                if not isinstance(node, list) or part >= len(node):
                    size = f"a list of {len(node)}" if isinstance(node, list) else f"not a list ({type(node).__name__})"
                    raise ValueError(f"parameter {path!r}: {where} is {size}, so it has no entry {part}")
            elif not isinstance(node, dict):
                raise ValueError(f"parameter {path!r}: {where} is not an object ({type(node).__name__})")
            if last:
                node[part] = value
            else:
                if isinstance(node, dict) and part not in node:
                    node[part] = {}
                node = node[part]
    return config


@functools.lru_cache(maxsize=1)
def build_id():
    """vibrissa's version and a digest of its compiled module: two processes with the same id compute the same
    numbers (the client checks every worker's against its own)."""
    digest = hashlib.sha256(pathlib.Path(_vibrissa.__file__).read_bytes()).hexdigest()[:16]
    return f"{_vibrissa.__version__}+{digest}"


# --- one run: configuration -> (coordinates, variables), each name -> (dims, attrs, values) ---------------

def _labelled(description, group=""):
    coords, variables = {}, {}
    for path, dims, attrs, values in description["variables"]:
        where, _, name = path.rpartition("/")
        if where == group:
            (coords if tuple(dims) == (name,) else variables)[name] = (tuple(dims), dict(attrs), values)
    return coords, variables


def _array_run(config):
    from .pipeline import simulate_array
    result = simulate_array(config, threads=1)
    coords, variables = _labelled(result._run.labelled())
    variables["solves"] = ((), {"units": "1", "long_name": "edge solves of the run"}, np.int64(result._run.solves))
    return coords, variables


def _flat_numbers(tree, prefix, out):
    """The numeric leaves of a summary (not in lists) as 'summary.a.b' -> value; None (null) -> NaN."""
    for key, value in tree.items():
        name = f"{prefix}.{key}"
        if isinstance(value, dict):
            _flat_numbers(value, name, out)
        elif isinstance(value, bool):
            out[name] = np.int8(value)
        elif isinstance(value, (int, float)) and key not in _WALL_CLOCK:
            out[name] = np.float64(value)
    return out


def _trial_run(config):
    from .pipeline import analyze_trial, read_trial, synthesize_trial
    unknown = set(config) - {"trial", "synth", "analysis"}
    if unknown:
        raise ValueError(f"trial run: unknown key(s) {sorted(unknown)} (expected 'trial' or 'synth', and 'analysis')")
    if config.get("trial") is not None:
        trial = read_trial(str(config["trial"]))
    else:
        trial = synthesize_trial(**config.get("synth", {}))
    result = analyze_trial(trial, **config.get("analysis", {}))
    coords, variables = _labelled(result._outputs.labelled())
    # Runs may differ in time stamps (other files, frame rates): the dimension is the frame, time a variable.
    dims, attrs, time = coords.pop("time")
    variables = {name: (tuple("frame" if d == "time" else d for d in dims_), attrs_, values)
                 for name, (dims_, attrs_, values) in variables.items()}
    variables["time"] = (("frame",), attrs, time)
    coords["frame"] = (("frame",), {"units": "1", "long_name": "frame of the trial, from 0"}, np.arange(len(time)))
    summary = {}
    for name, value in _flat_numbers(result.summary, "summary", {}).items():
        summary[name] = ((), {"long_name": f"{name[8:]} of summary.json (its units as its name says)"}, value)
    variables.update(summary)
    return coords, variables


def _enum_table(enum):
    return ", ".join(f"{int(v)} {v.label}" for v in sorted(enum.__members__.values(), key=int))


_SOLVE_SCALARS = (  # Solution field, units, description
    ("force_magnitude", "N", "magnitude of the contact force"),
    ("arc_length", "m", "arc length of the contact point from the base"),
    ("angle", "rad", "direction of the force about the loaded link (docs/conventions.md)"),
    ("normal_force", "N", "contact force normal to the edge (NaN without an edge)"),
    ("edge_force", "N", "contact force along the edge (NaN without an edge)"),
    ("residual", "m", "residual of the solve"),
    ("iterations", "1", "solver iterations"),
)
_SOLVE_VECTORS = (  # name in the sweep, in Solution (or its whisker_frame), units, description
    ("contact_point_W", "contact_point_W", "m", "contact point, world frame"),
    ("force_W", "force_W", "N", "contact force on the whisker, world frame"),
    ("moment_W", "moment_W", "N m", "moment of the contact force about the base, world frame"),
    ("force_B", "force", "N", "force at the base, whisker frame (Fx axial, Fy, Fz)"),
    ("moment_B", "moment", "N m", "moment at the base, whisker frame (Mx twist, My, Mz)"),
)
_SOLVE_SIGNALS = (("FT", "N", "transverse force at the base"), ("MB", "N m", "bending moment at the base"),
                  ("FD", "rad", "direction of the transverse force"), ("MD", "rad", "direction of the bending moment"))


def _solve_run(config):
    from .case import load_case
    solution = load_case(config).solve()
    frame = solution.whisker_frame
    variables = {}
    for name, enum, what in (("status", _vibrissa.Status, "status of the solve"),
                             ("contact_state", _vibrissa.ContactState, "contact state"),
                             ("friction", _vibrissa.FrictionState, "friction state (frictional edge mode)")):
        variables[name] = ((), {"units": "code", "long_name": what, "codes": _enum_table(enum)},
                           np.int8(int(getattr(solution, name))))
    variables["fold"] = ((), {"units": "1", "long_name": "1 if slipped off at a fold (push-past)"},
                         np.int8(solution.fold))
    for name, units, what in _SOLVE_SCALARS:
        value = getattr(solution, name)
        variables[name] = ((), {"units": units, "long_name": what}, np.float64(math.nan if value is None else value))
    for name, field, units, what in _SOLVE_VECTORS:
        value = getattr(frame if field in ("force", "moment") else solution, field)
        variables[name] = (("component",), {"units": units, "long_name": what}, np.asarray(value, dtype=float))
    for name, units, what in _SOLVE_SIGNALS:
        variables[name] = ((), {"units": units, "long_name": what}, np.float64(getattr(frame, name)))
    coords = {"component": (("component",), {"units": "text", "long_name": "vector component"},
                            np.array(["x", "y", "z"]))}
    return coords, variables


_RUNNERS = {"array": _array_run, "trial": _trial_run, "solve": _solve_run}


def run_chunk(kind, base, runs, variables=None, on_error="raise"):
    """Runs `runs` ([(run index, {path: value}), ...]) of `kind` on `base`; returns the chunk's results:
    {"runs": [indices], "coords": {name: (dims, attrs, values)}, "variables": {name: (("run", *dims), attrs,
    values stacked over runs)}, "failed": [[index, message], ...], "build": build_id()}. `variables` (names)
    keeps only those. A run that fails raises its error (ValueError, TypeError, ...) with the run's index and
    parameters in front, or with on_error="record" is listed in "failed" (and not in "runs") and the chunk goes
    on. KeyboardInterrupt and other non-Exception errors always propagate."""
    coords, stacked, failed = None, {}, []
    for index, overrides in runs:
        try:
            run_coords, run_variables = _RUNNERS[kind](configured(base, overrides))
        except Exception as error:  # name the run: the message travels back to the client
            where = ", ".join(f"{p}={v!r}" for p, v in overrides.items())
            message = f"sweep run {index} ({where or 'the base configuration'}): {error}"
            if on_error == "record":
                failed.append([index, message])
                continue
            try:
                renamed = type(error)(message)
            except Exception:
                renamed = RuntimeError(message)
            raise renamed from None
        if variables is not None:
            missing = sorted(set(variables) - set(run_variables))
            if missing:
                raise ValueError(f"variables: {missing} are not outputs of a {kind} run "
                                 f"(it has {sorted(run_variables)})")
            run_variables = {name: run_variables[name] for name in variables}
            used = {dim for dims, _, _ in run_variables.values() for dim in dims}
            run_coords = {name: c for name, c in run_coords.items() if name in used}
        if coords is None:
            coords = run_coords
        _check_same_coordinates(coords, run_coords, index, overrides)
        for name, (dims, attrs, values) in run_variables.items():
            stacked.setdefault(name, (("run", *dims), attrs, []))[2].append(values)
    out, packed = {}, {}
    for name, (dims, attrs, values) in stacked.items():
        values = np.stack(values)
        if values[0].size >= COMPRESS_FROM:
            packed[name] = (dims, attrs, pack(values))
        else:
            out[name] = (dims, attrs, values)
    done = [index for index, _ in runs if index not in {i for i, _ in failed}]
    return {"runs": done, "coords": coords or {}, "variables": out, "packed": packed, "failed": failed,
            "build": build_id()}


# Outputs of at least this many values per run are stored compressed, one HDF5 chunk per run (mostly zeros and
# NaN: they shrink about tenfold). The worker compresses them (`pack`) and the client writes the compressed bytes
# into sweep.nc as they are (sweep_store): the client, which has one core like each worker, neither receives
# nor compresses the uncompressed values, so the sweep scales with the workers (docs/sweeps.md, "Scale").
COMPRESS_FROM = 4096
COMPRESSION_LEVEL = 1  # zlib level: HDF5's deflate filter at this level (`compression_opts`)


def pack(values):
    """Each run's values (values[i], C order) compressed by zlib at COMPRESSION_LEVEL, the byte stream HDF5's deflate
    filter writes and reads: {"bytes": uint8 array of every run's stream in turn, "ends": int64 end of each,
    "dtype": the values' dtype (str), "shape": one run's shape (list)}."""
    streams = [zlib.compress(np.ascontiguousarray(v).tobytes(), COMPRESSION_LEVEL) for v in values]
    return {"bytes": np.frombuffer(b"".join(streams), dtype=np.uint8),
            "ends": np.cumsum([len(stream) for stream in streams], dtype=np.int64),
            "dtype": values.dtype.str, "shape": list(values.shape[1:])}


def _check_same_coordinates(expected, found, index, overrides):
    for name, (dims, _, values) in expected.items():
        other = found[name][2]
        if other.shape != values.shape or not np.array_equal(other, values):
            where = ", ".join(f"{p}={v!r}" for p, v in overrides.items())
            raise ValueError(f"sweep run {index} ({where}): its {name} coordinate ({other.shape[0]} values) differs "
                             f"from the other runs' ({values.shape[0]}): the runs of a sweep must share their "
                             f"dimensions (sweep parameters that change {name} in separate sweeps)")
