"""Files an input names (a mesh, a morphology table) are found relative to the folder of the file that names
them, never the current directory (io::resolve_input_paths, docs/formats.md "Paths"): array configs, cases,
sweep bases; and config.json of an array output names them absolutely, so the viewer (which simulates the
run again from it) finds them from anywhere."""
import json
import os
import subprocess

import numpy as np
import pytest

import vibrissa
from vibrissa import viewer

OCTAHEDRON_MM = ([[3, 0, 0], [-3, 0, 0], [0, 3, 0], [0, -3, 0], [0, 0, 3], [0, 0, -3]],
                 [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])


def write_ply(path):
    v, f = OCTAHEDRON_MM
    lines = ["ply", "format ascii 1.0", f"element vertex {len(v)}", "property float x", "property float y",
             "property float z", f"element face {len(f)}", "property list uchar int vertex_indices", "end_header"]
    lines += [" ".join(map(str, p)) for p in v] + ["3 " + " ".join(map(str, t)) for t in f]
    path.write_text("\n".join(lines) + "\n")


@pytest.fixture
def folders(tmp_path, monkeypatch):
    (tmp_path / "inputs").mkdir()
    (tmp_path / "elsewhere").mkdir()
    write_ply(tmp_path / "inputs" / "ball.ply")
    monkeypatch.chdir(tmp_path / "elsewhere")  # the mesh is not in the current directory
    return tmp_path


def array_config():
    config = vibrissa.default_array_config()
    config["morphology"]["whiskers"] = ["C1", "C2"]
    config["time"]["frames"] = 12
    config["objects"] = [{"type": "mesh", "frame": "head", "file": "ball.ply", "file_unit": "mm",
                          "translation_mm": [20, -8, -3]}]
    return config


def test_array_config_file_resolves_its_mesh_and_the_output_names_it_absolutely(folders):
    config_path = folders / "inputs" / "config.json"
    config_path.write_text(json.dumps(array_config()))
    result = vibrissa.simulate_array(str(config_path))
    out = result.write(folders / "out")
    written = json.loads((out / "config.json").read_text())["objects"][0]["file"]
    assert written == str(folders / "inputs" / "ball.ply")
    with pytest.raises(ValueError, match="ball.ply"):  # a dict is relative to the current directory: not here
        vibrissa.simulate_array(array_config())
    os.chdir(folders)  # yet another folder: the viewer simulates the run again from out/config.json
    page = viewer.write_array_view(out, folders / "view.html")
    assert page.is_file()
    cli = os.environ.get("VIBRISSA_CLI")
    if cli:  # `vibrissa array` writes the same absolute name
        done = subprocess.run([cli, "array", str(config_path), "--out", str(folders / "cli_out"), "--no-figures"],
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stderr
        assert json.loads((folders / "cli_out" / "config.json").read_text())["objects"][0]["file"] == written


def test_case_file_and_sweep_base_resolve_the_mesh_from_their_folder(folders):
    case = {"whisker": {"length": 0.03, "curvature": 20.0, "links": 40},
            "load": {"mode": "object", "approach": [0, 1, 0],
                     "object": {"type": "mesh", "file": "ball.ply", "file_unit": "mm", "translation": [0.02, 0.011, 0]}}}
    case_path = folders / "inputs" / "case.json"
    case_path.write_text(json.dumps(case))
    solution = vibrissa.load_case(str(case_path)).solve()
    assert solution.contact_state.name in ("contact", "free", "pushed_past")
    with pytest.raises(ValueError, match="ball.ply"):
        vibrissa.load_case(case)  # a dict: the current directory
    result = vibrissa.sweep("solve", str(case_path), scheduler="serial", grid={"options.max_iterations": [100, 101]})
    assert np.array_equal(result.status.values, [int(solution.status)] * 2)
    assert vibrissa._vibrissa._resolve_input_paths(json.dumps({"morphology": {"source": "towal2011"}}), "/x") == \
        json.dumps({"morphology": {"source": "towal2011"}}, separators=(",", ":"))  # names of built-ins kept
