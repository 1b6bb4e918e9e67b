"""Labelled outputs and one unit convention (docs/formats.md, "Labelled HDF5 outputs" and "Units"):
xarray.open_dataset reads every HDF5 file the tools write with both netCDF-4 engines and gives named dimensions
with coordinates; to_xarray() is exactly what the written file gives; every CSV and HDF5 output is in SI units
with names that carry no unit, and every CSV column is the HDF5 variable of its name, value for value."""

import csv
import json
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest

import vibrissa

from test_cli_outputs import SMALL_ARRAY, run
from test_recon import write_views

xr = pytest.importorskip("xarray")
h5py = pytest.importorskip("h5py")

# Units an output may state: SI (and "1", codes, text; pixels have no SI unit).
SI_UNITS = {"m", "s", "rad", "N", "N m", "1", "code", "text", "px"}
# A name ending in a unit: what the convention forbids (`_px` is the unit pixels, allowed above).
UNIT_SUFFIX = re.compile(r"_(mm|um|cm|m|mN|uN|N|uNm|mNm|Nm|deg|rad|ms|us|s|Hz|Pa|GPa)$")

# xarray.open_dataset in a child process: a reader that crashes on a file (as netCDF4 did on fixed-length
# strings) fails the tests instead of ending the test run. One line of JSON per file, group and engine.
OPEN = """import json, sys, xarray as xr
for path, group, engine in json.loads(sys.argv[1]):
    with xr.open_dataset(path, engine=engine, group=group or None) as ds:
        print(json.dumps([path, group, engine, {
            "sizes": dict(ds.sizes), "coords": {n: [list(c.dims), str(c.dtype)] for n, c in ds.coords.items()},
            "vars": {n: [list(v.dims), v.attrs.get("units"), v.attrs.get("long_name")] for n, v in ds.data_vars.items()}}]),
              flush=True)
"""
ENGINES = ("netcdf4", "h5netcdf")


@pytest.fixture(scope="module")
def outputs(cli, tmp_path_factory):
    """Every HDF5 and CSV output of the CLI, from small runs."""
    d = tmp_path_factory.mktemp("outputs")
    run(cli, "synth", d / "trial.h5", "--duration", "0.2", "--shapes")
    run(cli, "synth", d / "trial.csv", "--duration", "0.2", "--shapes")
    run(cli, "trial", d / "trial.h5", "--out", d / "results", "--no-figures", "--mu", "0.4")
    (d / "array.json").write_text(json.dumps(dict(SMALL_ARRAY, head={"pitches_deg": [-10, 0, 10]})))
    run(cli, "array", d / "array.json", "--out", d / "array", "--no-figures", "--csv")
    write_views(d)
    for ext in ("h5", "csv"):
        run(cli, "reconstruct", "--top", d / "top.csv", "--front", d / "front.csv", "--calibration", d / "cams.json",
            "-o", d / f"recon.{ext}")
    (d / "sweep.json").write_text(json.dumps({"kind": "array", "base": "array.json",
                                              "grid": {"whisking.amplitude_deg": [20, 30]}}))
    run(cli, "sweep", d / "sweep.json", "--out", d / "sweep", "--scheduler", "serial")
    return d


@pytest.fixture(scope="module")
def opened(outputs):
    """{(file, group, engine): what xarray.open_dataset saw} for every file of HDF5_FILES and both engines."""
    todo = [[str(outputs / name), group, engine] for name, group in HDF5_FILES for engine in ENGINES]
    done = subprocess.run([sys.executable, "-c", OPEN, json.dumps(todo)], capture_output=True, text=True, timeout=300)
    seen = {}
    for line in done.stdout.splitlines():
        path, group, engine, found = json.loads(line)
        seen[str(pathlib.Path(path).relative_to(outputs)), group, engine] = found
    assert done.returncode == 0, f"xarray.open_dataset failed after {sorted(seen)}: exit {done.returncode}\n{done.stderr}"
    return seen


