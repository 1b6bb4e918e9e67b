"""Dynamics from Python (docs/dynamics.md): the same numbers as `vibrissa modes` / `vibrissa dynamics`, the
labelled outputs, the physics of a release."""

import json
import subprocess

import numpy as np
import pytest

import vibrissa

CASE = {"whisker": {"length": 0.03, "curvature": 15.0, "links": 40},
        "dynamics": {"damping_ratio": 0.1},
        "whisking": {"amplitude_deg": 20, "frequency_Hz": 8},
        "duration": 0.05, "output_rate": 2000}


def whisker():
    return vibrissa.Whisker.from_parabola(0.03, 15.0, properties=vibrissa.WhiskerProperties(links=40))


def test_modes_match_the_cli(cli, tmp_path):
    case = tmp_path / "case.json"
    case.write_text(json.dumps(CASE))
    done = subprocess.run([cli, "modes", str(case), "-n", "6", "-o", str(tmp_path / "modes.json")],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    from_cli = json.loads((tmp_path / "modes.json").read_text())["modes"]
    m = vibrissa.modes(whisker(), 6, damping_ratio=0.1)
    assert len(m) == 6 and m.node_shapes.shape == (6, 41, 3)
    np.testing.assert_array_equal(m.frequency, [x["frequency"] for x in from_cli])
    np.testing.assert_array_equal(m.damping_ratio, [x["damping_ratio"] for x in from_cli])
    assert m.damping_ratio[0] == pytest.approx(0.1, rel=1e-12)
    assert np.all(np.diff(m.frequency) >= 0)


def test_simulation_matches_the_cli_and_its_files(cli, tmp_path):
    xr = pytest.importorskip("xarray")
    case = tmp_path / "case.json"
    case.write_text(json.dumps(CASE))
    done = subprocess.run([cli, "dynamics", str(case), "--out", str(tmp_path / "cli")], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    r = vibrissa.simulate_dynamics(whisker(), 0.05, 2000, whisking={"amplitude_deg": 20, "frequency_Hz": 8},
                                   damping_ratio=0.1)
    assert r.status == "completed" and len(r.time) == 101
    file = xr.open_dataset(tmp_path / "cli" / "dynamics.h5")
    np.testing.assert_array_equal(file.MB.values, r.MB)
    np.testing.assert_array_equal(file.nodes_W.values, r.nodes_W)
    assert r.nodes_W.shape == (101, 41, 3)
    assert file.Mz_B.attrs["units"] == "N m"
    ds = r.to_xarray()
    assert set(ds.data_vars) == set(file.data_vars)
    r.write(tmp_path / "py")
    assert (tmp_path / "py" / "summary.json").is_file()
    assert json.loads((tmp_path / "py" / "summary.json").read_text())["steps"] == r.summary["steps"]
    assert r.summary["warnings"] == []  # 0.3 mm of 30 mm: inside the linear range


def test_large_deflection_is_warned():
    r = vibrissa.simulate_dynamics(whisker(), 0.005, 1000, tip_force=[0, 1e-4, 0])
    assert len(r.summary["warnings"]) == 1 and "linearised" in r.summary["warnings"][0]


def test_release_rings_down_at_the_first_mode():
    w = whisker()
    m = vibrissa.modes(w, 2, damping_ratio=0.05)
    # The two lowest modes bend the curved whisker out of and in its plane (108 Hz apart by 0.6 %): a tip force
    # in the plane (y) rings the in-plane one, the mode whose tip moves along y.
    n = int(np.argmax(np.abs(m.node_shapes[:, -1, 1])))
    assert abs(m.node_shapes[n, -1, 2]) < 1e-6
    r = vibrissa.simulate_dynamics(w, 8 / m.frequency[n], 200 * m.frequency[n], tip_force=[0, 1e-6, 0],
                                   damping_ratio=0.05, relative_tolerance=1e-9)
    # Late in the ring-down that mode dominates: the tip's zero crossings are half a damped period apart.
    y = r.tip_y_B
    late = r.time > 3 / m.frequency[n]
    t, y = r.time[late], y[late]
    crossings = t[:-1][np.sign(y[:-1]) != np.sign(y[1:])]
    periods = 2 * np.diff(crossings)
    assert periods.mean() == pytest.approx(1 / m.damped_frequency[n], rel=1e-3)
    assert np.abs(r.tip_z_B).max() < 1e-9 * np.abs(r.tip_y_B).max()  # in the plane it stays
    energy = r.kinetic_energy + r.elastic_energy
    assert np.all(np.diff(energy) <= 1e-12 * energy[0])  # damped: the energy never grows


def test_bad_settings_name_the_field():
    with pytest.raises(ValueError, match="dynamics.density"):
        vibrissa.modes(whisker(), 3, density=-1.0)
    with pytest.raises(ValueError, match="whisking.frequency_Hz"):
        vibrissa.simulate_dynamics(whisker(), 0.01, whisking={"frequency_Hz": -2})
    with pytest.raises(ValueError, match="unknown field whisking"):
        vibrissa.simulate_dynamics(whisker(), 0.01, whisking={"amplitude": 3})


def test_peg_release_example(tmp_path):
    pytest.importorskip("matplotlib")
    pytest.importorskip("xarray")
    import os
    import pathlib
    import sys

    repo = pathlib.Path(__file__).resolve().parents[2]
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(vibrissa.__file__).resolve().parents[1]))
    done = subprocess.run([sys.executable, str(repo / "examples" / "dynamics" / "peg_release.py"), "--out",
                           str(tmp_path / "out")], capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "released:" in done.stdout
    assert (tmp_path / "out" / "dynamics.png").stat().st_size > 10_000


def test_modes_about_a_peg_match_the_cli(cli, tmp_path):
    # A peg held stuck (point mode) stiffens the whisker; Python and `vibrissa modes` give the same numbers.
    load = {"mode": "point", "point": [0.02, 0.003, 0.0]}
    case = tmp_path / "peg.json"
    case.write_text(json.dumps({"whisker": CASE["whisker"], "dynamics": CASE["dynamics"], "load": load}))
    done = subprocess.run([cli, "modes", str(case), "-n", "4", "-o", str(tmp_path / "modes.json")],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    from_cli = json.loads((tmp_path / "modes.json").read_text())
    m = vibrissa.modes(whisker(), 4, load=load, damping_ratio=0.1)
    np.testing.assert_array_equal(m.frequency, [x["frequency"] for x in from_cli["modes"]])
    assert m.equilibrium["contact"] == "stick" and m.equilibrium["constraints"] == 3
    assert from_cli["equilibrium"]["force_B"] == m.equilibrium["force_B"]
    assert m.frequency[0] > 1.5 * vibrissa.modes(whisker(), 1).frequency[0]
    slip = vibrissa.modes(whisker(), 4, load=load, hold="slip")
    assert slip.equilibrium["constraints"] == 1 and slip.frequency[0] < m.frequency[0]
    with pytest.raises(ValueError, match="hold"):
        vibrissa.modes(whisker(), 4, load={"mode": "dead_load", "force": [0, 1e-5, 0], "arc_length": 0.02},
                       hold="stick")


def test_array_dynamics_in_air():
    # simulate_array(dynamics=True) = `vibrissa array --dynamics`: every whisker whisks in air through the
    # integrator; the base signals are inertial (nonzero), nothing touches, the tip displacement is added.
    cfg = json.loads(vibrissa._vibrissa.default_array_config_json())
    cfg["time"] = {"start_s": 0.0, "end_s": 0.0625, "frames": 126}
    cfg["morphology"]["whiskers"] = ["C1", "D2"]
    cfg["objects"] = [{"type": "peg", "point_mm": [200, -8, -3]}]  # out of reach
    cfg["solver"]["links"] = 40
    cfg["output"]["render_count"] = 0
    r = vibrissa.simulate_array(cfg, dynamics=True)
    d = r.summary["dynamics"]
    assert not d["objects_touched"] and d["events"] == [] and d["steps"] > 0
    assert r.tip_displacement_B.shape == (1, 2, 126, 3)
    assert (r.state == 0).all() and r.MB.max() > 1e-9
    quasi = vibrissa.simulate_array(cfg)
    np.testing.assert_allclose(r.base_W, quasi.base_W, atol=1e-12)


def test_array_dynamics_touches_the_peg():
    # simulate_array(dynamics=True) with the default peg: C2 whisks into it; contact frames and events as the
    # command writes them (summary.json's "dynamics": "events" per whisker).
    cfg = json.loads(vibrissa._vibrissa.default_array_config_json())
    cfg["time"] = {"start_s": 0.0, "end_s": 0.0625, "frames": 126}
    cfg["morphology"]["whiskers"] = ["C2"]
    cfg["solver"]["links"] = 40
    cfg["output"]["render_count"] = 0
    r = vibrissa.simulate_array(cfg, dynamics=True)
    d = r.summary["dynamics"]
    assert d["objects_touched"] and d["events"][0]["whisker"] == "C2R"
    assert d["events"][0]["events"][0]["type"] == "touch"
    assert (r.state == 1).sum() > 20 and (r.edge_index[r.state == 1] == 0).all()


def test_a_peg_during_whisking_is_touched_then_let_go_at_the_tip():
    # docs/dynamics.md, "Large deflection and contact during motion": protraction 0 -> 24 deg against a peg at 27 mm.
    w = vibrissa.Whisker.from_parabola(0.03, 15.0, properties=vibrissa.WhiskerProperties(links=30))
    peg = {"type": "peg", "point": [0.02486, 0.00977, 0.0], "direction": [0, 0, 1], "radius": 1e-4}
    r = vibrissa.simulate_dynamics(w, 0.2, 500, objects=[peg],
                                   whisking={"amplitude_deg": 12, "frequency_Hz": 2, "set_point_deg": 12})
    assert r.status == "completed" and r.summary["model"] == "nonlinear"
    assert [e["type"] for e in r.events] == ["touch", "release"]
    assert r.events[1]["arc_length"] == pytest.approx(0.03, abs=1e-4)  # slides off the tip
    assert r.events[0]["time"] < r.events[1]["time"] < 0.2
    touching = (r.time > r.events[0]["time"] + 0.005) & (r.time < r.events[1]["time"] - 0.005)
    assert np.all(r.contact0_state[touching] == 2)  # frictionless: slipping while touching
    assert r.summary["max_penetration_m"] < 1e-7
    with pytest.raises(ValueError, match=r"objects\[0\].type"):
        vibrissa.simulate_dynamics(w, 0.01, objects=[{"type": "wall", "point": [0, 0, 0]}])
    with pytest.raises(ValueError, match="linear"):
        vibrissa.simulate_dynamics(w, 0.01, objects=[peg], model="linear")


def test_surfaces_in_motion_as_shapes_or_json_and_invalid_ones_named():
    # docs/dynamics.md, "Surfaces in motion": whisking against a 3 mm sphere; a vibrissa.Sphere and its JSON are
    # the same object; friction through {"shape": ..., "friction_coefficient": mu}.
    w = vibrissa.Whisker.from_parabola(0.03, 15.0, properties=vibrissa.WhiskerProperties(links=30))
    ball = vibrissa.Sphere([0.018, 0.013, 0.0], 0.003)
    wh = {"amplitude_deg": 12, "frequency_Hz": 4, "set_point_deg": 12}
    a = vibrissa.simulate_dynamics(w, 0.1, 1000, objects=[ball], whisking=wh)
    b = vibrissa.simulate_dynamics(w, 0.1, 1000, whisking=wh,
                                   objects=[{"type": "sphere", "centre": [0.018, 0.013, 0.0], "radius": 0.003}])
    assert a.status == "completed" and a.events[0]["type"] == "touch"
    assert np.array_equal(a.MB, b.MB)
    c = vibrissa.simulate_dynamics(w, 0.1, 1000, objects=[{"shape": ball, "friction_coefficient": 0.2}], whisking=wh)
    assert c.events[0]["type"] == "touch" and (c.contact0_state == 1).sum() > 10  # sticks on the sphere
    assert a.summary["max_penetration_m"] < 1e-7 and c.summary["max_penetration_m"] < 1e-7
    with pytest.raises(ValueError, match=r"objects\[0\]: unknown field 'mu'"):
        vibrissa.simulate_dynamics(w, 0.01, objects=[{"shape": ball, "mu": 0.2}])
    with pytest.raises(ValueError, match=r"objects\[1\].*friction_coefficient must be >= 0"):
        vibrissa.simulate_dynamics(w, 0.01, objects=[ball, {"shape": ball, "friction_coefficient": -1}])
    with pytest.raises(ValueError, match=r"objects\[0\].*thickness"):
        box = vibrissa.Box([0.02, 0.01, 0], [0.001, 0.001, 0.001])
        vibrissa.simulate_dynamics(w, 0.01, objects=[{"shape": box, "thickness": False}])
