"""NumPy handling: any array-like in, float64 arrays out; wrong shapes -> ValueError naming the argument."""

import numpy as np
import pytest

import vibrissa
from vibrissa import Edge, Pose, Whisker, WhiskerProperties


def test_float32_and_lists_give_the_same_result_as_float64(whisker):
    target64 = np.array([0.02, 0.004, 0.001])
    target32 = target64.astype(np.float32)
    ref = vibrissa.solve_point(whisker, target32.astype(np.float64))
    for variant in (target32, list(map(float, target32)), tuple(target32.astype(np.float64))):
        s = vibrissa.solve_point(whisker, variant)
        assert s.force_magnitude == ref.force_magnitude


def test_non_contiguous_inputs(whisker):
    pts = whisker.placed(Pose(theta=0.2)).rest_nodes_W
    wide = np.zeros((pts.shape[0], 6))
    wide[:, ::2] = pts
    strided = wide[:, ::2]
    assert not strided.flags["C_CONTIGUOUS"]
    a = Whisker.from_points(strided)
    b = Whisker.from_points(np.ascontiguousarray(pts))
    np.testing.assert_array_equal(a.rest_nodes_W, b.rest_nodes_W)
    fortran = np.asfortranarray(pts)
    np.testing.assert_array_equal(Whisker.from_points(fortran).rest_nodes_W, b.rest_nodes_W)
    reversed_view = np.array([0.0, 0.004, 0.02])[::-1]
    s = vibrissa.solve_point(whisker, reversed_view)
    assert s.converged


def test_outputs_are_float64_and_owned(whisker):
    s = vibrissa.solve_point(whisker, [0.02, 0.004, 0.0])
    for a in (s.contact_point_W, s.force_W, s.moment_W, s.shape_W, s.whisker_frame.force, whisker.rest_nodes_B,
              whisker.R_WB, whisker.node_radii):
        assert a.dtype == np.float64 and a.flags["C_CONTIGUOUS"] and a.flags["OWNDATA"]
    cp = s.contact_point_W
    cp[:] = 0.0  # a copy: the solution is unchanged
    assert s.contact_point_W[0] == pytest.approx(0.02)
    assert isinstance(s.force_magnitude, float) and isinstance(s.iterations, int)


@pytest.mark.parametrize("call, message", [
    (lambda w: vibrissa.solve_point(w, [0.02, 0.004]), r"load.point must have shape \(3,\), got \(2,\)"),
    (lambda w: vibrissa.solve_point(w, np.zeros((1, 3))), r"load.point must have shape \(3,\), got \(1, 3\)"),
    (lambda w: vibrissa.solve_point(w, "abc"), r"load.point must be an array of real numbers, got str"),
    (lambda w: vibrissa.solve_point(w, None), r"load.point .* None"),
    (lambda w: Whisker.from_points(np.zeros((10, 2))), r"whisker.points must have shape \(N, 3\), got \(10, 2\)"),
    (lambda w: Whisker.from_points(np.zeros(9)), r"whisker.points must have shape \(N, 3\), got \(9,\)"),
    (lambda w: Edge([0, 0, 0], [1, 2]), r"edge.direction must have shape \(3,\)"),
    (lambda w: Pose(base=[0, 0]), r"pose.base must have shape \(3,\)"),
    (lambda w: WhiskerProperties(radii=np.ones((2, 2))), r"whisker.radii must be 1-D"),
    (lambda w: w.to_world(np.zeros((4, 2))), r"p_B must have shape \(3,\) or \(N, 3\), got \(4, 2\)"),
    (lambda w: vibrissa.solve_point(w, [0.02, 0.004, 0.0], warm=3), r"warm must be"),
    (lambda w: vibrissa.solve_point_batch(w, np.zeros((5, 2))), r"points_W must have shape .*got \(5, 2\)"),
])
def test_wrong_shapes_raise_value_error(whisker, call, message):
    with pytest.raises(ValueError, match=message):
        call(whisker)


def test_many_points_geometry_helpers(whisker):
    pts = np.random.default_rng(1).normal(size=(7, 3)).astype(np.float32)
    out = whisker.placed(Pose(theta=1.0)).to_world(pts)
    assert out.shape == (7, 3) and out.dtype == np.float64
