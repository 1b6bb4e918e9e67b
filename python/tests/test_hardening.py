"""Hostile Python arguments raise ValueError naming the argument (docs/formats.md, "Limits")."""
import json

import numpy as np
import pytest

import vibrissa


def test_complex_arrays_are_refused_not_truncated(small_whisker):
    points = np.array([[0.02, 0.001, 0.0]], dtype=complex)
    with pytest.raises(ValueError, match=r"points_W must be real, got complex values"):
        vibrissa.solve_point_batch(small_whisker, points, warm_start=False)


@pytest.mark.parametrize("threads", [100000, 2**70, 0])
def test_thread_counts_are_bounded(small_whisker, threads):
    with pytest.raises(ValueError, match=r"threads must lie in \[1, 1024\]"):
        vibrissa.solve_point_batch(small_whisker, np.array([[0.02, 0.001, 0.0]]), warm_start=False, threads=threads)


def test_array_threads_are_bounded():
    with pytest.raises(ValueError, match=r"threads must lie in \[0, 1024\], got 100000"):
        vibrissa.simulate_array(threads=100000)


def test_json_type_errors_are_value_errors_naming_the_field():
    case = {"whisker": {"length": 0.03, "curvature": 5},
            "load": {"mode": "point", "point": [0.02, 0.001, 0]}, "options": {"compute_shape": "no"}}
    with pytest.raises(ValueError, match=r'options.compute_shape must be true or false, got "no"'):
        vibrissa.load_case(case)
    with pytest.raises(ValueError, match=r"duplicate key"):
        vibrissa.Case.from_json('{"whisker": {"length": 0.03, "length": 0.04}}')


def test_case_file_warns_about_a_likely_unit_slip(tmp_path):
    case = tmp_path / "case.json"
    case.write_text(json.dumps({"whisker": {"length": 40, "curvature": 0.005},
                                "load": {"mode": "force", "force": 0.001, "arc_length": 20}}))
    with pytest.warns(UserWarning, match=r"whisker length 40\.0000"):
        vibrissa.solve_case_file(case, tmp_path / "result.json")
    assert "whisker length 40" in json.loads((tmp_path / "result.json").read_text())["warnings"][0]


# Issue 23: one validation layer, the same in Python as in case JSON and the CLI.
@pytest.mark.parametrize("field", ["radii", "youngs_moduli"])
def test_empty_lists_are_errors_not_defaults(field):
    with pytest.raises(ValueError, match=rf"whisker.{field} needs at least 2 values, got 0"):
        vibrissa.WhiskerProperties(**{field: []})


@pytest.mark.parametrize("value", [1e-310, 5e-324, float("nan"), float("inf")])
def test_subnormal_and_non_finite_numbers_are_rejected_naming_the_field(value):
    with pytest.raises(ValueError, match="base_stiffness"):
        vibrissa.WhiskerProperties(base_stiffness=value)
    whisker = vibrissa.Whisker.from_parabola(0.03, 20.0)
    with pytest.raises(ValueError, match="load.point"):
        vibrissa.solve_point(whisker, [0.02, 0.004, value])


def test_case_json_overflowing_number_names_line_and_column():
    with pytest.raises(ValueError, match=r"line 1, column 35: the number 1e400 is beyond the range of a double"):
        vibrissa.Case.from_json('{"whisker": {"length": 0.03, "a": 1e400}}')
