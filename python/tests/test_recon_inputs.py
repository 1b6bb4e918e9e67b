"""vibrissa.reconstruct takes tracks as Python users hold them (docs/python.md, "Reconstruction"): a pandas
DataFrame in DeepLabCut's layout (single- and multi-animal) or a NumPy array gives the same trial, value for
value, as the same points in a track file; a missing file is FileNotFoundError."""

import json
import subprocess
import warnings

import numpy as np
import pandas as pd
import pytest

import vibrissa

K = np.array([[2000.0, 0.0, 320.0], [0.0, 2000.0, 240.0], [0.0, 0.0, 1.0]])
CAMERAS = {"top": (np.diag([1.0, -1.0, -1.0]), np.array([0.012, 0.01, 0.25])),
           "front": (np.array([[1.0, 0, 0], [0, 0, -1], [0, 1, 0]]), np.array([0.012, -0.25, 0.0]))}
FRAMES, POINTS = 8, 20


def views(tmp_path):
    """A 25 mm whisker y = 10 x^2 turning about z, projected into both cameras: {view: (F, P, 2) pixels}, with
    frame 3's tip not tracked in the top view; writes the calibration and the plain CSV of each view."""
    cal = {"length_unit": "m", "cameras": {name: {"model": "pinhole", "K": K.tolist(), "R": R.tolist(),
                                                  "t": (-R @ C).tolist()} for name, (R, C) in CAMERAS.items()}}
    (tmp_path / "cams.json").write_text(json.dumps(cal))
    x = np.linspace(0.0, 0.025, POINTS)
    px = {name: np.empty((FRAMES, POINTS, 2)) for name in CAMERAS}
    for i in range(FRAMES):
        th = np.radians(10.0 + 3.0 * i)
        pts = np.stack([x * np.cos(th) - 10 * x**2 * np.sin(th), x * np.sin(th) + 10 * x**2 * np.cos(th), 0 * x], 1)
        for name, (R, C) in CAMERAS.items():
            pc = (pts - C) @ R.T
            px[name][i] = (pc[:, :2] / pc[:, 2:]) @ K[:2, :2].T + K[:2, 2]
    px["top"][3, -1] = np.nan
    for name, a in px.items():
        rows = ["frame,point,x_px,y_px"] + [f"{f},{p},{u!r},{v!r}" for f in range(FRAMES) for p, (u, v) in
                                            enumerate(a[f]) if np.isfinite(u)]
        (tmp_path / f"{name}.csv").write_text("\n".join(rows) + "\n")
    return px


def dlc_frame(a, individuals=None, scorer="DLC_resnet50_whiskerNov1shuffle1_100000"):
    """DeepLabCut's DataFrame of (F, P, 2) pixels, likelihood 1 (0 where not tracked); with `individuals`
    {name: array} the multi-animal layout."""
    blocks = individuals or {None: a}
    data, keys = [], []
    for who, arr in blocks.items():
        for p in range(arr.shape[1]):
            for c, col in (("x", arr[:, p, 0]), ("y", arr[:, p, 1]),
                           ("likelihood", np.where(np.isfinite(arr[:, p, 0]), 1.0, 0.0))):
                data.append(col)
                keys.append((scorer, f"w{p}", c) if who is None else (scorer, who, f"w{p}", c))
    names = ["scorer", "bodyparts", "coords"] if individuals is None else ["scorer", "individuals", "bodyparts",
                                                                            "coords"]
    return pd.DataFrame(np.array(data).T, columns=pd.MultiIndex.from_tuples(keys, names=names))


def same_trial(a, b):
    assert len(a) == len(b) == FRAMES
    for name in ("time", "base_W", "theta", "phi", "zeta", "shape_W", "rest_shape"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


def test_numpy_arrays_and_dataframes_give_the_trial_of_the_files(tmp_path):
    px = views(tmp_path)
    cams = tmp_path / "cams.json"
    from_files, report = vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "front.csv", cams)
    assert sum(f["status"] == "ok" for f in report["frames"]) >= FRAMES - 1
    from_arrays, _ = vibrissa.reconstruct(px["top"], px["front"], cams)
    same_trial(from_arrays, from_files)
    # (F, P, 3) with a likelihood column: points below min_likelihood are dropped like missing ones.
    with_l = {n: np.concatenate([a, np.ones(a.shape[:2] + (1,))], axis=2) for n, a in px.items()}
    same_trial(vibrissa.reconstruct(with_l["top"], with_l["front"], cams)[0], from_files)
    # DeepLabCut's single-animal DataFrame (the tip of frame 3 NaN at likelihood 0: not tracked).
    top_df, front_df = dlc_frame(px["top"]), dlc_frame(px["front"])
    from_frames, report_df = vibrissa.reconstruct(top_df, front_df, cams)
    same_trial(from_frames, from_files)
    assert from_frames.source == "top: pandas DataFrame"
    # The multi-animal layout: the individual is chosen by name, the other one ignored.
    junk = px["top"][:, ::-1] + 50.0
    multi_top = dlc_frame(None, {"mouse1": junk, "mouse2": px["top"]})
    multi_front = dlc_frame(None, {"mouse1": px["front"] + 30.0, "mouse2": px["front"]})
    same_trial(vibrissa.reconstruct(multi_top, multi_front, cams, individual="mouse2")[0], from_files)
    with pytest.raises(ValueError, match="2 individuals: choose one"):
        vibrissa.reconstruct(multi_top, multi_front, cams)
    # A frame index that is not 0.. is the frame number, as in DeepLabCut's CSV.
    shifted = [df.set_index(pd.RangeIndex(100, 100 + FRAMES)) for df in (top_df, front_df)]
    trial, report = vibrissa.reconstruct(*shifted, cams)
    assert [f["frame"] for f in report["frames"]] == list(range(100, 100 + FRAMES))


