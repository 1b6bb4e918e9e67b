"""The output folder of a sweep (docs/sweeps.md, "Files"): written by the client only, each file atomically.

    sweep.json              what is swept (kind, base configuration, parameters, variables, chunk size)
    chunks/chunk-NNNNNN.npz the results of one finished chunk of runs: NumPy arrays stacked over its runs (large
                            outputs as each run's zlib stream, sweep_runs.pack), and their dimensions and
                            attributes as JSON (`meta`); the client's own bookkeeping
    index.json              the finished chunks: a chunk counts as done once it is listed here
    sweep.nc                every result on the sweep's dimensions (netCDF-4: xarray.open_dataset), written
                            once the last chunk is in

A chunk file is renamed into place before the index lists it, so an interrupted sweep (Ctrl-C, a killed
client, a power cut) leaves finished chunks that a rerun of the same sweep skips, and at worst one chunk file
that the index does not list yet, which the rerun computes and replaces: nothing is lost or counted twice.
"""

import contextlib
import json
import os
import pathlib

import numpy as np

from .sweep_runs import COMPRESSION_LEVEL

__all__ = ["SweepStore"]

FORMAT = "vibrissa-sweep"
VERSION = 2  # 2: large outputs stored compressed per run (sweep_runs.pack)


@contextlib.contextmanager
def _replacing(path):
    """Yields a temporary beside `path` (`.tmp-<pid>-<name>`, as every vibrissa output: docs/formats.md, "Atomic
    outputs"); once the block completes it is flushed to disk and renamed over `path`, else removed."""
    path = pathlib.Path(path)
    tmp = path.with_name(f".tmp-{os.getpid()}-{path.name}")
    try:
        yield tmp
        with open(tmp, "rb") as f:
            os.fsync(f.fileno())
        os.replace(tmp, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.remove(tmp)


def _write_json(path, value):
    with _replacing(path) as tmp:
        tmp.write_text(json.dumps(value, indent=1) + "\n")


class SweepStore:
    """The folder `directory` of the sweep described by `spec` (a JSON-able dict). Opening a folder that holds
    another sweep raises ValueError naming what differs."""

    def __init__(self, directory, spec):
        self.directory = pathlib.Path(directory)
        self.spec = dict(spec, format=FORMAT, format_version=VERSION)
        (self.directory / "chunks").mkdir(parents=True, exist_ok=True)
        spec_path = self.directory / "sweep.json"
        if spec_path.is_file():
            stored = json.loads(spec_path.read_text())
            differing = sorted(k for k in set(stored) | set(self.spec) if stored.get(k) != self.spec.get(k))
            if differing:
                raise ValueError(f"{self.directory} holds another sweep (its sweep.json differs in {differing}): "
                                 "choose another output folder, or delete this one to start over")
        else:
            _write_json(spec_path, self.spec)
        index_path = self.directory / "index.json"
        self.index = json.loads(index_path.read_text())["chunks"] if index_path.is_file() else {}
        # A listed chunk whose file is gone is computed again.
        self.index = {k: v for k, v in self.index.items() if (self.directory / v["file"]).is_file()}
        self._coords = None  # the output coordinates every chunk must share

    @property
    def result_path(self):
        return self.directory / "sweep.nc"

    def finished(self):
        """Ids (int) of the chunks whose results are on disk."""
        return {int(k) for k in self.index}

    def add(self, chunk, result):
        """Writes the results of chunk `chunk` (run_chunk's dict) and lists it in the index. Results of a chunk
        already listed are ignored (a task computed twice is stored once)."""
        if str(chunk) in self.index:
            return
        if result["runs"]:
            self._check_coordinates(result)
        name = f"chunks/chunk-{chunk:06d}.npz"
        arrays = {f"variable/{n}": values for n, (_, _, values) in result["variables"].items()}
        arrays.update({f"coordinate/{n}": values for n, (_, _, values) in result["coords"].items()})
        for n, (_, _, packed) in result["packed"].items():
            arrays.update({f"packed/{n}/bytes": packed["bytes"], f"packed/{n}/ends": packed["ends"]})
        meta = {kind: {n: {"dims": list(dims), "attrs": attrs} for n, (dims, attrs, _) in result[kind].items()}
                for kind in ("variables", "coords", "packed")}
        for n, (_, _, packed) in result["packed"].items():
            meta["packed"][n].update(dtype=packed["dtype"], shape=packed["shape"])
        with _replacing(self.directory / name) as tmp, open(tmp, "wb") as f:
            np.savez(f, runs=np.asarray(result["runs"]), meta=np.array(json.dumps(meta)), **arrays)
        failed = result.get("failed", [])
        every = list(result["runs"]) + [i for i, _ in failed]
        self.index[str(chunk)] = {"file": name, "runs": [min(every), max(every) + 1], "build": result["build"]}
        if failed:
            self.index[str(chunk)]["failed"] = failed
        _write_json(self.directory / "index.json", {"chunks": self.index})

    def _load(self, chunk):
        """The arrays of a chunk file: (runs, {name: values}, {name: values} of coordinates, meta, {name: (bytes,
        ends)} of the packed outputs)."""
        with np.load(self.directory / self.index[chunk]["file"], allow_pickle=False) as f:
            meta = json.loads(str(f["meta"]))
            variables = {n: f[f"variable/{n}"] for n in meta["variables"]}
            coords = {n: f[f"coordinate/{n}"] for n in meta["coords"]}
            packed = {n: (f[f"packed/{n}/bytes"], f[f"packed/{n}/ends"]) for n in meta["packed"]}
            return f["runs"], variables, coords, meta, packed

    def _check_coordinates(self, result):
        if self._coords is None and self.index:
            self._coords = self._load(next(iter(self.index)))[2]
        found = {name: values for name, (_, _, values) in result["coords"].items()}
        if self._coords is None:
            self._coords = found
        for name, values in self._coords.items():
            other = found.get(name)
            if other is None or other.shape != values.shape or not np.array_equal(other, values):
                raise ValueError(f"runs {min(result['runs'])}-{max(result['runs'])}: their {name} coordinate differs "
                                 "from the other runs': the runs of a sweep must share their dimensions (sweep "
                                 f"parameters that change {name} in separate sweeps)")

    def assemble(self, parameters, runs, attributes):
        """Writes sweep.nc: every variable of the chunk files on dimensions `parameters` ({name: values}, a grid,
        C order) or, for a list of runs (`parameters` None), on dimension run with each swept path a coordinate
        along it (`runs`: the list of {path: value}). The layout is written with h5netcdf (netCDF-4), the values
        with h5py one chunk file at a time (memory: one chunk)."""
        import h5netcdf
        import h5py

        chunks = sorted(self.index, key=int)
        failed = [entry for c in chunks for entry in self.index[c].get("failed", [])]
        with_runs = [c for c in chunks if len(self._load(c)[0])]
        if not with_runs:
            raise ValueError(f"every run of the sweep failed; the first: {min(failed)[1]}")
        _, first, coords, meta, _ = self._load(with_runs[0])
        if parameters is not None:
            names = list(parameters)
            shape = tuple(len(v) for v in parameters.values())
        else:
            names, shape = ["run"], (len(runs),)
        outputs = set(first) | set(coords) | set(meta["packed"])
        clash = sorted(set(names) & outputs)
        if clash:
            raise ValueError(f"swept parameter(s) {clash} have the names of outputs: rename them in the sweep")
        with _replacing(self.result_path) as tmp:
            with h5netcdf.File(tmp, "w") as f:
                f.attrs.update(attributes)
                f.dimensions.update(dict(zip(names, shape)))
                for name, values in coords.items():
                    f.dimensions.update(dict(zip(meta["coords"][name]["dims"], values.shape)))
                coordinates = []
                if parameters is not None:
                    for name, values in parameters.items():
                        _write_variable(f, name, (name,), _coordinate_values(values, name), _parameter_attrs(name))
                else:
                    _write_variable(f, "run", ("run",), np.arange(len(runs)), {"units": "1", "long_name": "run, from 0"})
                    for path in sorted({p for run in runs for p in run}):
                        values = [run.get(path) for run in runs]
                        _write_variable(f, path, ("run",), _coordinate_values(values, path), _parameter_attrs(path))
                        coordinates.append(path)
                for name, values in coords.items():
                    _write_variable(f, name, meta["coords"][name]["dims"], values, meta["coords"][name]["attrs"])
                # Small outputs stored plainly; a packed one as one compressed HDF5 chunk per run, the worker's
                # zlib stream of that run (HDF5's deflate filter reads it).
                layouts = [(name, values.dtype, meta["variables"][name], {}) for name, values in first.items()]
                layouts += [(name, np.dtype(m["dtype"]), m, {"chunks": (1,) * len(names) + tuple(m["shape"]),
                                                              "compression": "gzip",
                                                              "compression_opts": COMPRESSION_LEVEL})
                            for name, m in meta["packed"].items()]
                for name, dtype, m, layout in sorted(layouts, key=lambda item: item[0]):
                    attrs = dict(m["attrs"])
                    if coordinates:
                        attrs["coordinates"] = " ".join(coordinates)
                    # A failed run (on_error="record") keeps the fill value, NaN, or -1 for integers, which xarray
                    # reads as NaN too (the variable becomes float); none without failures (dtypes as before).
                    fill = None if not failed else (np.nan if dtype.kind == "f" else
                                                    -1 if dtype.kind in "iu" else None)
                    f.create_variable(name, (*names, *m["dims"][1:]), dtype, fillvalue=fill,
                                      **layout).attrs.update(attrs)
                if self.spec.get("on_error") == "record":  # why each failed run failed ("" for the others)
                    messages = np.full(shape, "", dtype=object)
                    for index, message in failed:
                        messages[np.unravel_index(int(index), shape)] = message
                    error = f.create_variable("error", tuple(names), h5py.string_dtype())
                    error.attrs.update({"long_name": "why the run failed (empty: it ran)"})
                    error[...] = messages
            with h5py.File(tmp, "r+") as f:
                for chunk in chunks:
                    run_indices, variables, _, meta, packed = self._load(chunk)
                    where = [np.unravel_index(int(r), shape) for r in run_indices]
                    for name, values in variables.items():
                        target = f[name]
                        for j, index in enumerate(where):
                            target[index] = values[j]
                    for name, (data, ends) in packed.items():
                        target, data, starts = f[name], data.tobytes(), [0, *ends[:-1].tolist()]
                        tail = (0,) * len(meta["packed"][name]["shape"])
                        for index, a, b in zip(where, starts, ends.tolist()):
                            target.id.write_direct_chunk(tuple(int(i) for i in index) + tail, data[a:b])


# Units of a swept input, read from its key (inputs name their units: docs/formats.md, "Units").
_INPUT_UNITS = {"deg": "deg", "mm": "mm", "um": "um", "ms": "ms", "s": "s", "Hz": "Hz", "GPa": "GPa", "Pa": "Pa",
                "m": "m", "rad": "rad", "N": "N"}


def _parameter_attrs(path):
    attrs = {"long_name": f"swept parameter {path} (in the input's units)"}
    suffix = path.split(".")[-1].rpartition("_")[2] if "_" in path.split(".")[-1] else ""
    if suffix in _INPUT_UNITS:
        attrs["units"] = _INPUT_UNITS[suffix]
    return attrs


def _coordinate_values(values, path):
    """The values of a swept parameter as one NumPy array: numbers (int64 if all integers, else float64; a
    missing value NaN), strings (missing: ""), or booleans as int8 0/1."""
    present = [v for v in values if v is not None]
    if all(isinstance(v, bool) for v in present):
        return np.array([int(bool(v)) for v in values], dtype=np.int8)
    if all(isinstance(v, str) for v in present):
        return np.array(["" if v is None else v for v in values], dtype=object)
    if all(isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool) for v in present):
        if all(isinstance(v, (int, np.integer)) for v in present) and len(present) == len(values):
            return np.array(values, dtype=np.int64)
        return np.array([np.nan if v is None else float(v) for v in values], dtype=np.float64)
    raise ValueError(f"parameter {path!r}: swept values must be all numbers, all strings or all booleans "
                     f"(sweep the components of a list one by one: '{path}.0'), got {values[:5]!r}")


def _write_variable(f, name, dims, values, attrs):
    import h5py
    values = np.asarray(values)
    text = values.dtype.kind in "OU"
    variable = f.create_variable(name, dims, h5py.string_dtype() if text else values.dtype)
    variable[...] = values.astype(object) if text else values
    variable.attrs.update(attrs)