HDF5_FILES = {  # file, group: dimensions expected of some variables
    ("trial.h5", ""): {"base": ["time", "component"], "shape": ["time", "node", "component"],
                       "rest_shape": ["rest_node", "component"], "edges": ["edge", "edge_component"]},
    ("recon.h5", ""): {"reprojection_px": ["time"], "contact": ["time"]},
    ("results/frames.h5", ""): {"cp_FT": ["time"], "edge_status": ["time"], "fric_MD": ["time"]},
    ("array/array.h5", ""): {"FT": ["pitch", "whisker", "time"], "force_B": ["pitch", "whisker", "time", "component"],
                             "theta": ["whisker", "time"], "side": ["whisker"]},
    ("array/array.h5", "render"): {"deflected": ["frame", "whisker", "node", "component"],
                                   "edges": ["frame", "edge", "end", "component"]},
    ("sweep/sweep.nc", ""): {"FT": ["whisking.amplitude_deg", "pitch", "whisker", "time"],
                             "force_W": ["whisking.amplitude_deg", "pitch", "whisker", "time", "component"]},
}


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("name, group", list(HDF5_FILES))
def test_every_hdf5_output_opens_labelled_with_both_engines(opened, engine, name, group):
    ds = opened[name, group, engine]
    for var, dims in HDF5_FILES[name, group].items():
        assert ds["vars"][var][0] == dims, var
    for var, (dims, units, long_name) in ds["vars"].items():
        assert units in SI_UNITS and long_name, var
    # Every dimension has its coordinate (in the render group, whisker and component have theirs at the root).
    assert set(ds["sizes"]) - set(ds["coords"]) == ({"whisker", "component"} if group else set())
    if name == "array/array.h5" and not group:
        assert ds["coords"]["whisker"] == [["whisker"], "object"] and ds["sizes"] == {
            "pitch": 3, "whisker": 3, "time": 20, "component": 3}


def test_to_xarray_is_the_written_file(tmp_path):
    config = dict(SMALL_ARRAY, head={"pitches_deg": [0, 5]})
    array = vibrissa.simulate_array(config)
    array.write(tmp_path / "array")
    for group in ("", "render"):
        with xr.open_dataset(tmp_path / "array" / "array.h5", engine="h5netcdf", group=group or None) as written:
            xr.testing.assert_identical(array.to_xarray(group), written.load())
    labelled = array.to_xarray()
    assert list(labelled.whisker.values) == ["C1R", "C2R", "D1R"]
    assert labelled.FT.attrs == {"units": "N", "long_name": "transverse force at the base, sqrt(Fy^2 + Fz^2)"}
    np.testing.assert_array_equal(labelled.FT.sel(whisker="C2R").values, array.FT[:, 1])
    np.testing.assert_array_equal(labelled.pitch.values, np.radians([0, 5]))
    with pytest.raises(ValueError, match="group must be one of"):
        array.to_xarray("nope")

    result = vibrissa.analyze_trial(vibrissa.synthesize_trial(duration=0.2), mu=0.4)
    result.write(tmp_path / "trial")
    with xr.open_dataset(tmp_path / "trial" / "frames.h5", engine="h5netcdf") as written:
        xr.testing.assert_identical(result.to_xarray(), written.load())
    table = result.to_xarray()
    assert table.cp_MB.attrs["units"] == "N m" and table.cp_status.dtype == np.int8
    np.testing.assert_array_equal(table.time.values, result.time)


def test_renamed_direction_columns_still_answer_in_degrees_with_a_warning():
    result = vibrissa.analyze_trial(vibrissa.synthesize_trial(duration=0.2))
    with pytest.warns(DeprecationWarning, match="'cp_FD_deg' is deprecated: use 'cp_FD'"):
        old = result.cp_FD_deg
    np.testing.assert_array_equal(old, np.degrees(result.cp_FD))
    with pytest.warns(DeprecationWarning):
        np.testing.assert_array_equal(result["edge_MD_deg"], np.degrees(result["edge_MD"]))


def hdf5_units(path):
    found = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: found.setdefault(name, obj.attrs.get("units", "(none)"))
                     if isinstance(obj, h5py.Dataset) else None)
    return found


def read_csv(path):
    lines = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    rows = list(csv.reader(lines))
    return rows[0], [dict(zip(rows[0], row)) for row in rows[1:]]


def numbers(rows, column):
    return np.array([float(r[column]) if r[column] not in ("", "nan") else np.nan for r in rows])


