"""The whole pipeline from Python: synthesize_trial, read_trial / Trial.write, analyze_trial, simulate_array.
Same inputs as the CLI give bit-identical numbers; progress; Ctrl-C; errors name the field."""

import json
import subprocess

import numpy as np
import pytest

import vibrissa
from calibrated import lasting
from interrupting import interrupt

h5py = pytest.importorskip("h5py")

WALL_CLOCK_KEYS = {"pipeline_seconds", "simulation_seconds"}


def run(cmd):
    done = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout


def attr_text(obj, name):
    value = obj.attrs.get(name, "")
    return value.decode() if isinstance(value, bytes) else str(value)


def h5_datasets(path, group=None, decode_codes=False):
    """Every dataset of an HDF5 file (or of one group) by path, as NumPy arrays (strings decoded; with
    `decode_codes`, code datasets as their names through their `codes` table, as Python's tables give them)."""
    out = {}
    with h5py.File(path, "r") as f:
        root = f[group] if group else f

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                value = obj[()]
                if obj.dtype.kind in "SO":
                    value = np.array([v.decode() if isinstance(v, bytes) else v for v in value], dtype="U")
                elif decode_codes and attr_text(obj, "units") == "code":
                    table = dict(entry.split(" ", 1) for entry in attr_text(obj, "codes").split(", "))
                    value = np.array([table[str(int(v))] for v in value], dtype="U")
                out[name] = value
        root.visititems(visit)
    return out


def without_wall_clock(summary):
    return {k: v for k, v in summary.items() if k not in WALL_CLOCK_KEYS}


def assert_same_arrays(expected, actual):
    """Same names, shapes, dtypes and bits (NaN where NaN)."""
    assert sorted(expected) == sorted(actual)
    for name, e in expected.items():
        a = actual[name]
        assert a.shape == e.shape, name
        if e.dtype.kind == "U":
            assert a.dtype.kind == "U" and (a == e).all(), name
        else:
            assert a.dtype == e.dtype, (name, a.dtype, e.dtype)
            assert np.array_equal(a, e, equal_nan=True), name


# A short synthetic trial shared by several tests (0.5 s: four contact periods).
SYNTH = dict(duration=0.5, mu=0.48, shapes=True, noise_position_um=3.0, noise_angle_deg=0.05, seed=7,
             theta_center_deg=12.0)


def scene(frames=None, whiskers=None, sides=None, pitches_deg=None):
    """The built-in array configuration with some fields changed."""
    config = vibrissa.default_array_config()
    if frames is not None:
        config["time"]["frames"] = frames
    if whiskers is not None:
        config["morphology"]["whiskers"] = whiskers
    if sides is not None:
        config["morphology"]["sides"] = sides
    if pitches_deg is not None:
        config["head"]["pitches_deg"] = pitches_deg
    return config


def synth_flags(options):
    flags = []
    for name, value in options.items():
        flag = "--" + name.replace("_", "-")
        flags += [flag] if value is True else [flag, value]
    return flags


@pytest.fixture(scope="module")
def synthetic_trial():
    return vibrissa.synthesize_trial(**SYNTH)


def test_synth_and_trial_match_the_cli_bit_for_bit(cli, tmp_path, synthetic_trial):
    cli_trial, py_trial = tmp_path / "cli.h5", tmp_path / "py.h5"
    run([cli, "synth", cli_trial, *synth_flags(SYNTH)])
    synthetic_trial.write(str(py_trial))
    assert_same_arrays(h5_datasets(cli_trial), h5_datasets(py_trial))

    run([cli, "trial", cli_trial, "--mu", "0.48", "--cutoff", "90", "--out", tmp_path / "cli_res", "--no-figures"])
    result = vibrissa.analyze_trial(str(cli_trial), mu=0.48, cutoff=90.0)
    cli_columns = h5_datasets(tmp_path / "cli_res" / "frames.h5", decode_codes=True)
    assert_same_arrays(cli_columns, result.columns)
    cli_summary = json.loads((tmp_path / "cli_res" / "summary.json").read_text())
    assert without_wall_clock(result.summary) == without_wall_clock(cli_summary)
    assert result.summary["friction"]["median"] == cli_summary["friction"]["median"]

    # .write(dir) writes the CLI's files: identical bytes except the wall-clock line.
    result.write(tmp_path / "py_res")
    for name in ("frames.csv",):
        assert (tmp_path / "py_res" / name).read_bytes() == (tmp_path / "cli_res" / name).read_bytes()
    assert_same_arrays(cli_columns, h5_datasets(tmp_path / "py_res" / "frames.h5", decode_codes=True))
    py_summary = json.loads((tmp_path / "py_res" / "summary.json").read_text())
    assert without_wall_clock(py_summary) == without_wall_clock(cli_summary)


