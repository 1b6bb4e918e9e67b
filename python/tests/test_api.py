"""The Python API mirrors the C++ model: construction, geometry, frames, solves, statuses, errors."""

import math

import numpy as np
import pytest

import vibrissa
from vibrissa import Edge, LoadState, Pose, SolveOptions, Status, Whisker, WhiskerProperties


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def test_pose_rotation_is_rz_ry_minus_phi_rx():
    pose = Pose(base=[1e-3, 2e-3, 3e-3], theta=0.4, phi=0.3, zeta=-0.2)
    expected = rot_z(0.4) @ rot_y(-0.3) @ rot_x(-0.2)
    np.testing.assert_allclose(pose.R_WB, expected, atol=1e-15)
    np.testing.assert_allclose(vibrissa.rotation_from_angles(0.4, 0.3, -0.2), expected, atol=1e-15)
    back = vibrissa.pose_from_rotation(expected, pose.base)
    assert (back.theta, back.phi, back.zeta) == pytest.approx((0.4, 0.3, -0.2), abs=1e-14)
    np.testing.assert_array_equal(back.p_W_base, [1e-3, 2e-3, 3e-3])


def test_whisker_from_parameters_has_spec_defaults(whisker):
    assert whisker.links == 100
    assert whisker.length == pytest.approx(0.03, rel=1e-4)
    p = whisker.properties
    assert (p.base_radius, p.taper_ratio, p.youngs_modulus, p.poisson_ratio) == (100e-6, 15.0, 3.3e9, 0.38)
    assert p.scheme == vibrissa.Scheme.second_order and p.base == vibrissa.BaseJoint.elastic
    radii = whisker.node_radii
    assert radii.shape == (101,) and radii.dtype == np.float64
    assert radii[0] == pytest.approx(100e-6) and radii[-1] == pytest.approx(100e-6 / 15)
    # E I at the base = E pi r^4 / 4 (spec §2.1, eq. (3))
    assert whisker.base_bending_stiffness == pytest.approx(3.3e9 * math.pi * 1e-16 / 4, rel=1e-2)


def test_whisker_geometry_arrays(whisker):
    nodes_B = whisker.rest_nodes_B
    assert nodes_B.shape == (101, 3)
    np.testing.assert_allclose(nodes_B[0], 0.0, atol=1e-15)
    assert np.all(nodes_B[1:, 1] > 0)  # concave toward +y (spec §2.1)
    np.testing.assert_allclose(np.cumsum(whisker.link_lengths), whisker.node_arc_lengths[1:], rtol=1e-12)
    placed = whisker.placed(Pose(base=[0.01, 0.0, 0.0], theta=0.5))
    np.testing.assert_allclose(placed.rest_nodes_W, placed.to_world(nodes_B), atol=1e-15)
    np.testing.assert_allclose(placed.to_body(placed.rest_nodes_W), nodes_B, atol=1e-15)
    np.testing.assert_allclose(placed.rest_point_W(whisker.length), placed.rest_nodes_W[-1], atol=1e-12)
    s50 = whisker.node_arc_lengths[50]
    link, h = whisker.locate(s50 + 1e-5)
    assert link == 50 and h == pytest.approx(1e-5, rel=1e-9)


def test_whisker_from_points_reproduces_the_world_placement(whisker):
    pts = whisker.placed(Pose(base=[0.0, 0.01, 0.0], theta=0.3, phi=0.1)).rest_nodes_W
    w = Whisker.from_points(pts, properties=WhiskerProperties(links=100))
    np.testing.assert_allclose(w.rest_nodes_W, pts, atol=1e-9)
    assert w.pose.theta == pytest.approx(0.3, abs=0.02)  # B is refitted to the points (spec §2.1)


def test_properties_accept_names_and_profiles():
    props = WhiskerProperties(links=20, radii=np.linspace(80e-6, 5e-6, 7), scheme="paper", base="rigid")
    assert props.scheme == vibrissa.Scheme.paper and props.base == vibrissa.BaseJoint.rigid
    w = Whisker.from_cubic(0.02, 100.0, 10.0, properties=props)
    assert w.links == 20
    assert w.node_radii[0] == pytest.approx(80e-6) and w.node_radii[-1] == pytest.approx(5e-6)
    props.scheme = vibrissa.Scheme.second_order
    props.radii = None
    assert props.radii.shape == (0,)


