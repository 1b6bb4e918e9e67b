"""Objects from Python: shapes, their query, object solves, cases with objects (docs/objects.md)."""
import json
import math

import numpy as np
import pytest

import vibrissa


def rat_whisker():
    return vibrissa.Whisker.from_parabola(0.040, 12.0, pose=vibrissa.Pose(theta=0.17, phi=0.17, zeta=0.52))


def test_shapes_answer_queries():
    ball = vibrissa.Sphere([0.0, 0.0, 0.0], 0.002)
    q = ball.nearest([0.0, 0.005, 0.0])
    assert q["signed_distance"] == pytest.approx(0.003, abs=1e-15)
    assert np.allclose(q["normal"], [0, 1, 0])
    assert q["feature"] == "face"
    assert ball.describe() == {"type": "sphere", "centre": [0.0, 0.0, 0.0], "radius": 0.002}
    box = vibrissa.Box([0, 0, 0], [0.001, 0.002, 0.003])
    assert box.nearest([0.002, 0.003, 0.0])["feature"] == "edge"
    with pytest.raises(ValueError, match="object.radius"):
        vibrissa.Sphere([0, 0, 0], -1.0)


def test_peg_with_zero_radius_is_edge_mode():
    w = rat_whisker()
    edge = vibrissa.Edge([0.02, 0.006, 0.0], [0.0, 0.0, 1.0])
    e = vibrissa.solve_edge(w, edge)
    c = vibrissa.solve_object(w, vibrissa.Cylinder([0.02, 0.006, 0.0], [0.0, 0.0, 1.0], 0.0), thickness=False)
    assert c.status == vibrissa.Status.converged
    assert np.linalg.norm(np.subtract(c.force_W, e.force_W)) < 1e-9 * np.linalg.norm(e.force_W)
    assert c.arc_length == pytest.approx(e.arc_length, rel=1e-9)


def test_force_along_the_normal_and_friction(tmp_path):
    w = rat_whisker()
    peg = vibrissa.Cylinder([0.02, 0.006, 0.0], [0.0, 0.0, 1.0], 0.001)
    s = vibrissa.solve_object(w, peg)
    assert s.status == vibrissa.Status.converged
    n = np.asarray(s.surface["normal_W"])
    f = np.asarray(s.force_W)
    assert np.linalg.norm(np.cross(f / np.linalg.norm(f), n)) < 1e-9
    assert abs(peg.signed_distance(s.contact_point_W)) < 1e-12
    previous = np.asarray(s.contact_point_W) + [0.0, 0.0, 0.0003]
    stuck = vibrissa.solve_frictional_object(w, peg, 1e9, previous)
    assert stuck.friction == vibrissa.FrictionState.stick
    zero = vibrissa.solve_frictional_object(w, peg, 0.0, previous)
    assert np.allclose(zero.force_W, s.force_W, rtol=1e-12)


def test_mesh_from_file_and_case_json(tmp_path):
    # An octahedron in mm, written as OBJ, read back in metres.
    v = [(3, 0, 0), (-3, 0, 0), (0, 3, 0), (0, -3, 0), (0, 0, 3), (0, 0, -3)]
    f = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    path = tmp_path / "octa.obj"
    path.write_text("".join(f"v {a} {b} {c}\n" for a, b, c in v) + "".join(f"f {a+1} {b+1} {c+1}\n" for a, b, c in f))
    mesh = vibrissa.Mesh.from_file(str(path), file_unit="mm", translation=[0.02, 0.009, 0.0])
    assert mesh.closed and mesh.vertices.shape == (6, 3) and mesh.triangles.shape == (8, 3)
    assert mesh.signed_distance([0.02, 0.009, 0.0]) == pytest.approx(-0.003 / math.sqrt(3), rel=1e-12)
    case = {"whisker": {"length": 0.04, "curvature": 12.0, "pose": {"theta": 0.17, "phi": 0.17, "zeta": 0.52}},
            "load": {"mode": "object", "object": {"type": "mesh", "file": str(path), "file_unit": "mm",
                                                  "translation": [0.02, 0.009, 0.0]}}}
    result = json.loads(vibrissa.solution_to_json(vibrissa.solve_case(vibrissa.Case.from_json(json.dumps(case)))))
    direct = vibrissa.solve_object(rat_whisker(), mesh)
    assert result["status"] == direct.status.name
    if direct.status == vibrissa.Status.converged:
        assert np.allclose(result["force_W"], direct.force_W, rtol=1e-12)


def test_array_against_a_sphere_records_the_object():
    config = json.loads(vibrissa.default_array_config_json()) if hasattr(vibrissa, "default_array_config_json") else None
    if config is None:
        from vibrissa import _vibrissa
        config = json.loads(_vibrissa.default_array_config_json())
    config["objects"] = [{"type": "sphere", "frame": "world", "centre_mm": [20, -8, -3], "radius_mm": 3}]
    config["morphology"]["whiskers"] = ["C1", "C2", "D1"]
    config["time"]["frames"] = 120
    config["output"] = {"render_count": 5}
    result = vibrissa.simulate_array(config)
    d = result.datasets if hasattr(result, "datasets") else result
    state = np.asarray(d["state"])
    assert (state == 1).any()
    contact = state == 1
    normal = np.asarray(d["normal_force"])
    assert (normal[contact] > 0).all()
    poses = np.asarray(d["render/object_poses"])
    assert poses.shape[1:] == (1, 12)
