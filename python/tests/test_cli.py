"""Round trip with `vibrissa solve`: the same case JSON solved from Python gives the CLI's result exactly, and
the direct API (Whisker / solve_*) agrees with the CLI on the same cases."""

import json
import subprocess

import numpy as np
import pytest

import vibrissa

PARABOLA = {"length": 0.03, "curvature": 20.0}
CASES = {
    "force": {"whisker": PARABOLA, "load": {"mode": "force", "force": 1e-4, "arc_length": 0.02, "angle": 0.3}},
    "point": {"whisker": PARABOLA, "load": {"mode": "point", "point": [0.02, 0.004, 0.001]}},
    "point_hint": {"whisker": dict(PARABOLA, scheme="paper", links=60),
                   "load": {"mode": "point", "point": [0.02, 0.004, 0.0], "arc_length_hint": 0.021}},
    "edge": {"whisker": dict(PARABOLA, pose={"base": [0.001, 0.0, 0.0], "theta": 0.1, "phi": 0.05, "zeta": 0.02}),
             "load": {"mode": "edge", "point": [0.018, 0.005, 0.0], "direction": [0.0, 0.2, 1.0]}},
    "frictional_edge": {"whisker": dict(PARABOLA, base="rigid"),
                        "load": {"mode": "frictional_edge", "point": [0.018, 0.003, 0.0], "direction": [0, 0.3, 1],
                                 "friction_coefficient": 0.3, "previous_contact": [0.018, 0.0031, 0.0002]}},
    "dead_load": {"whisker": {"length": 0.025, "cubic": [50.0, 15.0], "radii": [9e-5, 5e-5, 1e-5]},
                  "load": {"mode": "dead_load", "force": [0.0, -5e-5, 1e-5], "arc_length": 0.015}},
    "points": {"whisker": {"points": [[0, 0, 0], [0.005, 0.0006, 0.0001], [0.01, 0.002, 0.0003],
                                      [0.02, 0.008, 0.0006], [0.028, 0.0155, 0.001]], "links": 50},
               "load": {"mode": "point", "point": [0.015, 0.003, 0.001]}},
    "no_contact": {"whisker": PARABOLA, "load": {"mode": "point", "point": [0.2, 0.0, 0.0]},
                   "options": {"find_other_roots": False}},
}


