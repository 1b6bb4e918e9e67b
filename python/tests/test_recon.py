"""vibrissa.reconstruct (docs/python.md, "Reconstruction") is `vibrissa reconstruct`: the same files and
options give the same trial, value for value; flagged frames stay flagged; progress counts frames."""

import json
import subprocess

import numpy as np
import pytest

import vibrissa

K = np.array([[2400.0, 0.0, 320.0], [0.0, 2400.0, 240.0], [0.0, 0.0, 1.0]])
CAMERAS = {"top": (np.diag([1.0, -1.0, -1.0]), np.array([0.015, 0.01, 0.3])),
           "front": (np.array([[1.0, 0, 0], [0, 0, -1], [0, 1, 0]]), np.array([0.015, -0.3, 0.0]))}


def write_views(tmp_path, frames=12):
    """A 30 mm whisker y = 8 x^2 whisking about z, seen by two pinhole cameras; frame 5 lacks the front view."""
    cal = {"length_unit": "m", "cameras": {name: {"model": "pinhole", "K": K.tolist(), "R": R.tolist(),
                                                  "t": (-R @ C).tolist()} for name, (R, C) in CAMERAS.items()}}
    (tmp_path / "cams.json").write_text(json.dumps(cal))
    x = np.linspace(0.0, 0.03, 25)
    rows = {"top": ["frame,point,x_px,y_px"], "front": ["frame,point,x_px,y_px"]}
    for i in range(frames):
        th = np.radians(5.0 + 2.0 * i)
        pts = np.stack([x * np.cos(th) - 8 * x**2 * np.sin(th), x * np.sin(th) + 8 * x**2 * np.cos(th), 0 * x], 1)
        for name, (R, C) in CAMERAS.items():
            if name == "front" and i == 5:
                continue
            pc = (pts - C) @ R.T
            px = (pc[:, :2] / pc[:, 2:]) @ K[:2, :2].T + K[:2, 2]
            rows[name] += [f"{i},{k},{u:.6f},{v:.6f}" for k, (u, v) in enumerate(px)]
    for name, lines in rows.items():
        (tmp_path / f"{name}.csv").write_text("\n".join(lines) + "\n")


def test_python_and_cli_give_the_same_trial(cli, tmp_path):
    write_views(tmp_path)
    th = np.radians(5.0 + 2.0 * 8)  # a peg through the whisker's point at x = 20 mm in frame 8
    peg = [0.02 * np.cos(th) - 8 * 0.02**2 * np.sin(th), 0.02 * np.sin(th) + 8 * 0.02**2 * np.cos(th), 0.0]
    subprocess.run([cli, "reconstruct", "--top", str(tmp_path / "top.csv"), "--front", str(tmp_path / "front.csv"),
                    "--calibration", str(tmp_path / "cams.json"), "--peg-mm", *[repr(v * 1e3) for v in peg],
                    "-o", str(tmp_path / "cli.h5"), "--report", str(tmp_path / "cli.json")],
                   check=True, capture_output=True)
    seen = []
    trial, report = vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "front.csv", tmp_path / "cams.json",
                                         peg_m=peg, progress=lambda done, total: seen.append((done, total)))
    from_cli = vibrissa.read_trial(str(tmp_path / "cli.h5"))
    assert len(trial) == len(from_cli) == 12
    for name in ("time", "base_W", "theta", "phi", "zeta", "contact", "contact_W", "shape_W", "rest_shape"):
        np.testing.assert_array_equal(getattr(trial, name), getattr(from_cli, name), err_msg=name)
    assert report == json.loads((tmp_path / "cli.json").read_text())
    assert report["frames"][5]["status"] == "missing_view"
    # Every null of the report has its reason (docs/formats.md, "Nulls and their reasons").
    nulls = {f"/frames/{i}/{k}" for i, f in enumerate(report["frames"]) for k, v in f.items() if v is None}
    assert set(report["nan_reasons"]) == nulls
    assert report["nan_reasons"]["/frames/5/reprojection_px"].startswith("frame flagged 'missing_view'")
    free = next(i for i, f in enumerate(report["frames"]) if f["status"] == "ok" and f["contact_s_m"] is None)
    assert report["nan_reasons"][f"/frames/{free}/contact_s_m"].startswith("not in contact")
    assert np.isnan(trial.theta[5]) and np.isnan(trial.base_W[5]).all()
    assert seen and seen[-1] == (12, 12)
    assert trial.contact[8] == 1 and len(report["contact_periods"]) == 1
    ok = np.array([f["status"] == "ok" for f in report["frames"]])
    assert ok.sum() == 11
    np.testing.assert_allclose(trial.theta[ok], np.radians(5.0 + 2.0 * np.arange(12))[ok], atol=1e-4)


