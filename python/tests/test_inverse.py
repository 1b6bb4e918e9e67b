"""The base-wrench inverse from Python and the CLI (docs/inverse.md): round trips force mode -> base wrench ->
contact, reduced signal sets, the time-series batch with warm starts, and the `vibrissa solve` mode."""

import json
import subprocess

import numpy as np
import pytest

import vibrissa


def wrapped(a):
    return np.remainder(a + np.pi, 2 * np.pi) - np.pi


@pytest.mark.parametrize("s, f, zeta", [(0.006, 3e-5, 0.2), (0.015, 1e-4, -2.0), (0.022, 5e-5, 3.0)])
def test_round_trip_with_pose(whisker, s, f, zeta):
    pose = vibrissa.Pose(base=[0.01, -0.02, 0.005], theta=0.5, phi=-0.3, zeta=1.1)
    fwd = vibrissa.solve_force(whisker, f, s, zeta, pose=pose)
    inv = vibrissa.solve_base_wrench(whisker, fwd.force_W, fwd.moment_W, pose=pose)
    assert inv.solution.status == vibrissa.Status.converged
    assert inv.solution.arc_length == pytest.approx(s, rel=1e-9)
    assert inv.solution.force_magnitude == pytest.approx(f, rel=1e-9)
    assert abs(wrapped(inv.solution.angle - zeta)) < 1e-9
    np.testing.assert_allclose(inv.solution.contact_point_W, fwd.contact_point_W, atol=1e-12)
    assert inv.identifiability.identifiable and len(inv.roots) == 1
    assert inv.roots[0].arc_length == inv.solution.arc_length


def test_bending_only_is_flagged_underdetermined(whisker):
    fwd = vibrissa.solve_force(whisker, 1e-4, 0.015, 0.4)
    with pytest.warns(UserWarning, match=r"underdetermined: the signals bending \(2 equations\)"):
        inv = vibrissa.solve_base_wrench(whisker, fwd.force_W, fwd.moment_W, signals=["My", "Mz"])
    assert inv.solution.status == vibrissa.Status.underdetermined
    assert vibrissa.STATUS_NAMES[int(vibrissa.Status.underdetermined)] == "underdetermined"
    assert len(inv.warnings) == 1 and inv.warnings[0].startswith("underdetermined")
    assert inv.signals == "bending"
    assert not inv.identifiability.identifiable
    assert np.isinf(inv.identifiability.condition_number)
    assert np.linalg.norm(inv.identifiability.null_direction) == pytest.approx(1.0)
    assert np.all(inv.identifiability.covariance == 0.0)


def test_noise_shapes_and_errors(whisker):
    fwd = vibrissa.solve_force(whisker, 1e-4, 0.015, 0.4)
    sd = [1e-6, 1e-6, 1e-6, 1e-8, 1e-8, 1e-8]
    a = vibrissa.solve_base_wrench(whisker, fwd.force_W, fwd.moment_W, noise=sd)
    b = vibrissa.solve_base_wrench(whisker, fwd.force_W, fwd.moment_W, noise=np.diag(np.square(sd)))
    np.testing.assert_allclose(a.identifiability.covariance, b.identifiability.covariance, rtol=1e-12)
    with pytest.raises(ValueError, match="noise"):
        vibrissa.solve_base_wrench(whisker, fwd.force_W, fwd.moment_W, noise=[1e-6, 1e-6])
    with pytest.raises(ValueError, match="signals"):
        vibrissa.solve_base_wrench(whisker, fwd.force_W, fwd.moment_W, signals="Fq")
    with pytest.raises(ValueError, match="force_W"):
        vibrissa.solve_base_wrench(whisker, [1.0, 2.0], fwd.moment_W)