def test_force_mode_zero_force_leaves_rest_shape(whisker):
    s = vibrissa.solve_force(whisker, 0.0, 0.02)
    assert s.status == Status.converged and s.converged
    np.testing.assert_allclose(s.shape_W, whisker.rest_nodes_W, atol=1e-15)


def test_force_mode_small_load_matches_beam_theory():
    # Straight, untapered rod, rigid base: tip deflection F L^3 / (3 E I) for small loads.
    props = WhiskerProperties(links=400, taper_ratio=1.0, base="rigid")
    w = Whisker.from_parabola(0.02, 0.0, properties=props)
    F = 1e-6
    s = vibrissa.solve_force(w, F, w.length, angle=0.0)
    EI = 3.3e9 * math.pi * (100e-6) ** 4 / 4
    assert s.shape_W[-1, 1] == pytest.approx(F * w.length**3 / (3 * EI), rel=1e-2)
    assert s.whisker_frame.MB == pytest.approx(F * w.length, rel=1e-6)


def test_point_mode_reaches_the_point_and_reports_spec_signals(whisker):
    target = np.array([0.02, 0.004, 0.001])
    s = vibrissa.solve_point(whisker, target)
    assert s.status == Status.converged, s.message
    np.testing.assert_allclose(s.contact_point_W, target, atol=1e-11)
    wf = s.whisker_frame
    assert wf.FT == pytest.approx(math.hypot(wf.force[1], wf.force[2]), rel=1e-14)
    assert wf.MB == pytest.approx(math.hypot(wf.moment[1], wf.moment[2]), rel=1e-14)
    assert wf.FD == pytest.approx(math.atan2(wf.force[2], wf.force[1]), abs=1e-14)
    assert np.linalg.norm(s.force_W) == pytest.approx(s.force_magnitude, rel=1e-12)
    np.testing.assert_allclose(s.moment_W, np.cross(s.contact_point_W - whisker.p_W_base, s.force_W), rtol=1e-9, atol=1e-18)
    assert s.normal_force is None and s.edge_force is None
    assert s.shape_W.shape == (101, 3)


def test_edge_mode_force_is_normal_to_the_edge(whisker):
    edge = Edge(point=[0.02, 0.004, 0.0], direction=[0.0, 0.2, 1.0])
    s = vibrissa.solve_edge(whisker, edge)
    assert s.status == Status.converged, s.message
    d = edge.direction / np.linalg.norm(edge.direction)
    assert abs(np.dot(s.force_W, d)) < 1e-12 * s.force_magnitude + 1e-18
    off = s.contact_point_W - edge.point
    assert np.linalg.norm(off - np.dot(off, d) * d) < 1e-10
    assert s.normal_force == pytest.approx(s.force_magnitude, rel=1e-9)


def test_out_of_reach_is_a_status_not_nan(whisker):
    s = vibrissa.solve_point(whisker, [0.5, 0.0, 0.0])
    assert s.status == Status.no_contact and not s.converged
    assert "beyond" in s.message
    assert np.all(np.isfinite(s.contact_point_W))


def test_warm_start_accepts_state_or_solution(whisker):
    first = vibrissa.solve_point(whisker, [0.02, 0.004, 0.0])
    a = vibrissa.solve_point(whisker, [0.02, 0.0042, 0.0], warm=first)
    b = vibrissa.solve_point(whisker, [0.02, 0.0042, 0.0], warm=first.state)
    st = first.state
    c = vibrissa.solve_point(whisker, [0.02, 0.0042, 0.0],
                             warm=LoadState(force_x=st.force_x, force_y=st.force_y, force_z=st.force_z,
                                            arc_length=st.arc_length))
    # A solution and its state carry the record of the solve (its first step costs no walk); four numbers
    # typed in do not: the same root to within the tolerance.
    assert a.force_magnitude == b.force_magnitude
    assert c.force_magnitude == pytest.approx(a.force_magnitude, rel=1e-12)
    assert np.linalg.norm(np.subtract(a.contact_point_W, c.contact_point_W)) <= 1e-12
    assert a.iterations == c.iterations <= 6