def test_every_output_follows_one_unit_convention(outputs):
    for name in ("trial.h5", "recon.h5", "results/frames.h5", "array/array.h5", "sweep/sweep.nc"):
        for dataset, units in hdf5_units(outputs / name).items():
            if dataset == "whisking.amplitude_deg":  # a swept input: named and valued as in the input
                assert units == "deg"
                continue
            assert units in SI_UNITS, f"{name}: {dataset} in {units}"
            assert not UNIT_SUFFIX.search(dataset), f"{name}: {dataset} names its unit"
    for name in ("trial.csv", "recon.csv", "results/frames.csv", "array/array.csv", "array/pitch_summary.csv"):
        header, _ = read_csv(outputs / name)
        assert not [c for c in header if UNIT_SUFFIX.search(c)], f"{name}: {header}"


def assert_same(csv_values, h5_values, what):
    assert csv_values.shape == h5_values.shape, what
    np.testing.assert_array_equal(csv_values, h5_values, err_msg=what)  # exact: CSV numbers read back bit for bit


def test_csv_columns_are_the_hdf5_variables_value_for_value(outputs):
    # frames.csv: the columns of frames.h5 under the same names (status columns by name, codes in HDF5).
    header, rows = read_csv(outputs / "results" / "frames.csv")
    with h5py.File(outputs / "results" / "frames.h5", "r") as f:
        assert set(header) == set(f)
        for column in header:
            if f[column].attrs["units"] == "code":
                labels = dict(entry.split(" ", 1) for entry in f[column].attrs["codes"].split(", "))
                assert [r[column] for r in rows] == [labels[str(v)] for v in f[column][()]], column
            else:
                assert_same(numbers(rows, column), f[column][()], column)

    # array.csv: every [pitch][whisker][frame] variable of array.h5 in long format, vectors as _x, _y, _z.
    header, rows = read_csv(outputs / "array" / "array.csv")
    with h5py.File(outputs / "array" / "array.h5", "r") as f:
        P, W, F = f["state"].shape
        assert header[:4] == ["pitch", "whisker", "frame", "time"] and len(rows) == P * W * F
        assert_same(numbers(rows, "pitch"), np.repeat(f["pitch"][()], W * F), "pitch")
        assert [r["whisker"] for r in rows] == [w.decode() for w in np.tile(np.repeat(f["whisker"][()], F), P)]
        assert_same(numbers(rows, "time"), np.tile(f["time"][()], P * W), "time")
        per_frame = [n for n, d in f.items() if isinstance(d, h5py.Dataset) and d.ndim >= 3]
        expected = [n + s for n in per_frame for s in (["_x", "_y", "_z"] if f[n].ndim == 4 else [""])]
        assert sorted(header[4:]) == sorted(expected)
        for column in header[4:]:
            name, axis = (column[:-2], "xyz".index(column[-1])) if column[:-2] in per_frame else (column, None)
            values = f[name][()].reshape(P * W * F, -1)[:, axis or 0]
            if f[name].attrs["units"] == "code":
                labels = dict(entry.split(" ", 1) for entry in f[name].attrs["codes"].split(", "))
                assert [r[column] for r in rows] == [labels[str(v)] for v in values], column
            else:
                assert_same(numbers(rows, column), values.astype(float), column)

        # pitch_summary.csv: per pitch, from the same arrays.
        _, pitches = read_csv(outputs / "array" / "pitch_summary.csv")
        state, MB, time = f["state"][()], f["MB"][()], f["time"][()]
        assert_same(numbers(pitches, "pitch"), f["pitch"][()], "pitch")
        assert_same(numbers(pitches, "peak_MB"), MB.max(axis=(1, 2)), "peak_MB")
        onset = [time[(s == 1).any(axis=0)].min() if (s == 1).any() else np.nan for s in state]
        assert_same(numbers(pitches, "first_onset"), np.array(onset), "first_onset")

    # Trial files: the CSV's columns are the HDF5 file's arrays (base_x = base[:, 0], shape_y_3 = shape[:, 3, 1]).
    header, rows = read_csv(outputs / "trial.csv")
    with h5py.File(outputs / "trial.h5", "r") as f:
        for column in header:
            parts = re.fullmatch(r"(base|contact|shape)_([xyz])(?:_(\d+))?", column)
            if parts is None:
                assert_same(numbers(rows, column), f[column][()].astype(float), column)
                continue
            name = {"base": "base", "contact": "contact_point", "shape": "shape"}[parts[1]]
            index = (slice(None),) + ((int(parts[3]),) if parts[3] else ()) + ("xyz".index(parts[2]),)
            assert_same(numbers(rows, column), f[name][()][index], column)