def test_reconstruction_columns_round_trip(tmp_path):
    """reconstructed, reprojection_px and likelihood: from the reconstruction, through every trial format, and
    from Python arrays; None on a trial without them."""
    write_views(tmp_path)
    th = np.radians(5.0 + 2.0 * 8)  # a peg through the whisker in frame 8: a trial file needs a contact period
    peg = [0.02 * np.cos(th) - 8 * 0.02**2 * np.sin(th), 0.02 * np.sin(th) + 8 * 0.02**2 * np.cos(th), 0.0]
    trial, _ = vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "front.csv", tmp_path / "cams.json", peg_m=peg)
    assert trial.reconstructed.dtype == np.uint8
    np.testing.assert_array_equal(trial.reconstructed, [1] * 5 + [0] + [1] * 6)  # frame 5 lacks the front view
    assert np.isnan(trial.reprojection_px[5]) and np.all(trial.reprojection_px[trial.reconstructed == 1] < 1e-3)
    np.testing.assert_array_equal(trial.likelihood[trial.reconstructed == 1], 1.0)  # plain CSV: likelihood 1
    for ext in ("csv", "h5", "mat"):
        trial.write(str(tmp_path / f"t.{ext}"))
        again = vibrissa.read_trial(str(tmp_path / f"t.{ext}"))
        for name in ("reconstructed", "reprojection_px", "likelihood"):
            np.testing.assert_array_equal(getattr(again, name), getattr(trial, name), err_msg=f"{name} .{ext}")
    mine = vibrissa.Trial(time=trial.time, base_W=trial.base_W, theta=trial.theta, phi=trial.phi,
                          contact=trial.contact, rest_shape=trial.rest_shape, edges=[0, 0, 0, 0, 0, 1],
                          reconstructed=trial.reconstructed, reprojection_px=trial.reprojection_px,
                          likelihood=np.full(12, 0.5))
    np.testing.assert_array_equal(mine.reconstructed, trial.reconstructed)
    np.testing.assert_array_equal(mine.likelihood, 0.5)
    plain = vibrissa.synthesize_trial(duration=0.05)
    assert plain.reconstructed is None and plain.reprojection_px is None and plain.likelihood is None
    bad = dict(time=trial.time, base_W=trial.base_W, theta=trial.theta, phi=trial.phi, contact=trial.contact,
               rest_shape=trial.rest_shape, edges=[0, 0, 0, 0, 0, 1])
    for kw, message in ((dict(reconstructed=np.full(12, 2)), "reconstructed must hold only 0 and 1, got 2.0"),
                        (dict(likelihood=np.ones(3)), "likelihood")):
        try:
            vibrissa.Trial(**bad, **kw)
        except ValueError as e:
            assert message in str(e), str(e)
        else:
            raise AssertionError(f"{kw} accepted")