def test_python_synthesized_trial_analyses_like_its_file(tmp_path, synthetic_trial):
    path = tmp_path / "t.h5"
    synthetic_trial.write(str(path))
    from_object = vibrissa.analyze_trial(synthetic_trial)
    from_file = vibrissa.analyze_trial(path)
    assert_same_arrays(from_file.columns, from_object.columns)
    assert from_file.summary["source"] == str(path) and from_object.summary["source"] == "synthetic"


def test_array_matches_the_cli_bit_for_bit(cli, tmp_path):
    config = scene(frames=120, whiskers=["C1", "C2", "C3", "D2", "B2"], pitches_deg=[-10, 0])
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(config))
    run([cli, "array", path, "--out", tmp_path / "cli", "--no-figures"])
    result = vibrissa.simulate_array(config)
    cli_data = h5_datasets(tmp_path / "cli" / "array.h5")
    assert_same_arrays(cli_data, result.datasets)
    assert (result.state == 1).any(), "the scene must have contacts for the comparison to mean anything"
    cli_summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    assert without_wall_clock(result.summary) == without_wall_clock(cli_summary)

    result.write(tmp_path / "py")
    for name in ("pitch_summary.csv", "config.json"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert_same_arrays(cli_data, h5_datasets(tmp_path / "py" / "array.h5"))
    # A path gives the same as the dict; None gives the built-in default, as `vibrissa array` without CONFIG.
    assert_same_arrays(result.datasets, vibrissa.simulate_array(path, threads=1).datasets)


def test_default_array_config_is_the_cli_default(cli):
    assert vibrissa.default_array_config() == json.loads(run([cli, "array", "--print-default-config"]))


def test_synthetic_trial_recovers_mu():
    trial = vibrissa.synthesize_trial(mu=0.48, duration=1.0)
    result = vibrissa.analyze_trial(trial)
    assert abs(result.summary["friction"]["median"] - 0.48) < 0.02
    used = result.mu_used == 1
    assert used.sum() == result.summary["friction"]["frames_used"]
    assert abs(np.median(result.mu[used]) - 0.48) < 0.02


def test_trial_arrays_and_round_trips(tmp_path, synthetic_trial):
    t = synthetic_trial
    n = len(t)
    assert n == 500 and repr(t).startswith("Trial(frames=500, contact_frames=")
    assert t.time.shape == (n,) and t.base_W.shape == (n, 3) and t.contact_W.shape == (n, 3)
    assert t.contact.dtype == np.uint8 and set(np.unique(t.contact)) == {0, 1}
    assert t.shape_W.shape[0] == n and t.shape_W.shape[2] == 3
    assert t.edges.shape == (1, 6) and t.rest_shape.shape == (41, 3)
    assert t.material["links"] == 100 and t.frame_rate_Hz == 1000.0
    for ext in ("h5", "mat"):
        path = tmp_path / f"t.{ext}"
        t.write(str(path))
        back = vibrissa.read_trial(str(path))
        for name in ("time", "base_W", "theta", "phi", "zeta", "contact", "contact_W", "shape_W", "rest_shape", "edges"):
            assert np.array_equal(getattr(back, name), getattr(t, name), equal_nan=True), (ext, name)
    t.write(str(tmp_path / "t.csv"))
    assert len(vibrissa.read_trial(str(tmp_path / "t.csv"))) == n


def test_result_table_and_dataframe(synthetic_trial):
    pd = pytest.importorskip("pandas")
    result = vibrissa.analyze_trial(synthetic_trial, mu=0.48)
    df = result.to_dataframe()
    assert isinstance(df, pd.DataFrame) and len(df) == len(synthetic_trial)
    assert list(df.columns) == list(result.columns)
    assert np.array_equal(df["cp_FT"].to_numpy(), result.cp_FT, equal_nan=True)
    assert result["fric_status"][synthetic_trial.contact == 0].tolist() == ["not_in_contact"] * int(
        (synthetic_trial.contact == 0).sum())
    with pytest.raises(AttributeError, match="no_such_column"):
        result.no_such_column  # noqa: B018


def test_figures_run_the_cli_script(tmp_path, synthetic_trial):
    pytest.importorskip("matplotlib")
    pngs = vibrissa.analyze_trial(synthetic_trial).figures(tmp_path / "fig")
    assert len(pngs) >= 5 and all(p.stat().st_size > 5_000 for p in pngs)


@pytest.mark.parametrize("call, total", [
    (lambda progress: vibrissa.synthesize_trial(duration=0.4, progress=progress), 400),
    (lambda progress: vibrissa.simulate_array(scene(frames=60), progress=progress), 31 * 60),
])
def test_progress_counts_increase_to_the_total(call, total):
    seen = []
    call(lambda done, of: seen.append((done, of)))
    assert seen, "progress was never called"
    counts = [d for d, _ in seen]
    assert all(of == total for _, of in seen)
    assert counts == sorted(set(counts)) and counts[-1] == total


def test_progress_of_analyze_trial(synthetic_trial):
    seen = []
    vibrissa.analyze_trial(synthetic_trial, progress=lambda done, of: seen.append((done, of)))
    total = int(synthetic_trial.contact.sum())
    counts = [d for d, _ in seen]
    assert counts and counts == sorted(set(counts)) and counts[-1] == total and {of for _, of in seen} == {total}


def test_an_exception_in_progress_stops_the_call():
    calls = []

    def progress(done, total):
        calls.append(done)
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        vibrissa.synthesize_trial(duration=20.0, progress=progress)
    assert len(calls) == 1 and calls[0] < 20_000


@pytest.mark.parametrize("with_progress", [False, True])
def test_ctrl_c_stops_simulate_array_within_half_a_second(with_progress):
    big = scene(frames=1000, sides="both", pitches_deg=[-20, -15, -10, -5, 0, 5, 10, 15, 20])
    assert interrupt(lambda p: vibrissa.simulate_array(big, progress=p, threads=1), 0.3, with_progress) < 0.5
    # The library is usable afterwards.
    assert vibrissa.simulate_array(scene(frames=20)).state.shape == (1, 31, 20)


@pytest.mark.parametrize("with_progress", [False, True])
def test_ctrl_c_stops_synthesis_and_analysis_within_half_a_second(with_progress):
    assert interrupt(lambda p: vibrissa.synthesize_trial(duration=60.0, progress=p), 0.3, with_progress) < 0.5
    long_trial = lasting(lambda d: vibrissa.synthesize_trial(duration=d), lambda t: vibrissa.analyze_trial(t, mu=0.48),
                         5.0, 0.5)
    assert interrupt(lambda p: vibrissa.analyze_trial(long_trial, mu=0.48, progress=p), 0.05, with_progress) < 0.5


def test_errors_name_the_field(tmp_path, synthetic_trial):
    with pytest.raises(TypeError, match="'peg_distance'"):
        vibrissa.synthesize_trial(peg_distance=20.0)
    with pytest.raises(ValueError, match="duration"):
        vibrissa.synthesize_trial(duration=-1.0)
    with pytest.raises(ValueError, match="cutoff must be finite and > 0 \\[Hz\\], got -5"):
        vibrissa.analyze_trial(synthetic_trial, cutoff=-5.0)
    with pytest.raises(ValueError, match="filter_order must be 2 or 4, got 3"):
        vibrissa.analyze_trial(synthetic_trial, filter_order=3)
    with pytest.raises(ValueError, match="mu must be finite and >= 0, got -0.1"):
        vibrissa.analyze_trial(synthetic_trial, mu=-0.1)
    with pytest.raises(ValueError, match="mu_eq7"):
        vibrissa.analyze_trial(synthetic_trial, mu_eq7=float("nan"))
    with pytest.raises(ValueError, match="time.frames"):
        vibrissa.simulate_array(scene(frames=1))
    with pytest.raises(ValueError, match=r"threads must lie in \[0, 1024\], got -2"):
        vibrissa.simulate_array(threads=-2)
    bad = tmp_path / "bad.csv"
    bad.write_text("# vibrissa-trial: 1\n# rest_point: 0 0 0\n# rest_point: 1 0 0\n# rest_point: 2 0.1 0\n"
                   "# edge: 1 1 0 0 0 1\ntime,base_x,base_y,base_z,theta,phi,contact\n0,0,0,0,0,0,1\n"
                   "0.001,0,nan,0,0,0,1\n")
    with pytest.raises(ValueError, match="column 'base_y'"):
        vibrissa.analyze_trial(bad)


def test_a_trial_built_from_arrays_analyses_like_the_same_trial_from_a_file(synthetic_trial):
    t = synthetic_trial
    mine = vibrissa.Trial(time=t.time, base_W=t.base_W, theta=t.theta, phi=t.phi, zeta=t.zeta, contact=t.contact,
                          contact_W=t.contact_W, rest_shape=t.rest_shape, edges=t.edges,
                          frame_rate_Hz=t.frame_rate_Hz, **t.material)
    assert len(mine) == len(t) and mine.source == "python"
    a, b = vibrissa.analyze_trial(t, mu=0.48), vibrissa.analyze_trial(mine, mu=0.48)
    for name in ("cp_FT", "fric_s_applied", "edge_MB"):
        np.testing.assert_array_equal(a[name], b[name])
    bad_time = t.time.copy()
    bad_time[5] = bad_time[4]
    with pytest.raises(ValueError, match="time"):
        vibrissa.Trial(time=bad_time, base_W=t.base_W, theta=t.theta, phi=t.phi, contact=t.contact,
                       rest_shape=t.rest_shape, edges=t.edges)
    with pytest.raises(ValueError, match="edges must have shape"):
        vibrissa.Trial(time=t.time, base_W=t.base_W, theta=t.theta, phi=t.phi, contact=t.contact,
                       rest_shape=t.rest_shape, edges=[0.0, 1.0])
