"""Batch solves equal the loop of single solves (to 1e-12), whatever the thread count and layout."""

import numpy as np
import pytest

import vibrissa
from interrupting import interrupt
from vibrissa import Edge, Pose, SolveOptions, Status, WhiskerProperties

FIELDS = ("force_magnitude", "arc_length", "angle", "contact_point_W", "force_W", "moment_W", "residual")


def assert_matches(batch, index, sol, tol=1e-12):
    assert batch.status[index] == int(sol.status)
    assert batch.iterations[index] == sol.iterations
    for name in FIELDS:
        np.testing.assert_allclose(getattr(batch, name)[index], getattr(sol, name), rtol=tol, atol=0.0, err_msg=name)
    for name in ("Fx", "Mx", "FT", "MB", "FD", "MD", "force", "moment"):
        np.testing.assert_allclose(getattr(batch.whisker_frame, name)[index], getattr(sol.whisker_frame, name),
                                   rtol=tol, atol=0.0, err_msg=name)
    for name in ("normal_force", "edge_force"):
        v = getattr(sol, name)
        if v is None:
            assert np.isnan(getattr(batch, name)[index])
        else:
            assert getattr(batch, name)[index] == pytest.approx(v, rel=tol, abs=0.0)


def loop_point(w, points, warm_start):
    out, warm = [], None
    for p in points:
        s = vibrissa.solve_point(w, p, warm=warm if warm_start else None)
        warm = s if s.converged else None
        out.append(s)
    return out


@pytest.mark.parametrize("warm_start", [True, False])
def test_point_batch_equals_loop(small_whisker, peg_track, warm_start):
    batch = vibrissa.solve_point_batch(small_whisker, peg_track, warm_start=warm_start, shapes=True)
    assert batch.frames_shape == (12,) and batch.shape_W.shape == (12, 41, 3)
    for i, s in enumerate(loop_point(small_whisker, peg_track, warm_start)):
        assert_matches(batch, i, s)
        np.testing.assert_allclose(batch.shape_W[i], s.shape_W, rtol=1e-12, atol=1e-300)
    assert batch.converged.all()


def test_warm_start_continues_the_root_and_saves_iterations(small_whisker):
    # The peg track's path in 100 frames (0.03 mm apart, as at 1 kHz): cold solves start from the cantilever
    # guess, which on the 12-frame track (0.27 mm apart) is as near the root as the previous frame.
    f = np.linspace(0.0, 1.0, 100)
    track = np.column_stack([0.02 - 0.002 * f, 0.004 + 0.002 * f, 0.001 * f])
    warm = vibrissa.solve_point_batch(small_whisker, track, warm_start=True)
    cold = vibrissa.solve_point_batch(small_whisker, track, warm_start=False)
    assert warm.iterations[1:].sum() < cold.iterations[1:].sum()
    # ... and continues the same root: where on the whisker the contact is, and its load, agree with the cold
    # solve's in every frame (the contact point itself is the target in both)
    np.testing.assert_array_equal(warm.status, cold.status)
    np.testing.assert_allclose(warm.arc_length, cold.arc_length, rtol=0, atol=1e-9)
    np.testing.assert_allclose(warm.force_magnitude, cold.force_magnitude, rtol=1e-6)


def test_thread_count_does_not_change_results(small_whisker, peg_track):
    series = np.stack([peg_track + [0.0, 1e-4 * k, 0.0] for k in range(6)])
    one = vibrissa.solve_point_batch(small_whisker, series, threads=1)
    two = vibrissa.solve_point_batch(small_whisker, series, threads=2)
    for name in ("status", "force_magnitude", "contact_point_W", "state", "iterations"):
        np.testing.assert_array_equal(getattr(one, name), getattr(two, name))
    cold1 = vibrissa.solve_point_batch(small_whisker, series, warm_start=False, threads=1)
    cold2 = vibrissa.solve_point_batch(small_whisker, series, warm_start=False, threads=3)
    np.testing.assert_array_equal(cold1.force_W, cold2.force_W)


def test_many_whiskers_and_series_axis(small_whisker, peg_track):
    whiskers = [small_whisker.placed(Pose(theta=t)) for t in (0.0, 0.02, -0.02)]
    batch = vibrissa.solve_point_batch(whiskers, peg_track)  # (F, 3) shared by 3 series
    assert batch.frames_shape == (3, 12)
    for k, w in enumerate(whiskers):
        for i, s in enumerate(loop_point(w, peg_track, True)):
            assert_matches(batch, (k, i), s)


def test_poses_per_frame(small_whisker, peg_track):
    angles = np.column_stack([np.linspace(0, 0.05, 12), np.zeros(12), np.zeros(12)])
    base = np.tile([0.0, 0.0, 1e-4], (12, 1))
    batch = vibrissa.solve_point_batch(small_whisker, peg_track, pose_angles=angles, pose_base=base,
                                       warm_start=False)
    for i in range(12):
        w = small_whisker.placed(Pose(base=base[i], theta=angles[i, 0]))
        assert_matches(batch, i, vibrissa.solve_point(w, peg_track[i]))