def run_cli(cli, case_path, out_path):
    done = subprocess.run([cli, "solve", str(case_path), "-o", str(out_path)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return json.loads(out_path.read_text())


@pytest.mark.parametrize("name", sorted(CASES))
def test_python_round_trip_equals_cli(cli, tmp_path, name):
    case_path = tmp_path / "case.json"
    case_path.write_text(json.dumps(CASES[name]))
    cli_text_path = tmp_path / "cli.json"
    cli_result = run_cli(cli, case_path, cli_text_path)

    py_path = tmp_path / "py.json"
    solution = vibrissa.solve_case_file(case_path, py_path)
    assert py_path.read_bytes() == cli_text_path.read_bytes()  # bit-identical files
    # The case's warnings (only the unreachable point of no_contact has one); the Solution's JSON is the rest.
    warned = cli_result.pop("warnings")
    assert warned == vibrissa.load_case(CASES[name]).warnings
    assert [w.split(" passes ")[0] for w in warned] == (["load.point"] if name == "no_contact" else [])
    assert json.loads(solution.to_json()) == cli_result
    assert json.loads(vibrissa.load_case(CASES[name]).solve().to_json()) == cli_result
    assert json.loads(vibrissa.load_case(case_path.read_text()).solve().to_json()) == cli_result

    d = solution.to_dict()
    assert d["status"] == cli_result["status"] == solution.status.label
    assert solution.force_magnitude == cli_result["force_magnitude"]
    np.testing.assert_array_equal(solution.contact_point_W, cli_result["contact_point_W"])
    np.testing.assert_array_equal(solution.shape_W, np.asarray(cli_result["shape_W"]).reshape(-1, 3))
    assert solution.whisker_frame.FT == cli_result["whisker_frame"]["FT"]


def test_direct_api_agrees_with_cli(cli, tmp_path):
    """The same physics through the one-to-one API (no JSON in between)."""
    opts = vibrissa.SolveOptions(find_other_roots=True)  # the CLI's default for cases
    w = vibrissa.make_whisker(**CASES["edge"]["whisker"])
    load = CASES["edge"]["load"]
    direct = vibrissa.solve_edge(w, vibrissa.Edge(load["point"], load["direction"]), options=opts)
    case_path = tmp_path / "case.json"
    case_path.write_text(json.dumps(CASES["edge"]))
    cli_result = run_cli(cli, case_path, tmp_path / "out.json")
    assert cli_result.pop("warnings") == []
    assert json.loads(direct.to_json()) == cli_result

    w = vibrissa.Whisker.from_cubic(0.03, 0.0, 20.0)
    direct = vibrissa.solve_point(w, CASES["point"]["load"]["point"], options=opts)
    case_path.write_text(json.dumps(CASES["point"]))
    cli_result = run_cli(cli, case_path, tmp_path / "out.json")
    for key in ("force_magnitude", "arc_length", "iterations"):
        assert getattr(direct, key) == cli_result[key]


def test_invalid_case_raises_value_error_with_the_cli_message(cli, tmp_path):
    bad = {"whisker": dict(PARABOLA, links=1), "load": {"mode": "point", "point": [0.02, 0.004, 0.0]}}
    with pytest.raises(ValueError, match="whisker.links") as info:
        vibrissa.load_case(bad)
    case_path = tmp_path / "bad.json"
    case_path.write_text(json.dumps(bad))
    done = subprocess.run([cli, "solve", str(case_path)], capture_output=True, text=True)
    assert done.returncode != 0 and str(info.value) in done.stderr
    with pytest.raises(ValueError, match="unknown field load.pointt"):
        vibrissa.load_case({"whisker": PARABOLA, "load": {"mode": "point", "pointt": [0, 0, 0]}})


def test_case_accessors():
    case = vibrissa.load_case(CASES["frictional_edge"])
    assert case.mode == "frictional_edge"
    assert case.load["friction_coefficient"] == 0.3
    np.testing.assert_array_equal(case.load["previous_contact"], [0.018, 0.0031, 0.0002])
    assert case.whisker.properties.base == vibrissa.BaseJoint.rigid
    assert case.options.find_other_roots


def test_jsonl_batch_equals_one_solve_per_case(cli, tmp_path):
    """`vibrissa solve --jsonl`: one result line per case line, in order, each equal to `vibrissa solve` of that
    case; blank lines skipped; a bad line gives an error object naming its line and field, the others still
    solve, and the exit status is non-zero."""
    names = sorted(CASES)
    lines = [json.dumps(CASES[n]) for n in names]
    bad = {"whisker": dict(PARABOLA, length=-1.0), "load": CASES["force"]["load"]}
    text = "\n".join(lines[:2] + ["", "  ", json.dumps(bad), "{not json"] + lines[2:]) + "\n"
    done = subprocess.run([cli, "solve", "--jsonl", "-"], input=text, capture_output=True, text=True)
    assert done.returncode == 1
    assert "2 line(s) of the JSON Lines batch failed" in done.stderr
    out = [json.loads(line) for line in done.stdout.splitlines()]
    assert len(out) == len(names) + 2
    assert out[2] == {"line": 5, "error": "whisker.length must be positive, got -1"}
    assert out[3]["line"] == 6 and out[3]["error"].startswith("line 6: not valid JSON")
    solved = out[:2] + out[4:]
    for name, result in zip(names, solved):
        case_path = tmp_path / f"{name}.json"
        case_path.write_text(json.dumps(CASES[name]))
        assert result == run_cli(cli, case_path, tmp_path / f"{name}.out.json"), name

    good = tmp_path / "good.jsonl"
    good.write_text("\n".join(lines) + "\n")
    out_path = tmp_path / "good.out.jsonl"
    done = subprocess.run([cli, "solve", "--jsonl", str(good), "-o", str(out_path)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert [json.loads(line) for line in out_path.read_text().splitlines()] == solved

    both = subprocess.run([cli, "solve", str(good), "--jsonl", str(good)], capture_output=True, text=True)
    neither = subprocess.run([cli, "solve"], capture_output=True, text=True)
    assert both.returncode != 0 and "excludes" in both.stderr
    assert neither.returncode != 0 and "CASE or --jsonl is required" in neither.stderr