def test_a_track_file_that_crashes_libhdf5_is_an_error_of_the_cli(cli, tmp_path):
    """libhdf5 divides by zero on this fuzzed DeepLabCut file on x86 (tests/data/deeplabcut/README.md); the CLI, a
    single-threaded process, reads it in a child process first and exits 1 naming it. (The Python package runs
    its calls on a worker thread, so it does not fork for this: docs/formats.md.)"""
    import pathlib
    crash = pathlib.Path(__file__).resolve().parents[2] / "tests/data/deeplabcut/libhdf5_crash_fpe.h5"
    write_views(tmp_path)
    run = subprocess.run([cli, "reconstruct", "--top", str(crash), "--front", str(tmp_path / "front.csv"),
                          "--calibration", str(tmp_path / "cams.json"), "-o", str(tmp_path / "t.h5")],
                         capture_output=True, text=True)
    assert run.returncode == 1, (run.returncode, run.stderr)
    assert run.stderr.startswith(f"vibrissa: error: {crash}: "), run.stderr
    assert not (tmp_path / "t.h5").exists()


SIDE = {"side": (np.array([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]]), np.array([0.315, 0.01, 0.0]))}


def write_three_views(tmp_path, frames=12, sigma=0.3, seed=7):
    """write_views' whisker seen by a third camera too (looking along -x), with Gaussian pixel noise."""
    rng = np.random.default_rng(seed)
    cams = {**CAMERAS, **SIDE}
    cal = {"length_unit": "m", "cameras": {name: {"model": "pinhole", "K": K.tolist(), "R": R.tolist(),
                                                  "t": (-R @ C).tolist()} for name, (R, C) in cams.items()}}
    (tmp_path / "cams3.json").write_text(json.dumps(cal))
    x = np.linspace(0.0, 0.03, 25)
    for name, (R, C) in cams.items():
        lines = ["frame,point,x_px,y_px"]
        for i in range(frames):
            th = np.radians(5.0 + 2.0 * i)
            pts = np.stack([x * np.cos(th) - 8 * x**2 * np.sin(th), x * np.sin(th) + 8 * x**2 * np.cos(th),
                            0.004 * x / 0.03], 1)
            pc = (pts - C) @ R.T
            px = (pc[:, :2] / pc[:, 2:]) @ K[:2, :2].T + K[:2, 2] + rng.normal(0.0, sigma, (len(x), 2))
            lines += [f"{i},{k},{u:.6f},{v:.6f}" for k, (u, v) in enumerate(px)]
        (tmp_path / f"{name}3.csv").write_text("\n".join(lines) + "\n")


def test_three_named_views_in_python_and_the_cli(cli, tmp_path):
    write_three_views(tmp_path)
    views = {name: tmp_path / f"{name}3.csv" for name in ("top", "front", "side")}
    th = np.radians(5.0 + 2.0 * 8)  # a peg through the whisker's point at x = 20 mm in frame 8
    peg = [0.02 * np.cos(th) - 8 * 0.02**2 * np.sin(th), 0.02 * np.sin(th) + 8 * 0.02**2 * np.cos(th), 0.0]
    subprocess.run([cli, "reconstruct", *[a for n, p in views.items() for a in ("--view", f"{n}={p}")],
                    "--calibration", str(tmp_path / "cams3.json"), "--peg-mm", *[repr(v * 1e3) for v in peg],
                    "-o", str(tmp_path / "cli3.h5"), "--report", str(tmp_path / "cli3.json")],
                   check=True, capture_output=True)
    trial, report = vibrissa.reconstruct(views=views, calibration=tmp_path / "cams3.json", peg_m=peg)
    from_cli = vibrissa.read_trial(str(tmp_path / "cli3.h5"))
    for name in ("base_W", "theta", "phi", "shape_W"):
        np.testing.assert_array_equal(getattr(trial, name), getattr(from_cli, name), err_msg=name)
    assert report == json.loads((tmp_path / "cli3.json").read_text())
    assert report["views"] == ["top", "front", "side"]
    assert set(report["frames"][0]["view_reprojection_px"]) == {"top", "front", "side"}
    assert [p["views"] for p in report["checks"]["view_pairs"]] == [["top", "front"], ["top", "side"], ["front", "side"]]
    assert 0.2 < report["checks"]["view_reprojection_px_median"]["side"] < 0.45  # about the 0.3 px noise
    assert trial.reconstructed.all()
    # The shorthands are the views named top and front: the same trial.
    trial2, _ = vibrissa.reconstruct(tmp_path / "top3.csv", tmp_path / "front3.csv", tmp_path / "cams3.json",
                                     views={"side": views["side"]}, peg_m=peg)
    np.testing.assert_array_equal(trial2.shape_W, trial.shape_W)


