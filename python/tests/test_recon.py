"""vibrissa.reconstruct (docs/python.md, "Reconstruction") is `vibrissa reconstruct`: the same files and
options give the same trial, value for value; flagged frames stay flagged; progress counts frames."""

import json
import struct
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


WHISKERS = {"C1": (0.0, 5.0), "C2": (0.003, 15.0), "C3": (0.006, 25.0)}  # base y [m], theta at frame 0 [deg]


def whisker_points(name, i, n=15):
    """Whisker `name` in frame i: a 30 mm whisker y = 8 x^2 whose base is WHISKERS[name][0] along y."""
    dy, th0 = WHISKERS[name]
    x = np.linspace(0.0, 0.03, n)
    th = np.radians(th0 + 2.0 * i)
    return np.stack([x * np.cos(th) - 8 * x**2 * np.sin(th), dy + x * np.sin(th) + 8 * x**2 * np.cos(th), 0 * x], 1)


def pegs_mm(names):
    """One peg per whisker, through its point 20 mm out in frame 6 (every trial needs a contact period)."""
    return [a for w in names for a in ("--peg-mm", *[repr(v * 1e3) for v in whisker_points(w, 6, n=4)[2]])]


def pegs_m(names):
    return [whisker_points(w, 6, n=4)[2] for w in names]


def pixels(name, pts):
    R, C = CAMERAS[name]
    pc = (pts - C) @ R.T
    return (pc[:, :2] / pc[:, 2:]) @ K[:2, :2].T + K[:2, 2]


def write_dlc_whiskers(tmp_path, frames=10):
    """Both views as DeepLabCut CSVs whose keypoints name three whiskers (c1_0 ... c3_14), in shuffled order."""
    write_views(tmp_path, frames=1)  # the calibration
    parts = [f"{w.lower()}_{k}" for w in WHISKERS for k in range(15)]
    order = np.random.default_rng(1).permutation(len(parts))
    for view in ("top", "front"):
        head = ["scorer," + ",".join(["dlc"] * 3 * len(parts)),
                "bodyparts," + ",".join(parts[j] for j in order for _ in range(3)),
                "coords," + ",".join(["x", "y", "likelihood"] * len(parts))]
        rows = []
        for i in range(frames):
            px = {w: pixels(view, whisker_points(w, i)) for w in WHISKERS}
            cells = []
            for j in order:
                w, k = parts[j].split("_")
                u, v = px[w.upper()][int(k)]
                cells += [f"{u:.6f}", f"{v:.6f}", "0.99"]
            rows.append(f"{i}," + ",".join(cells))
        (tmp_path / f"{view}_dlc.csv").write_text("\n".join(head + rows) + "\n")


