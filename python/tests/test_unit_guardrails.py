"""Unit guardrails (docs/conventions.md, "Plausible ranges"): inputs that are probably a unit slip are run, but
warned about, naming the quantity, the value and the likely mistake, in Python (warnings.warn), in the CLI
(standard error) and in the results' "warnings". The cases are those of issue 22."""

import json
import subprocess
import warnings

import pytest

import vibrissa


def test_a_plausible_whisker_and_pose_raise_nothing():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        vibrissa.Whisker.from_parabola(0.04, 12.0, pose=vibrissa.Pose(theta=1.2, phi=-0.3, zeta=0.5))


def test_constructors_warn_about_mm_given_as_metres_and_degrees_given_as_radians():
    with pytest.warns(UserWarning, match=r"whisker length 40(\.0\d*)? m \(40 m\) .* did you mean 40 mm \(a "
                                         r"length in mm given as metres"):
        vibrissa.Whisker.from_parabola(40, 12)
    with pytest.warns(UserWarning, match=r"Pose.theta 10 rad \(573 deg\) is beyond \+-pi: did you mean 10 deg"):
        vibrissa.Pose(theta=10)
    with pytest.warns(UserWarning, match=r"whisker.pose.theta 10 rad"):
        vibrissa.make_whisker(length=0.03, curvature=20.0, pose={"theta": 10})


def test_case_pose_load_and_reach_warnings_reach_the_cli(cli, tmp_path):
    case = {"whisker": {"length": 0.03, "curvature": 20.0, "pose": {"theta": 10}},
            "load": {"mode": "point", "point": [16.6, 11.2, 0.0]}}
    path = tmp_path / "case.json"
    path.write_text(json.dumps(case))
    loaded = vibrissa.load_case(str(path))
    assert [w.split(" ")[0] for w in loaded.warnings] == ["whisker.pose.theta", "load.point"]
    assert "positions in mm given as metres?" in loaded.warnings[1]
    run = subprocess.run([cli, "solve", str(path)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["warnings"] == loaded.warnings
    assert "vibrissa: warning: whisker.pose.theta 10 rad" in run.stderr
    case["load"] = {"mode": "force", "force": 2.0, "arc_length": 0.02}
    path.write_text(json.dumps(case))
    assert "load.force 2 N is above the plausible 0.1 N" in vibrissa.load_case(str(path)).warnings[1]


@pytest.fixture(scope="module")
def trial_csv(tmp_path_factory):
    path = tmp_path_factory.mktemp("guardrails") / "trial.csv"
    vibrissa.synthesize_trial(duration=0.1, seed=3).write(str(path))
    return path


def with_units(trial_csv, tmp_path, old, new):
    text = trial_csv.read_text()
    assert old in text
    out = tmp_path / "declared.csv"
    out.write_text(text.replace(old, new, 1))
    return out


def test_a_trial_as_written_raises_nothing(trial_csv):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert vibrissa.read_trial(str(trial_csv)).warnings == []


def test_a_trial_in_metres_declared_mm_is_a_35_um_whisker(trial_csv, tmp_path):
    declared = with_units(trial_csv, tmp_path, "length=m ", "length=mm ")
    with pytest.warns(UserWarning, match=r"whisker length .* um\) lies outside the plausible 1-200 mm of a rodent "
                                         r"whisker: did you mean .* mm \(metres given or declared as mm\)\?"):
        trial = vibrissa.read_trial(str(declared))
    assert len(trial.warnings) == 1


def test_radians_declared_as_degrees(trial_csv, tmp_path):
    declared = with_units(trial_csv, tmp_path, "angle=rad", "angle=deg")
    with pytest.warns(UserWarning, match=r"theta stays within \+-.* deg although the file declares angle=deg"):
        trial = vibrissa.read_trial(str(declared))
    assert any(w.startswith("theta stays within") for w in trial.warnings)
    with pytest.warns(UserWarning, match="radians declared as degrees"):
        vibrissa.analyze_trial(trial)