def test_a_view_without_a_camera_of_its_name_is_an_error_naming_it(cli, tmp_path):
    write_three_views(tmp_path, frames=3)
    run = subprocess.run([cli, "reconstruct", "--view", f"top={tmp_path / 'top3.csv'}", "--view",
                          f"sid={tmp_path / 'side3.csv'}", "--calibration", str(tmp_path / "cams3.json"),
                          "-o", str(tmp_path / "x.h5")], capture_output=True, text=True)
    assert run.returncode == 1
    assert "'cameras.sid': no camera of that name for view 'sid'" in run.stderr
    assert "the calibration has 'front', 'side', 'top'" in run.stderr
    with pytest.raises(ValueError, match="no camera of that name for view 'sid'"):
        vibrissa.reconstruct(views={"top": tmp_path / "top3.csv", "sid": tmp_path / "side3.csv"},
                             calibration=tmp_path / "cams3.json")
    with pytest.raises(ValueError, match="at least two camera views"):
        vibrissa.reconstruct(views={"top": tmp_path / "top3.csv"}, calibration=tmp_path / "cams3.json")


def test_the_cli_consistency_options_in_python(tmp_path):
    """front_frame_offset, min_yield, max_unpaired, max_epipolar_px: the CLI's defaults, errors and effect."""
    write_views(tmp_path, frames=20)
    lines = (tmp_path / "front.csv").read_text().splitlines()
    late = [lines[0]] + [f"{int(r.split(',')[0]) - 4},{r.split(',', 1)[1]}" for r in lines[1:] if int(r.split(",")[0]) >= 4]
    (tmp_path / "late.csv").write_text("\n".join(late) + "\n")  # the front video starts 4 frames later
    with pytest.raises(RuntimeError, match="out of step"):
        vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "late.csv", tmp_path / "cams.json")
    trial, report = vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "late.csv", tmp_path / "cams.json",
                                         front_frame_offset=4)
    assert report["checks"]["problems"] == [] and trial.reconstructed.sum() >= 14
    trial2, _ = vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "late.csv", tmp_path / "cams.json",
                                     frame_offsets={"front": 4})
    np.testing.assert_array_equal(trial2.shape_W, trial.shape_W)
    vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "late.csv", tmp_path / "cams.json", max_unpaired=1.0)
    with pytest.raises(ValueError, match="min_yield must be in"):
        vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "front.csv", tmp_path / "cams.json", min_yield=2.0)
    with pytest.raises(ValueError, match="max_epipolar_px must be > 0"):
        vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "front.csv", tmp_path / "cams.json", max_epipolar_px=0)
    with pytest.raises(RuntimeError, match="only 0 of the 19 frames"):
        vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "front.csv", tmp_path / "cams.json", min_yield=1.0,
                             max_reprojection_px=1e-9)


def test_unit_names_of_contact_threshold_and_base_jump(tmp_path):
    write_views(tmp_path)
    new, _ = vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "front.csv", tmp_path / "cams.json",
                                  contact_threshold_m=2e-4, base_jump_m=2e-3)
    with pytest.warns(DeprecationWarning, match="contact_threshold_m="):
        old, _ = vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "front.csv", tmp_path / "cams.json",
                                      contact_threshold=2e-4, base_jump_m=2e-3)
    with pytest.warns(DeprecationWarning, match="base_jump_m="):
        vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "front.csv", tmp_path / "cams.json", base_jump=2e-3)
    np.testing.assert_array_equal(new.shape_W, old.shape_W)
    with pytest.raises(TypeError, match="both contact_threshold_m and its deprecated name"):
        vibrissa.reconstruct(tmp_path / "top.csv", tmp_path / "front.csv", tmp_path / "cams.json",
                             contact_threshold=2e-4, contact_threshold_m=2e-4)