def test_status_enum():
    # The batch names also the Python-only code of a refused frame, one past the solver's statuses.
    assert [s.label for s in Status.__members__.values()] + ["invalid_input"] == list(vibrissa.STATUS_NAMES)
    assert vibrissa.STATUS_NAMES[vibrissa.batch.INVALID_INPUT] == "invalid_input"
    assert vibrissa.status_from_string("slipped_off") == Status.slipped_off
    assert int(Status.converged) == 0
    with pytest.raises(ValueError, match="unknown value"):
        vibrissa.status_from_string("exploded")


def test_to_dict_uses_the_json_names(whisker):
    d = vibrissa.solve_point(whisker, [0.02, 0.004, 0.0]).to_dict()
    for key in ("status", "message", "force_magnitude", "arc_length", "angle", "contact_point_W", "force_W",
                "moment_W", "whisker_frame", "normal_force", "edge_force", "residual", "iterations", "shape_W"):
        assert key in d
    for key in ("force", "moment", "Fx", "Mx", "FT", "MB", "FD", "MD"):
        assert key in d["whisker_frame"]
    assert d["status"] == "converged" and d["contact_point_W"].shape == (3,) and d["shape_W"].shape == (101, 3)
    # The keys without _W are deprecated copies (removed in 0.2.0).
    for old in ("contact_point", "force", "moment", "shape"):
        np.testing.assert_array_equal(d[old], d[old + "_W"])


@pytest.mark.parametrize("call, field", [
    (lambda w: vibrissa.solve_force(w, -1.0, 0.01), "load.force"),
    (lambda w: vibrissa.solve_force(w, 1e-4, 1.0), "load.arc_length"),
    (lambda w: vibrissa.solve_point(w, [0.01, np.nan, 0.0]), "load.point"),
    (lambda w: vibrissa.solve_edge(w, Edge([0.02, 0.0, 0.0], [0.0, 0.0, 0.0])), "edge.direction"),
    (lambda w: vibrissa.solve_frictional_edge(w, Edge([0.02, 0.0, 0.0]), -0.1, [0.02, 0.0, 0.0]),
     "friction_coefficient"),
    (lambda w: Whisker.from_parabola(0.03, 20.0, properties=WhiskerProperties(links=1)), "whisker.links"),
    (lambda w: WhiskerProperties(poisson_ratio=0.7), "whisker.poisson_ratio"),
    (lambda w: WhiskerProperties(scheme="third_order"), "whisker.scheme"),
    (lambda w: Pose(theta=math.inf), "pose.theta"),
    (lambda w: Whisker.from_points([[0, 0, 0], [1e-3, 0, 0]]), "whisker.points"),
])
def test_invalid_input_raises_value_error_naming_the_field(whisker, call, field):
    with pytest.raises(ValueError) as info:
        call(whisker)
    assert field in str(info.value)


def test_options_and_reprs(whisker):
    s = vibrissa.solve_point(whisker, [0.02, 0.004, 0.0], options=SolveOptions(compute_shape=False,
                                                                             find_other_roots=True))
    assert s.shape_W.shape == (0, 3)
    for obj in (s, s.whisker_frame, s.state, whisker, whisker.properties, Pose(), Edge([0, 0, 0]), SolveOptions()):
        assert type(obj).__name__ in repr(obj)


def test_stubs_cover_the_public_api():
    import ast
    import pathlib

    package = pathlib.Path(vibrissa.__file__).parent
    init_stub = ast.parse((package / "__init__.pyi").read_text())
    stubbed = {alias.asname or alias.name for node in ast.walk(init_stub) if isinstance(node, ast.ImportFrom)
               for alias in node.names}
    assert set(vibrissa.__all__) <= stubbed
    core_stub = ast.parse((package / "_vibrissa.pyi").read_text())
    core_names = {n.name for n in core_stub.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    core_names |= {t.id for n in core_stub.body if isinstance(n, (ast.AnnAssign,)) for t in [n.target]}
    public = {n for n in dir(vibrissa._vibrissa) if not n.startswith("__")}
    assert public <= core_names | {"_has_case_json"}, public - core_names
    assert (package / "py.typed").is_file()