def test_batch_series_with_warm_starts_equals_single_solves(whisker):
    s = np.linspace(0.008, 0.02, 12)
    f = np.linspace(2e-5, 1e-4, 12)
    fwd = [vibrissa.solve_force(whisker, fk, sk, 0.5) for fk, sk in zip(f, s)]
    F = np.array([r.force_W for r in fwd])
    M = np.array([r.moment_W for r in fwd])
    one = vibrissa.solve_base_wrench_batch(whisker, F, M)
    assert one.status.shape == (12,) and one.converged.all()
    np.testing.assert_allclose(one.arc_length, s, rtol=1e-9)
    np.testing.assert_allclose(one.force_magnitude, f, rtol=1e-9)
    two = vibrissa.solve_base_wrench_batch(whisker, np.stack([F, F[::-1]]), np.stack([M, M[::-1]]), threads=2)
    assert two.arc_length.shape == (2, 12) and two.covariance.shape == (2, 12, 3, 3)
    np.testing.assert_allclose(two.arc_length[1], s[::-1], rtol=1e-9)
    for k in (0, 5, 11):
        single = vibrissa.solve_base_wrench(whisker, F[k], M[k])
        assert two.arc_length[0, k] == pytest.approx(single.solution.arc_length, rel=1e-9)
    with pytest.warns(UserWarning, match="12 of 12 fits are underdetermined"):
        bending = vibrissa.solve_base_wrench_batch(whisker, F, M, signals="bending")
    assert bending.underdetermined.all() and not bending.converged.any()


def test_cli_base_wrench_mode(cli, tmp_path, whisker):
    fwd = vibrissa.solve_force(whisker, 1e-4, 0.01815, -0.7)  # mid-link: at a node the map has a kink
    case = {"whisker": {"length": 0.03, "curvature": 20.0},
            "load": {"mode": "base_wrench", "force": fwd.force_W.tolist(), "moment": fwd.moment_W.tolist(),
                     "signals": "all", "noise": [1e-6, 1e-6, 1e-6, 1e-8, 1e-8, 1e-8]}}
    path = tmp_path / "case.json"
    path.write_text(json.dumps(case))
    out = json.loads(subprocess.run([cli, "solve", str(path)], check=True, capture_output=True, text=True).stdout)
    assert out["status"] == "converged"
    assert out["arc_length"] == pytest.approx(0.01815, rel=1e-9)
    assert out["force_magnitude"] == pytest.approx(1e-4, rel=1e-9)
    bw = out["base_wrench"]
    assert bw["signals"] == "all" and bw["identifiability"]["identifiable"]
    assert len(bw["roots"]) == 1 and np.shape(bw["identifiability"]["covariance"]) == (3, 3)
    case["load"]["signals"] = ["My", "Mz"]
    case["load"].pop("noise")
    path.write_text(json.dumps(case))
    run = subprocess.run([cli, "solve", str(path)], check=True, capture_output=True, text=True)
    out = json.loads(run.stdout)
    assert out["status"] == "underdetermined"
    assert out["warnings"][0].startswith("underdetermined: the signals bending")
    assert run.stderr.startswith("vibrissa: warning: underdetermined")
    assert out["base_wrench"]["identifiability"]["condition_number"] is None
    assert vibrissa.Case.from_file(str(path)).mode == "base_wrench"
    case["load"]["noise"] = [1e-6]
    path.write_text(json.dumps(case))
    bad = subprocess.run([cli, "solve", str(path)], capture_output=True, text=True)
    assert bad.returncode != 0 and "load.noise" in bad.stderr


def test_a_refused_frame_does_not_stop_the_batch(whisker):
    # Issue 23: a NaN force in frame 1 of series 1 is recorded (invalid_input, NaN) and every other frame is fit.
    fits = [vibrissa.solve_force(whisker, 1e-4, s, 0.3) for s in (0.01215, 0.01815, 0.02415)]
    F = np.array([[f.force_W for f in fits]] * 2)
    M = np.array([[f.moment_W for f in fits]] * 2)
    F[1, 1, 0] = np.nan
    with pytest.warns(UserWarning, match=r"1 of 6 frames refused.*series 1, frame 1: force must be finite"):
        batch = vibrissa.solve_base_wrench_batch(whisker, F, M)
    assert [(s, f) for s, f, _ in batch.errors] == [(1, 1)]
    assert vibrissa.STATUS_NAMES[batch.status[1, 1]] == "invalid_input" and np.isnan(batch.arc_length[1, 1])
    assert batch.results[1][1] is None
    assert batch.converged[0].all() and batch.converged[1, [0, 2]].all()
    np.testing.assert_allclose(batch.arc_length[1, [0, 2]], [0.01215, 0.02415], rtol=1e-9)
    with pytest.raises(ValueError, match=r"force must be finite.*\(series 1, frame 1\)"):
        vibrissa.solve_base_wrench_batch(whisker, F, M, on_error="raise")