def test_several_whiskers_of_deeplabcut_keypoints(cli, tmp_path):
    write_dlc_whiskers(tmp_path)
    spec = {w: [f"{w.lower()}_{k}" for k in range(15)] for w in WHISKERS}
    run = subprocess.run([cli, "reconstruct", "--top", str(tmp_path / "top_dlc.csv"), "--front",
                          str(tmp_path / "front_dlc.csv"), "--calibration", str(tmp_path / "cams.json"),
                          *[a for w, parts in spec.items() for a in ("--whisker", f"{w}={','.join(parts)}")],
                          *pegs_mm(WHISKERS),
                          "-o", str(tmp_path / "out" / "trial.h5"), "--report", str(tmp_path / "out" / "report.json")],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    table = [line.split("\t") for line in run.stdout.splitlines() if "\t" in line]
    assert table[0][:3] == ["whisker", "frames", "reconstructed"]
    assert [(r[0], r[1], r[2]) for r in table[1:]] == [(w, "10", "10") for w in WHISKERS]
    results = vibrissa.reconstruct(tmp_path / "top_dlc.csv", tmp_path / "front_dlc.csv", tmp_path / "cams.json",
                                   whiskers=spec, peg_m=pegs_m(WHISKERS))
    assert list(results) == list(WHISKERS)
    for w, (trial, report) in results.items():
        from_cli = vibrissa.read_trial(str(tmp_path / "out" / w / "trial.h5"))
        np.testing.assert_array_equal(trial.shape_W, from_cli.shape_W)
        cli_report = json.loads((tmp_path / "out" / w / "report.json").read_text())
        assert report["checks"] == cli_report["checks"]  # (the pegs differ in the last bit: mm -> m)
        assert [f["status"] for f in report["frames"]] == [f["status"] for f in cli_report["frames"]]
        for i in range(10):  # each whisker is itself, not a neighbour
            np.testing.assert_allclose(trial.base_W[i], whisker_points(w, i)[0], atol=1e-6)
    # A whisker whose keypoints are not in the files fails by name; the others are still written.
    run = subprocess.run([cli, "reconstruct", "--top", str(tmp_path / "top_dlc.csv"), "--front",
                          str(tmp_path / "front_dlc.csv"), "--calibration", str(tmp_path / "cams.json"),
                          "--whisker", "C1=" + ",".join(spec["C1"]), "--whisker", "D1=d1_0,d1_1,d1_2", *pegs_mm(WHISKERS),
                          "-o", str(tmp_path / "out2" / "trial.h5")], capture_output=True, text=True)
    assert run.returncode == 1
    assert "1 of 2 whiskers failed" in run.stderr and "whisker 'D1'" in run.stderr and "d1_0" in run.stderr
    assert (tmp_path / "out2" / "C1" / "trial.h5").exists()
    with pytest.raises(RuntimeError, match="whisker 'D1'"):
        vibrissa.reconstruct(tmp_path / "top_dlc.csv", tmp_path / "front_dlc.csv", tmp_path / "cams.json",
                             whiskers={"D1": "d1_0,d1_1,d1_2"})


def write_janelia(path_whiskers, path_measurements, view, frames):
    """Text .whiskers (whisker1) with whiskers C1 and C2 as segments 0 and 1 of each frame, stored tip first,
    and measv3 measurements labelling them 7 and 3 (a third segment, noise, is labelled -1)."""
    lines = ["whisker1 (frame,id,time,n,x1,y1,thick1,score1...)"]
    rows = []  # (frame, segment, label, follicle x, y)
    for i in range(frames):
        for seg, (w, label) in enumerate((("C1", 7), ("C2", 3), (None, -1))):
            px = pixels(view, whisker_points(w, i)) if w else np.array([[5.0, 5.0], [6.0, 6.0], [7.0, 7.0]])
            tip_first = px[::-1]
            cells = [f"{u:.6f},{v:.6f},1,1" for u, v in tip_first]
            lines.append(f"{i},{seg},{i},{len(px)}," + ",".join(cells))
            rows.append((i, seg, label, *px[0]))
    path_whiskers.write_text("\n".join(lines) + "\n")
    data = bytearray(b"measv3\0\0") + struct.pack("<ii", len(rows), 2)
    for fid, wid, state, fx, fy in reversed(rows):  # written last row first
        data += struct.pack("<10i", 0, fid, wid, state, 0, 0, 0, 1, 0, 2) + b"x" + struct.pack("<4d", fx, fy, 0.0, 0.0)
    path_measurements.write_bytes(bytes(data))


def test_several_whiskers_of_janelia_labels(cli, tmp_path):
    write_views(tmp_path, frames=1)  # the calibration
    for view in ("top", "front"):
        write_janelia(tmp_path / f"{view}.whiskers", tmp_path / f"{view}.measurements", view, frames=8)
    args = [cli, "reconstruct", "--view", f"top={tmp_path / 'top.whiskers'}", "--view",
            f"front={tmp_path / 'front.whiskers'}", "--measurements", f"top={tmp_path / 'top.measurements'}",
            "--measurements", f"front={tmp_path / 'front.measurements'}", "--calibration", str(tmp_path / "cams.json"),
            *pegs_mm(["C1", "C2"])]
    run = subprocess.run(args + ["--all-whiskers", "-o", str(tmp_path / "j" / "t.h5")], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert sorted(p.name for p in (tmp_path / "j").iterdir()) == ["3", "7"]  # every label, by label
    results = vibrissa.reconstruct(views={"top": tmp_path / "top.whiskers", "front": tmp_path / "front.whiskers"},
                                   measurements={"top": tmp_path / "top.measurements",
                                                 "front": tmp_path / "front.measurements"},
                                   calibration=tmp_path / "cams.json", whiskers={"C1": 7, "C2": 3},
                                   peg_m=pegs_m(["C1", "C2"]))
    for w, label in (("C1", "7"), ("C2", "3")):
        trial, _ = results[w]
        np.testing.assert_array_equal(trial.shape_W, vibrissa.read_trial(str(tmp_path / "j" / label / "t.h5")).shape_W)
        for i in range(8):
            np.testing.assert_allclose(trial.base_W[i], whisker_points(w, i)[0], atol=1e-6)
