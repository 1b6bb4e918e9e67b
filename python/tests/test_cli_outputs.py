"""Outputs of `vibrissa array`, `trial`, `synth` and of the figure scripts are atomic: a run killed while
writing (SIGTERM, SIGINT, SIGHUP) leaves the older outputs byte-identical and no `.tmp-*` file, and exits
with the signal's status; --no-figures removes the figures of an older run. Deterministic through the documented test hook
VIBRISSA_TEST_PAUSE_BEFORE_COMMIT (io/atomic_file.hpp): the writer stops after writing every temporary,
before the first rename, and waits for the signal."""

import json
import os
import signal
import subprocess
import sys

import pytest

SMALL_ARRAY = {
    "morphology": {"source": "towal2011", "sides": "right", "whiskers": ["C1", "C2", "D1"]},
    "time": {"start_s": 0, "end_s": 0.0625, "frames": 20},
    "objects": [{"type": "peg", "frame": "world", "point_mm": [20, -8, -3]}],
    "output": {"render_count": 2},
}


def default_signals():
    # The test runner may run with SIGINT ignored (background jobs); the CLI keeps ignored signals ignored.
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, signal.SIG_DFL)


def snapshot(folder):
    return {p.relative_to(folder): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def leftovers(folder):
    """Temporaries left in the folder or beside it (an output folder is staged as a sibling `.tmp-*`)."""
    return [p.name for p in folder.rglob(".tmp-*")] + [p.name for p in folder.parent.glob(".tmp-*")]


def run(cli, *args):
    done = subprocess.run([cli, *map(str, args)], capture_output=True, text=True, preexec_fn=default_signals)
    assert done.returncode == 0, done.stderr
    return done


def kill_while_writing(cli, args, pause_at, sig):
    """Runs the CLI until its writer pauses before renaming `pause_at`, sends `sig`, returns the exit code."""
    env = dict(os.environ, VIBRISSA_TEST_PAUSE_BEFORE_COMMIT=pause_at)
    proc = subprocess.Popen([cli, *map(str, args)], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True, preexec_fn=default_signals)
    lines = []
    for line in proc.stderr:
        lines.append(line)
        if "test hook: paused before renaming" in line:
            break
    else:
        proc.wait()
        pytest.fail("the run ended without reaching the test hook: " + "".join(lines))
    temporary = lines[-1].split("paused before renaming ")[1].split(" to ")[0]
    # beside the target (`.tmp-<pid>-<name>`) or in the staged output folder (`.tmp-<pid>-<folder>/<name>`)
    assert f".tmp-{proc.pid}-" in temporary and temporary.endswith(pause_at)
    proc.send_signal(sig)
    proc.stderr.read()
    return proc.wait()


def array_config(tmp_path, frames):
    path = tmp_path / f"array_{frames}.json"
    path.write_text(json.dumps(dict(SMALL_ARRAY, time=dict(SMALL_ARRAY["time"], frames=frames))))
    return path


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT, signal.SIGHUP])
def test_killed_array_run_keeps_the_older_outputs(cli, tmp_path, sig):
    out = tmp_path / "out"
    run(cli, "array", array_config(tmp_path, 20), "--out", out, "--csv", "--no-figures")
    before = snapshot(out)
    assert set(map(str, before)) == {"array.h5", "array.csv", "pitch_summary.csv", "config.json", "summary.json"}

    code = kill_while_writing(cli, ["array", array_config(tmp_path, 30), "--out", out, "--csv", "--no-figures"],
                              "array.h5", sig)
    assert code == -sig
    assert leftovers(out) == []
    assert snapshot(out) == before
    h5py = pytest.importorskip("h5py")
    with h5py.File(out / "array.h5", "r") as f:
        assert f["MB"].shape == (1, 3, 20)


def test_killed_trial_run_keeps_the_older_outputs(cli, tmp_path):
    trial = tmp_path / "trial.h5"
    run(cli, "synth", trial, "--duration", "0.1")
    out = tmp_path / "results"
    run(cli, "trial", trial, "--out", out, "--no-figures")
    before = snapshot(out)
    assert set(map(str, before)) == {"frames.csv", "frames.h5", "summary.json"}

    code = kill_while_writing(cli, ["trial", trial, "--out", out, "--no-figures", "--mu", "0.3"], "frames.csv",
                              signal.SIGINT)
    assert code == -signal.SIGINT
    assert leftovers(out) == []
    assert snapshot(out) == before


def test_killed_synth_keeps_the_older_trial_file(cli, tmp_path):
    trial = tmp_path / "trial.mat"
    run(cli, "synth", trial, "--duration", "0.1")
    before = trial.read_bytes()
    code = kill_while_writing(cli, ["synth", trial, "--duration", "0.2"], "trial.mat", signal.SIGTERM)
    assert code == -signal.SIGTERM
    assert leftovers(tmp_path) == []
    assert trial.read_bytes() == before


def test_no_figures_removes_the_figures_of_an_older_run(cli, tmp_path):
    out = tmp_path / "array_out"
    out.mkdir()
    stale = ["array_traces.png", "array_animation.mp4", "array_animation.gif", "array_animation_frame.png",
             "pitch_sweep.png"]
    for name in stale:
        (out / name).write_bytes(b"old figure")
    (out / "notes.txt").write_text("mine")
    run(cli, "array", array_config(tmp_path, 10), "--out", out, "--no-figures")
    assert sorted(p.name for p in out.iterdir()) == sorted(
        ["array.h5", "pitch_summary.csv", "config.json", "summary.json", "notes.txt"])

    trial = tmp_path / "trial.csv"
    run(cli, "synth", trial, "--duration", "0.1")
    results = tmp_path / "trial_results"
    (results / "figures").mkdir(parents=True)
    (results / "figures" / "fig3a_world_signals.png").write_bytes(b"old figure")
    run(cli, "trial", trial, "--out", results, "--no-figures")
    assert sorted(p.name for p in results.iterdir()) == ["frames.csv", "frames.h5", "summary.json"]