def test_edge_batch_equals_loop(small_whisker):
    F = 10
    points = np.column_stack([np.full(F, 0.018), np.linspace(0.003, 0.006, F), np.zeros(F)])
    direction = np.array([0.0, 0.1, 1.0], dtype=np.float32)  # (3,) shared, float32
    approach = [0.0, 1.0, 0.0]  # F · approach < 0 for these contacts (solve_edge docs)
    batch = vibrissa.solve_edge_batch(small_whisker, points, direction, approach_W=approach)
    warm = None
    for i in range(F):
        s = vibrissa.solve_edge(small_whisker, Edge(points[i], direction.astype(np.float64)), warm=warm,
                                approach_W=approach)
        warm = s if s.converged else None
        assert_matches(batch, i, s)
    assert np.all(batch.converged[1:])
    assert np.all(np.abs(batch.edge_force[batch.converged]) < 1e-12)


def test_frictional_edge_batch_equals_loop(small_whisker):
    F = 10
    points = np.column_stack([np.full(F, 0.018), np.linspace(0.003, 0.006, F), np.zeros(F)])
    direction = np.array([0.0, 0.6, 0.8])  # unit to the last bit: the tracker's normalised edge is the same
    mu = 0.3
    batch = vibrissa.solve_frictional_edge_batch(small_whisker, points, direction, mu)
    # The tracker's policy (docs/conventions.md): friction starts where the rest whisker is nearest the edge
    # line, then follows the last converged contact; a lost frame restarts from the nearest point.
    prev, warm = None, None
    for i in range(F):
        edge = Edge(points[i], direction)
        if prev is None:
            prev = vibrissa.nearest_rest_point(small_whisker, edge)["on_edge_W"]
        s = vibrissa.solve_frictional_edge(small_whisker, edge, mu, prev, warm=warm)
        prev = s.contact_point_W if s.converged else None
        warm = s if s.converged else None
        assert_matches(batch, i, s)
    ok = batch.converged
    assert ok.any()
    assert np.all(np.abs(batch.edge_force[ok]) <= mu * batch.normal_force[ok] * (1 + 1e-9))


def test_force_batch_equals_loop(small_whisker):
    forces = np.linspace(0.0, 2e-4, 8)
    angles = np.linspace(-1.0, 1.0, 8)
    batch = vibrissa.solve_force_batch(small_whisker, forces, 0.015, angles, shapes=True)
    for i in range(8):
        s = vibrissa.solve_force(small_whisker, forces[i], 0.015, angles[i])
        assert_matches(batch, i, s)
        np.testing.assert_array_equal(batch.shape_W[i], s.shape_W)


def test_statuses_are_reported_per_frame(small_whisker):
    points = np.array([[0.02, 0.004, 0.0], [0.5, 0.0, 0.0], [0.02, 0.0045, 0.0]])
    batch = vibrissa.solve_point_batch(small_whisker, points)
    assert list(batch.status_names) == ["converged", "no_contact", "converged"]
    assert batch.status[1] == int(Status.no_contact)


def test_batch_layout_errors_name_the_arguments(small_whisker, peg_track):
    with pytest.raises(ValueError, match=r"arc_length_hint has 5 frames but points_W has 12"):
        vibrissa.solve_point_batch(small_whisker, peg_track, arc_length_hint=np.full(5, 0.02))
    with pytest.raises(ValueError, match=r"points_W has 2 series but whisker has 3"):
        vibrissa.solve_point_batch([small_whisker] * 3, np.stack([peg_track, peg_track]))
    with pytest.raises(ValueError, match=r"whisker\[1\] must be a vibrissa.Whisker"):
        vibrissa.solve_point_batch([small_whisker, 3], peg_track)
    with pytest.raises(ValueError, match=r"edge_points_W must have shape"):
        vibrissa.solve_edge_batch(small_whisker, np.zeros((2, 2, 2, 3)))
    with pytest.raises(ValueError, match=r"threads must lie in \[1, 1024\], got 0"):
        vibrissa.solve_point_batch(small_whisker, peg_track, threads=0)
    with pytest.raises(ValueError, match=r"load.force must be >= 0.*series 0, frame 1"):
        vibrissa.solve_force_batch(small_whisker, [1e-5, -1.0], 0.01, on_error="raise")
    with pytest.raises(ValueError, match=r"on_error must be one of \['record', 'raise'\], got 'stop'"):
        vibrissa.solve_force_batch(small_whisker, [1e-5], 0.01, on_error="stop")