def test_bad_inputs_name_the_argument(tmp_path):
    px = views(tmp_path)
    cams = tmp_path / "cams.json"
    with pytest.raises(FileNotFoundError, match="top"):
        vibrissa.reconstruct(tmp_path / "missing.csv", tmp_path / "front.csv", cams)
    with pytest.raises(FileNotFoundError, match="calibration"):
        vibrissa.reconstruct(px["top"], px["front"], tmp_path / "missing.json")
    with pytest.raises(FileNotFoundError, match="front_measurements"):
        vibrissa.reconstruct(px["top"], px["front"], cams, front_measurements=tmp_path / "none.measurements")
    with pytest.raises(ValueError, match=r"front: a NumPy track array has shape .* got \(8, 20\)"):
        vibrissa.reconstruct(px["top"], px["front"][..., 0], cams)
    flat = pd.DataFrame(px["top"].reshape(FRAMES, -1))
    with pytest.raises(ValueError, match="top: a DataFrame in DeepLabCut's layout"):
        vibrissa.reconstruct(flat, px["front"], cams)
    with pytest.raises(TypeError, match="front: expected a path"):
        vibrissa.reconstruct(px["top"], 42, cams)


def test_a_peg_in_mm_given_as_metres_is_warned_and_peg_is_renamed_peg_m(tmp_path):
    px = views(tmp_path)
    cams = tmp_path / "cams.json"
    th = np.radians(10.0 + 3.0 * 4)  # a peg through the whisker's point at x = 15 mm in frame 4
    peg_m = [0.015 * np.cos(th) - 10 * 0.015**2 * np.sin(th), 0.015 * np.sin(th) + 10 * 0.015**2 * np.cos(th), 0.0]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        trial, report = vibrissa.reconstruct(px["top"], px["front"], cams, peg_m=peg_m)
    assert report["warnings"] == [] and trial.contact.any()
    with pytest.warns(DeprecationWarning, match=r"reconstruct\(peg=...\) is deprecated .* use peg_m="):
        old, _ = vibrissa.reconstruct(px["top"], px["front"], cams, peg=peg_m)
    np.testing.assert_array_equal(old.contact, trial.contact)
    # The same peg in millimetres given as metres: no contact frame, and a warning saying why.
    with pytest.warns(UserWarning, match=r"edge 1 \(peg\) passes .* m from the whisker base, beyond the reach of a "
                                         r"2[0-9.]+ mm whisker .* positions in mm given as metres\?"):
        trial, report = vibrissa.reconstruct(px["top"], px["front"], cams, peg_m=np.array(peg_m) * 1e3)
    assert not trial.contact.any() and len(report["warnings"]) == 1
    with pytest.raises(TypeError, match="both peg_m and its deprecated name peg"):
        vibrissa.reconstruct(px["top"], px["front"], cams, peg_m=peg_m, peg=peg_m)


def test_the_cli_prints_and_reports_the_same_warning(cli, tmp_path):
    views(tmp_path)
    run = subprocess.run([cli, "reconstruct", "--top", str(tmp_path / "top.csv"),
                          "--front", str(tmp_path / "front.csv"), "--calibration", str(tmp_path / "cams.json"),
                          "--peg-mm", "16600", "11200", "0",
                          "-o", str(tmp_path / "t.h5"), "--report", str(tmp_path / "r.json")],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    report = json.loads((tmp_path / "r.json").read_text())
    assert len(report["warnings"]) == 1 and report["warnings"][0].startswith("edge 1 (peg) passes 20.0")
    assert f"vibrissa reconstruct: warning: {report['warnings'][0]}" in run.stderr
