"""Outputs describe themselves (docs/formats.md, "Units and codes"): every dataset of every HDF5 file the CLI
writes states its units (a new dataset without a `units` attribute fails here), code datasets (units "code")
carry their code table, and values that do not exist are NaN (empty in CSV)."""

import csv
import json
import subprocess

import numpy as np
import pytest

import vibrissa

from test_cli_outputs import SMALL_ARRAY, run
from test_recon import write_views

h5py = pytest.importorskip("h5py")


def datasets(path):
    found = []
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: found.append(name) if isinstance(obj, h5py.Dataset) else None)
    return found


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def assert_units_everywhere(path):
    names = datasets(path)
    assert names, path
    with h5py.File(path, "r") as f:
        for name in names:
            attrs = f[name].attrs
            assert "units" in attrs, f"{path}: dataset {name} has no units attribute"
            units = text(attrs["units"])
            assert units, f"{path}: dataset {name} has empty units"
            if units == "code":
                assert text(attrs["codes"]), f"{path}: code dataset {name} has no code table"
                assert f[name].dtype.kind == "i", f"{path}: code dataset {name} is not integer"
    return names


def code_table(attr):
    return {int(code): label for code, label in (entry.split(" ", 1) for entry in text(attr).split(", "))}


def test_every_cli_hdf5_dataset_has_units(cli, tmp_path):
    trial = tmp_path / "trial.h5"
    run(cli, "synth", trial, "--duration", "0.1", "--shapes")
    names = assert_units_everywhere(trial)
    assert {"time", "theta", "contact", "shape"} <= set(names)
    with h5py.File(trial, "r") as f:
        assert text(f["theta"].attrs["units"]) == "rad" and text(f["shape"].attrs["units"]) == "m"

    out = tmp_path / "results"
    run(cli, "trial", trial, "--out", out, "--no-figures", "--mu", "0.3")
    names = assert_units_everywhere(out / "frames.h5")
    with h5py.File(out / "frames.h5", "r") as f, open(out / "frames.csv") as c:
        rows = list(csv.DictReader(c))
        g = f
        assert text(g["edge_FD"].attrs["units"]) == "rad" and text(g["edge_MB"].attrs["units"]) == "N m"
        status = g["edge_status"]
        assert status.dtype == np.int8 and text(status.attrs["units"]) == "code"
        table = code_table(status.attrs["codes"])
        assert table == {-1: "not_in_contact", 0: "converged", 1: "no_contact", 2: "slipped_off", 3: "not_converged",
                         4: "second_contact", 5: "underdetermined"}
        labels = [r["edge_status"] for r in rows]
        assert [table[int(v)] for v in status[()]] == labels
        assert "converged" in labels and "not_in_contact" in labels

    array_cfg = tmp_path / "array.json"
    array_cfg.write_text(json.dumps(SMALL_ARRAY))
    run(cli, "array", array_cfg, "--out", tmp_path / "array", "--no-figures", "--csv")
    names = assert_units_everywhere(tmp_path / "array" / "array.h5")
    assert {"state", "solver_status", "whisker", "render/deflected"} <= set(names)
    with h5py.File(tmp_path / "array" / "array.h5", "r") as f:
        assert code_table(f["state"].attrs["codes"]) == {0: "free", 1: "contact", 2: "pushed_past"}
        assert code_table(f["solver_status"].attrs["codes"])[-1] == "not_in_contact"
        # Free frames: no contact point, arc length, directions or z_error (NaN); zero loads.
        state = f["state"][()]
        free, touching = state == 0, state == 1
        assert free.any() and touching.any()
        for name in ("s_applied", "FD", "MD", "z_edge", "z_error"):
            assert np.isnan(f[name][()][free]).all() and np.isfinite(f[name][()][touching]).all(), name
        assert np.isnan(f["contact_point_W"][()][free]).all()
        assert np.isfinite(f["contact_point_W"][()][touching]).all()
        assert (f["FT"][()][free] == 0).all() and (f["force_W"][()][free] == 0).all()
    with open(tmp_path / "array" / "array.csv") as c:
        rows = list(csv.DictReader(c))
    free_rows = [r for r in rows if r["state"] == "free"]
    contact_rows = [r for r in rows if r["state"] == "contact"]
    assert free_rows and contact_rows
    for name in ("s_applied", "contact_point_W_x", "FD", "MD", "z_error"):
        assert all(r[name] == "" for r in free_rows) and all(r[name] != "" for r in contact_rows), name
    assert all(float(r["FT"]) == 0.0 for r in free_rows)

    write_views(tmp_path)
    subprocess.run([cli, "reconstruct", "--top", str(tmp_path / "top.csv"), "--front", str(tmp_path / "front.csv"),
                    "--calibration", str(tmp_path / "cams.json"), "-o", str(tmp_path / "recon.h5")],
                   check=True, capture_output=True)
    assert {"reconstructed", "reprojection_px"} <= set(assert_units_everywhere(tmp_path / "recon.h5"))


def test_trial_summary_records_the_declared_input_units(cli, tmp_path):
    """A trial file in mm, deg and ms: summary.json says so (its data were converted to SI on reading)."""
    synth = tmp_path / "synth.h5"
    run(cli, "synth", synth, "--duration", "0.1")
    t = vibrissa.read_trial(str(synth))
    lines = ["# vibrissa-trial: 1", "# units: length=mm angle=deg time=ms", "# base_radius: 0.1"]
    lines += ["# edge: " + " ".join(repr(v) for v in np.concatenate([e[:3] * 1e3, e[3:]])) for e in t.edges]
    lines += ["# rest_point: " + " ".join(repr(v) for v in p * 1e3) for p in t.rest_shape]
    lines.append("time,base_x,base_y,base_z,theta,phi,contact")
    for i in range(len(t)):
        row = [t.time[i] * 1e3, *(t.base_W[i] * 1e3), np.degrees(t.theta[i]), np.degrees(t.phi[i]), t.contact[i]]
        lines.append(",".join(repr(float(v)) for v in row))
    trial = tmp_path / "trial_mm.csv"
    trial.write_text("\n".join(lines) + "\n")
    out = tmp_path / "results"
    run(cli, "trial", trial, "--out", out, "--no-figures")
    summary = json.loads((out / "summary.json").read_text())
    assert summary["input_units"] == {"length": "mm", "angle": "deg", "time": "ms"}
    run(cli, "trial", synth, "--out", tmp_path / "results_si", "--no-figures")
    summary = json.loads((tmp_path / "results_si" / "summary.json").read_text())
    assert summary["input_units"] == {"length": "m", "angle": "rad", "time": "s"}


def test_mat_trial_files_carry_a_units_struct(cli, tmp_path):
    loadmat = pytest.importorskip("scipy.io").loadmat
    trial = tmp_path / "trial.mat"
    run(cli, "synth", trial, "--duration", "0.1", "--shapes")
    units = loadmat(trial, squeeze_me=True)["units"]
    names = set(units.dtype.names)
    assert {"time", "theta", "contact", "shape", "rest_shape", "edges"} <= names
    assert str(units["theta"].item()) == "rad" and str(units["time"].item()) == "s"
    assert str(units["shape"].item()) == "m" and str(units["contact"].item()) == "1"
    t = vibrissa.read_trial(str(trial))  # the reader ignores the struct
    assert len(t) > 0 and t.shape_W is not None