def test_a_refused_frame_is_recorded_and_the_batch_goes_on(small_whisker, peg_track):
    # Issue 23: like `solve --jsonl`, a bad frame is reported (status invalid_input, NaN, its message naming
    # the series, frame and field) and every other frame is solved as on its own.
    forces = [1e-5, -1.0, float("nan"), 2e-5]
    with pytest.warns(UserWarning, match=r"solve_force_batch: 2 of 4 frames refused.*series 0, frame 1: "
                                         r"load.force must be >= 0"):
        batch = vibrissa.solve_force_batch(small_whisker, forces, 0.01)
    assert list(batch.status_names) == ["converged", "invalid_input", "invalid_input", "converged"]
    assert [(s, f) for s, f, _ in batch.errors] == [(0, 1), (0, 2)]
    assert "load.force" in batch.errors[0][2] and "-1" in batch.errors[0][2]
    assert "load.force" in batch.errors[1][2] and "nan" in batch.errors[1][2].lower()
    assert np.isnan(batch.force_W[1:3]).all() and np.isnan(batch.arc_length[1:3]).all()
    assert not batch.converged[1:3].any()
    for k in (0, 3):
        assert_matches(batch, k, vibrissa.solve_force(small_whisker, forces[k], 0.01))
    # A warm-started series goes on after its bad frame; the other series is untouched.
    track = np.stack([peg_track, peg_track])
    track[1, 4] = np.nan
    with pytest.warns(UserWarning, match=r"1 of 24 frames refused.*series 1, frame 4"):
        both = vibrissa.solve_point_batch([small_whisker] * 2, track)
    assert [(s, f) for s, f, _ in both.errors] == [(1, 4)]
    assert both.status_names[1, 4] == "invalid_input"
    clean = vibrissa.solve_point_batch(small_whisker, peg_track)
    assert len(clean.errors) == 0
    np.testing.assert_array_equal(both.status[0], clean.status)
    np.testing.assert_allclose(both.force_W[0], clean.force_W, rtol=1e-12, atol=0.0)
    np.testing.assert_array_equal(both.status[1, :4], clean.status[:4])
    assert (both.status[1, 5:] != vibrissa.batch.INVALID_INPUT).all()


def test_result_conveniences(small_whisker, peg_track):
    batch = vibrissa.solve_point_batch(small_whisker, peg_track)
    d = batch.to_dict()
    assert set(d["whisker_frame"]) == {"force", "moment", "Fx", "Mx", "FT", "MB", "FD", "MD"}
    assert len(batch) == 12 and "12" in repr(batch)
    assert batch.state.shape == (12, 4) and batch.status.dtype == np.int32


@pytest.mark.parametrize("with_progress", [False, True])
def test_ctrl_c_stops_a_long_batch_within_half_a_second(with_progress):
    w = vibrissa.Whisker.from_parabola(0.03, 20.0, properties=WhiskerProperties(links=200))
    f = np.linspace(0.0, 1.0, 40_000)
    points = np.column_stack([0.02 - 0.002 * f, 0.004 + 0.002 * f, 0.001 * f])  # seconds of work on one core
    call = lambda p: vibrissa.solve_point_batch(w, points, warm_start=False, threads=1, progress=p)  # noqa: E731
    assert interrupt(call, 0.3, with_progress) < 0.5


def test_batch_progress_counts_frames_up_to_the_total(small_whisker):
    F = 2000
    points = np.column_stack([np.full(F, 0.018), np.linspace(0.003, 0.006, F), np.zeros(F)])
    seen = []
    batch = vibrissa.solve_edge_batch(small_whisker, points, progress=lambda d, t: seen.append((d, t)))
    assert batch.converged.sum() > F // 2
    assert seen and seen[-1] == (F, F)
    assert all(a[0] < b[0] for a, b in zip(seen, seen[1:]))


def test_a_warm_started_series_is_a_contact_tracker_run(small_whisker):
    F = 30
    points = np.column_stack([np.full(F, 0.018), np.linspace(0.003, 0.006, F), np.zeros(F)])
    direction = np.array([0.0, 0.6, 0.8])
    batch = vibrissa.solve_frictional_edge_batch(small_whisker, points, direction, mu=0.3)
    tracker = vibrissa.ContactTracker(small_whisker, "frictional_edge", mu=0.3)
    for i in range(F):
        frame = tracker.step_tracked(None, Edge(points[i], direction))
        assert_matches(batch, i, frame["solution"], tol=0.0)
        assert frame["onset"] == (i == 0)
    assert tracker.solves == F


def test_tracker_onset_by_crossing_then_push_past_and_release():
    w = vibrissa.Whisker.from_parabola(0.03, 20.0, properties=WhiskerProperties(links=60))
    peg = Edge([0.02 * np.cos(0.25), 0.02 * np.sin(0.25), 0.0])
    tracker = vibrissa.ContactTracker(w, vibrissa.ContactMode.edge)
    thetas = np.concatenate([np.linspace(-0.3, 1.2, 301), np.linspace(1.2, -0.3, 301)[1:]])
    frames = [tracker.step(Pose(theta=t), [peg]) for t in thetas]
    states = [f["state"].label for f in frames]
    onsets = [i for i, f in enumerate(frames) if f["onset"]]
    assert states[0] == "free" and onsets and states[onsets[0]] == "contact"
    first_past = states.index("pushed_past")
    back = first_past + states[first_past:].index("free")
    assert onsets[0] < first_past < 301 < back
    assert set(states[first_past:back]) == {"pushed_past"}
    assert all(f["solution"].friction == vibrissa.FrictionState.none for f in frames)
    with pytest.raises(ValueError, match="mode"):
        vibrissa.ContactTracker(w, "sliding")