FIGURES = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, "figures")
SAVE_THEN = """
import os, signal, sys
from atomic_save import replacing
with replacing(sys.argv[1]) as tmp:
    with open(tmp, "wb") as f:
        f.write(b"half a new figure")
    assert os.path.dirname(tmp) == os.path.dirname(os.path.abspath(sys.argv[1]))
    if sys.argv[2] == "raise":
        raise RuntimeError("matplotlib failed")
    if sys.argv[2] == "kill":
        os.kill(os.getpid(), signal.SIGTERM)
"""


@pytest.mark.parametrize("how, code", [("raise", 1), ("kill", 128 + signal.SIGTERM), ("finish", 0)])
def test_figure_scripts_replace_their_files_atomically(tmp_path, how, code):
    figure = tmp_path / "array_traces.png"
    figure.write_bytes(b"old figure")
    done = subprocess.run([sys.executable, "-c", SAVE_THEN, str(figure), how], cwd=FIGURES,
                          env=dict(os.environ, PYTHONPATH=FIGURES), capture_output=True, text=True,
                          preexec_fn=default_signals)
    assert done.returncode == code, done.stderr
    assert figure.read_bytes() == (b"half a new figure" if how == "finish" else b"old figure")
    assert leftovers(tmp_path) == []


def test_several_trials_are_analysed_each_with_one_summary_table(cli, tmp_path):
    # The per-whisker trials of `vibrissa reconstruct --whisker` (NAME/trial.h5): one folder each inside --out,
    # named after the trial's folder since the file names repeat; a bad trial does not stop the others.
    import numpy as np
    import vibrissa
    for name, seed in (("C1", 1), ("C2", 3)):
        (tmp_path / name).mkdir()
        subprocess.run([cli, "synth", str(tmp_path / name / "trial.h5"), "--duration", "0.5", "--seed", str(seed)],
                       check=True, capture_output=True)
    (tmp_path / "D1").mkdir()
    (tmp_path / "D1" / "trial.csv").write_text("not a trial\n")
    trials = [str(tmp_path / n / f) for n, f in (("C1", "trial.h5"), ("D1", "trial.csv"), ("C2", "trial.h5"))]
    run = subprocess.run([cli, "trial", *trials, "--out", str(tmp_path / "all"), "--no-figures", "--mu", "0.48"],
                         capture_output=True, text=True)
    assert run.returncode == 1 and "1 of 3 trials failed" in run.stderr and "D1/trial.csv" in run.stderr
    lines = (tmp_path / "all" / "trials_summary.tsv").read_text().splitlines()
    assert lines[0].split("\t") == ["trial", "frames", "contact_periods", "contact_frames", "median_mu", "mu_frames",
                                    "results"]
    rows = [line.split("\t") for line in lines[1:]]
    assert [r[0] for r in rows] == [trials[0], trials[2]]
    for row, name in zip(rows, ("C1", "C2")):
        summary = json.loads((tmp_path / "all" / name / "summary.json").read_text())
        direct = vibrissa.analyze_trial(vibrissa.read_trial(str(tmp_path / name / "trial.h5")), mu=0.48)
        assert row[6] == str(tmp_path / "all" / name) and int(row[1]) == len(direct.time)
        assert float(row[4]) == pytest.approx(direct.summary["friction"]["median"], rel=1e-5)
        assert summary["friction"]["median"] == direct.summary["friction"]["median"]
        assert not np.isnan(float(row[4]))
    same = subprocess.run([cli, "trial", trials[0], trials[0], "--out", str(tmp_path / "x"), "--no-figures"],
                          capture_output=True, text=True)
    assert same.returncode == 1 and "--out" in same.stderr and "repeat" in same.stderr


def test_analyze_trials_gives_the_cli_summary_table(cli, tmp_path):
    import vibrissa
    paths = {}
    for name, seed in (("C1", 1), ("C2", 3)):
        paths[name] = tmp_path / f"{name}.h5"
        subprocess.run([cli, "synth", str(paths[name]), "--duration", "0.5", "--seed", str(seed)], check=True,
                       capture_output=True)
    results, table = vibrissa.analyze_trials({n: vibrissa.read_trial(str(p)) for n, p in paths.items()}, mu=0.48)
    assert list(table.index) == ["C1", "C2"] and set(results) == {"C1", "C2"}
    run = subprocess.run([cli, "trial", str(paths["C1"]), str(paths["C2"]), "--out", str(tmp_path / "all"),
                          "--no-figures", "--mu", "0.48"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    rows = [line.split("\t") for line in (tmp_path / "all" / "trials_summary.tsv").read_text().splitlines()[1:]]
    for row, name in zip(rows, ("C1", "C2")):
        line = table.loc[name]
        assert [int(row[1]), int(row[2]), int(row[3]), int(row[5])] == [
            line.frames, line.contact_periods, line.contact_frames, line.mu_frames]
        assert float(row[4]) == pytest.approx(line.median_mu, rel=1e-5)
        assert results[name].summary["friction"]["median"] == line.median_mu
    # reconstruct(whiskers=...) pairs and lists of paths are taken too
    again = vibrissa.analyze_trials({"C1": (vibrissa.read_trial(str(paths["C1"])), {})}, mu=0.48)[1]
    assert again.loc["C1"].median_mu == table.loc["C1"].median_mu
    assert list(vibrissa.analyze_trials([paths["C2"]])[1].index) == [str(paths["C2"])]
    with pytest.raises(ValueError, match="trials"):
        vibrissa.analyze_trials({})
