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
    with pytest.warns(UserWarning, match=r"whisker length 39\.99"):
        vibrissa.solve_case_file(case, tmp_path / "result.json")
    assert "whisker length 39.99" in json.loads((tmp_path / "result.json").read_text())["warnings"][0]
