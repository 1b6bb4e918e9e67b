"""Sweeps on Dask (docs/sweeps.md): a real LocalCluster of worker processes, one worker killed mid-run, Ctrl-C,
resuming, and results bit for bit those of the same runs made one by one. Every cluster a test starts is shut
down by it, also on failure, and every wait has a deadline."""

import contextlib
import json
import logging
import os
import pathlib
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np
import pytest

import vibrissa
from vibrissa import sweep_runs, sweeps as sweep_module

xr = pytest.importorskip("xarray")
distributed = pytest.importorskip("distributed")
psutil = pytest.importorskip("psutil")

# Small array runs: 3 whiskers against a peg, each run a fraction of a second.
BASE = {"morphology": {"whiskers": ["C1", "C2", "D1"]}, "time": {"frames": 600},
        "objects": [{"type": "peg", "frame": "world", "point_mm": [20, -8, -3]}]}
GRID = {"objects.0.point_mm.0": [17.0, 20.0, 23.0], "whisking.amplitude_deg": [20, 30]}


@contextlib.contextmanager
def deadline(seconds, on_expiry):
    """Calls on_expiry() (which should kill what hangs) and interrupts the main thread if the block lasts longer
    than `seconds`."""
    expired = threading.Event()

    def expire():
        expired.set()
        on_expiry()
        import _thread
        _thread.interrupt_main()
    timer = threading.Timer(seconds, expire)
    timer.start()
    try:
        yield
    except KeyboardInterrupt:
        if expired.is_set():
            pytest.fail(f"timed out after {seconds} s")
        raise
    finally:
        timer.cancel()


@pytest.fixture
def local_cluster():
    """A LocalCluster of 2 worker processes started here; its Client and {address: pid} of the workers. Shut
    down afterwards; every worker process it started is killed if still alive."""
    with tempfile.TemporaryDirectory() as scratch:
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                           dashboard_address=None, silence_logs=logging.ERROR,
                                           local_directory=scratch)
        client = distributed.Client(cluster)
        started = set()

        def pids():
            found = client.run(os.getpid)
            started.update(found.values())
            return found
        try:
            yield client, pids
        finally:
            client.close()
            cluster.close()
            for pid in started:
                with contextlib.suppress(ProcessLookupError):
                    os.kill(pid, signal.SIGKILL)


@pytest.fixture(scope="module")
def serial():
    """The sweep's runs made one by one in this process (scheduler "serial": no Dask)."""
    return vibrissa.sweep("array", BASE, grid=GRID, scheduler="serial")


def assert_same_results(expected, found):
    """Same variables, coordinates and values, bit for bit (NaN where NaN)."""
    assert set(expected.variables) == set(found.variables)
    for name in expected.variables:
        e, f = expected[name].values, found[name].values
        assert e.dtype == f.dtype and e.shape == f.shape, name
        if e.dtype.kind == "f":
            assert np.array_equal(e.view(np.uint64), f.view(np.uint64)), name  # bit for bit, NaN included
        else:
            assert np.array_equal(e, f), name


def test_a_worker_killed_mid_run_loses_nothing_and_results_match_serial(local_cluster, serial, tmp_path):
    """A worker is killed (SIGKILL) while it is inside a chunk: the workers are held at the start of their
    chunks (holding.py) until one is killed, so the kill cannot come too late under load (all chunks already
    done) or too early (a task assigned but not started)."""
    import cloudpickle
    import holding
    client, pids = local_cluster
    workers = pids()
    flags = tmp_path / "flags"
    flags.mkdir()
    (flags / "hold").touch()
    cloudpickle.register_pickle_by_value(holding)
    try:
        assert sorted(client.run(holding.hold_chunks, str(flags)).values()) == sorted(workers.values())
    finally:
        cloudpickle.unregister_pickle_by_value(holding)
    killed = {}

    def kill_a_worker_in_a_chunk():
        try:
            stop = time.monotonic() + 60
            while time.monotonic() < stop:  # until a worker has entered a chunk (it is held there)
                started = [int(f.name.split("-")[1]) for f in flags.glob("started-*")]
                running = {address: keys for address, keys in client.processing().items() if keys}
                inside = [a for a, pid in workers.items() if pid in started and a in running]
                if inside:
                    killed["pid"], killed["keys"] = workers[inside[0]], running[inside[0]]
                    os.kill(killed["pid"], signal.SIGKILL)
                    break
                time.sleep(0.02)
        finally:
            (flags / "hold").unlink()  # let the other worker go on

    killer = threading.Thread(target=kill_a_worker_in_a_chunk)
    killer.start()
    with deadline(120, lambda: [os.kill(p, signal.SIGKILL) for p in pids().values()]):
        found = vibrissa.sweep("array", BASE, grid=GRID, client=client, chunk_size=1,
                               out=tmp_path / "dask").load()
    killer.join()
    assert killed, "no worker entered a chunk within 60 s"
    assert not psutil.pid_exists(killed["pid"]) or psutil.Process(killed["pid"]).status() == psutil.STATUS_ZOMBIE
    # Its chunk ran again elsewhere: every run is there once, and the results are the serial ones bit for bit.
    index = json.loads((tmp_path / "dask" / "index.json").read_text())["chunks"]
    assert sorted(map(int, index)) == list(range(6))
    assert_same_results(serial, found)
    assert dict(found.sizes) == {"objects.0.point_mm.0": 3, "whisking.amplitude_deg": 2, "pitch": 1, "whisker": 3,
                                 "time": 600, "component": 3}
    # ... and those of simulate_array called directly.
    config = sweep_runs.configured(BASE, {"objects.0.point_mm.0": 23.0, "whisking.amplitude_deg": 20})
    direct = vibrissa.simulate_array(config)
    one = found.sel({"objects.0.point_mm.0": 23.0, "whisking.amplitude_deg": 20})
    for name in ("FT", "MB", "state", "contact_point_W", "force_B"):
        np.testing.assert_array_equal(one[name].values, direct[name], err_msg=name)
    assert (direct.state == 1).any(), "the peg should touch some whisker"


def test_an_interrupted_sweep_resumes_where_it_stopped(serial, tmp_path, monkeypatch):
    ran = []
    original = sweep_module.run_chunk

    def counting(kind, base, runs, variables=None, on_error="raise"):
        ran.append([index for index, _ in runs])
        return original(kind, base, runs, variables, on_error)
    monkeypatch.setattr(sweep_module, "run_chunk", counting)

    def stop_after_two_chunks(done, total):
        if done >= 2:
            raise KeyboardInterrupt
    out = tmp_path / "out"
    with pytest.raises(KeyboardInterrupt):
        vibrissa.sweep("array", BASE, grid=GRID, scheduler="serial", chunk_size=1, out=out,
                       progress=stop_after_two_chunks)
    index = json.loads((out / "index.json").read_text())["chunks"]
    assert sorted(index) == ["0", "1"] and not (out / "sweep.nc").exists()
    # A chunk file written but not yet listed (killed between the two writes) is computed again, not doubled.
    del index["1"]
    (out / "index.json").write_text(json.dumps({"chunks": index}))
    ran.clear()
    seen = []
    resumed = vibrissa.sweep("array", BASE, grid=GRID, scheduler="serial", out=out,
                             progress=lambda done, total: seen.append(done)).load()
    assert ran == [[1], [2], [3], [4], [5]] and seen[0] == 1 and seen[-1] == 6
    assert_same_results(serial, resumed)
    # Done: a third call reads the results without running anything.
    ran.clear()
    vibrissa.sweep("array", BASE, grid=GRID, scheduler="serial", out=out).close()
    assert ran == []
    with pytest.raises(ValueError, match="holds another sweep"):
        vibrissa.sweep("array", BASE, grid={"whisking.amplitude_deg": [10, 20]}, scheduler="serial", out=out)


def children(pid):
    with contextlib.suppress(psutil.NoSuchProcess):
        return psutil.Process(pid).children(recursive=True)
    return []


def test_cli_ctrl_c_shuts_the_cluster_down_and_the_sweep_resumes(cli, tmp_path):
    # 24 runs of ~0.2 s (with GRID's six, all were once done before the interrupt took effect on a quiet machine;
    # with 24, 1-2 were done): the interrupt comes after the first chunk and well before the last.
    base = BASE
    grid = dict(GRID, **{"whisking.frequency_Hz": [6.0, 7.0, 8.0, 9.0]})
    config = {"kind": "array", "base": base, "grid": grid, "chunk_size": 1, "variables": ["state", "FT", "MB"]}
    path = tmp_path / "sweep.json"
    path.write_text(json.dumps(config))
    out = tmp_path / "out"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}  # the CLI finds its own package
    process = subprocess.Popen([cli, "sweep", str(path), "--out", str(out), "--workers", "2"], env=env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    workers = []
    try:
        with deadline(120, process.kill):
            while not (out / "index.json").exists():  # a chunk is done: the workers are up and busy
                assert process.poll() is None, process.communicate()
                workers = [p for p in children(process.pid) if "python" in p.name()] or workers
                time.sleep(0.05)
            workers = children(process.pid) or workers
            process.send_signal(signal.SIGINT)
            stdout, stderr = process.communicate()
    finally:
        process.kill()
        for w in workers:
            with contextlib.suppress(psutil.NoSuchProcess):
                w.kill()
    assert process.returncode == 130, stderr
    assert "interrupted" in stderr and "run the same command to resume" in stderr
    assert len(workers) >= 2
    gone, alive = psutil.wait_procs(workers, timeout=10)
    assert not alive, f"worker processes left running: {alive}"
    finished = json.loads((out / "index.json").read_text())["chunks"]
    assert 0 < len(finished) < 24 and not (out / "sweep.nc").exists()

    # The same command resumes it (here in this process: the scheduler is not part of the sweep).
    done = subprocess.run([cli, "sweep", str(path), "--out", str(out), "--scheduler", "serial"], env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "wrote" in done.stdout
    with xr.open_dataset(out / "sweep.nc") as found:
        assert not any(found.error.values.ravel().tolist())  # every run ran (the error variable is always there)
        expected = vibrissa.sweep("array", base, grid=grid, scheduler="serial")[["state", "FT", "MB"]]
        assert_same_results(expected, found.load().drop_vars("error"))


def test_trial_and_solve_sweeps_give_the_numbers_of_the_direct_calls(tmp_path):
    cases = vibrissa.sweep("solve", {"whisker": {"length": 0.03, "curvature": 20.0},
                                     "load": {"mode": "point", "point": [0.02, 0.005, 0.0]}},
                           grid={"load.point.1": [0.004, 0.005, 0.006], "whisker.curvature": [10.0, 20.0]},
                           scheduler="serial")
    assert cases.FT.dims == ("load.point.1", "whisker.curvature") and cases.force_W.dims[-1] == "component"
    direct = vibrissa.solve_point(vibrissa.Whisker.from_parabola(0.03, 10.0), [0.02, 0.006, 0.0])
    one = cases.sel({"load.point.1": 0.006, "whisker.curvature": 10.0})
    assert one.FT.item() == direct.whisker_frame.FT and np.array_equal(one.force_W.values, direct.force_W)
    assert one.status.item() == int(vibrissa.Status.converged) and "converged" in cases.status.attrs["codes"]

    trials = vibrissa.sweep("trial", {"synth": {"duration": 0.3}, "analysis": {"mu": 0.48}},
                            runs=[{"synth.mu": 0.3}, {"synth.mu": 0.6, "synth.seed": 5}], scheduler="serial")
    assert trials.cp_FT.dims == ("run", "frame") and list(trials["synth.mu"].values) == [0.3, 0.6]
    direct = vibrissa.analyze_trial(vibrissa.synthesize_trial(duration=0.3, mu=0.6, seed=5), mu=0.48)
    second = trials.isel(run=1)
    np.testing.assert_array_equal(second.cp_FT.values, direct.cp_FT)
    np.testing.assert_array_equal(second.time.values, direct.time)
    assert second["summary.friction.median"].item() == direct.summary["friction"]["median"]
    assert trials["synth.seed"].values.tolist()[1] == 5


def test_an_array_base_that_omits_keys_takes_the_defaults_values():
    """As in `vibrissa array`: a partial base (here without objects, as in docs/sweeps.md's JSON example) lies over
    the built-in configuration, so a swept path inside the default's peg exists."""
    partial = {"morphology": {"whiskers": ["C2"]}, "time": {"frames": 20}}
    found = vibrissa.sweep("array", partial, grid={"objects.0.point_mm.0": [16.0, 24.0]}, variables=["FT"],
                           scheduler="serial")
    default = vibrissa.default_array_config()
    assert default["objects"][0]["point_mm"][0] not in (16.0, 24.0)  # the sweep, not the default, placed the peg
    config = sweep_runs.configured(dict(default, morphology={**default["morphology"], "whiskers": ["C2"]},
                                        time={**default["time"], "frames": 20}), {"objects.0.point_mm.0": 24.0})
    np.testing.assert_array_equal(found.FT.sel({"objects.0.point_mm.0": 24.0}).values,
                                  vibrissa.simulate_array(config).FT)


def test_bad_sweeps_are_refused_before_anything_runs(tmp_path):
    with pytest.raises(ValueError, match=r"sweep run 1 \(time.frames=1\): time.frames must be an integer in \[2, "):
        vibrissa.sweep("array", BASE, grid={"time.frames": [100, 1]}, scheduler="serial", on_error="raise")
    with pytest.raises(ValueError, match=r"on_error must be one of \['record', 'raise'\], got 'ignore'"):
        vibrissa.sweep("array", BASE, grid={"time.frames": [100]}, scheduler="serial", on_error="ignore")
    with pytest.raises(ValueError, match="objects is a list of 1, so it has no entry 3"):
        vibrissa.sweep("array", BASE, grid={"objects.3.point_mm.0": [1.0]}, scheduler="serial")
    with pytest.raises(ValueError, match="kind must be one of"):
        vibrissa.sweep("arrays", BASE)
    with pytest.raises(ValueError, match="not both"):
        vibrissa.sweep("array", BASE, grid=GRID, runs=[{}])
    with pytest.raises(ValueError, match="sweep the components of a list"):
        vibrissa.sweep("array", BASE, grid={"objects.0.point_mm": [[20, -8, -3], [21, -8, -3]]}, scheduler="serial")
    with pytest.raises(ValueError, match=r"variables: \['nope'\] are not outputs"):
        vibrissa.sweep("array", BASE, grid={"whisking.amplitude_deg": [10]}, variables=["FT", "nope"],
                       scheduler="serial")
    assert not list(tmp_path.iterdir())


def test_the_command_refuses_bad_files_and_flags_before_starting_a_cluster(tmp_path, capsys):
    from vibrissa import sweeps
    empty = tmp_path / "empty.json"
    empty.write_text("")
    bogus = tmp_path / "bogus.json"
    bogus.write_text('{"kind": "bogus"}')
    good = tmp_path / "good.json"
    good.write_text('{"kind": "solve", "grid": {"load.point.0": [0.02]}}')
    out = str(tmp_path / "out")
    cases = [([str(empty)], "empty.json: not valid JSON"),
             ([str(bogus)], "kind must be one of ['array', 'trial', 'solve'], got 'bogus'"),
             ([str(good), "--out", out, "--workers", "0"], "workers must be a positive integer, got 0"),
             ([str(good), "--out", out, "--chunk-size", "0"], "chunk_size must be a positive integer, got 0")]
    for argv, message in cases:
        assert sweeps.main(argv) == 1
        captured = capsys.readouterr()
        assert captured.out == ""  # refused before the banner: no cluster was started
        first = captured.err.splitlines()[0]
        assert first.startswith("vibrissa sweep: error: ") and message in first, first
    assert not (tmp_path / "out").exists()


REPO = pathlib.Path(__file__).resolve().parents[2]
PACKAGE_PARENT = str(pathlib.Path(vibrissa.__file__).resolve().parents[1])


def test_the_documented_sweep_and_the_scaling_script_run_as_written(tmp_path):
    script = tmp_path / "peg_sweep.py"
    script.write_text(re.findall(r"```python\n(.*?)```", (REPO / "docs" / "sweeps.md").read_text(), flags=re.S)[0])
    env = dict(os.environ, PYTHONPATH=PACKAGE_PARENT)
    done = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=180)
    assert done.returncode == 0, done.stderr
    with xr.open_dataset(tmp_path / "peg_sweep" / "sweep.nc") as found:
        assert dict(found.sizes)["objects.0.point_mm.0"] == 3 and "MB" in found
    done = subprocess.run([sys.executable, str(REPO / "examples" / "sweep_scaling.py"), "--runs", "8", "--frames", "20",
                           "--workers", "2", "--variables", "FT", "MB", "--overhead-tasks", "6"],
                          env=env, capture_output=True, text=True, timeout=180)
    assert done.returncode == 0, done.stderr
    assert done.stdout.count("bit-identical to serial: True") == 2 and "overhead per task" in done.stdout


def test_a_sweep_goes_on_after_a_bad_run_and_says_why(tmp_path):
    # Issue 23: a refused configuration (run 1: an array config the reader refuses) and a run that fails when
    # it runs (run 3: a solve case whose load is refused) are recorded; the other runs equal a clean sweep.
    case = {"whisker": {"length": 0.03, "curvature": 20.0},
            "load": {"mode": "force", "force": 1e-4, "arc_length": 0.02}}
    forces = [1e-4, 2e-4, 3e-4, -1.0]
    with pytest.warns(UserWarning, match=r"sweep: 1 of 4 runs failed .*sweep run 3 \(load.force=-1.0\): "
                                         r"load.force must be >= 0"):
        solved = vibrissa.sweep("solve", case, grid={"load.force": forces}, scheduler="serial",
                                out=tmp_path / "solve")
    assert solved.error.values.tolist()[:3] == ["", "", ""]
    assert np.isnan(solved.force_magnitude.values[3]) and np.isnan(solved.status.values[3])
    clean = vibrissa.sweep("solve", case, grid={"load.force": forces[:3]}, scheduler="serial")
    np.testing.assert_array_equal(solved.force_W.values[:3], clean.force_W.values)
    assert "error" not in clean.variables or not any(clean.error.values.tolist())
    with pytest.warns(UserWarning, match=r"1 of 2 runs failed .*sweep run 1 \(time.frames=1\): time.frames must"):
        arrays = vibrissa.sweep("array", BASE, grid={"time.frames": [100, 1]}, scheduler="serial",
                                variables=["FT"])
    assert arrays.error.values.tolist()[0] == "" and np.isnan(arrays.FT.values[1]).all()
    assert np.isfinite(arrays.FT.values[0]).any()
    # Every run refused: nothing to record, the first error is raised.
    with pytest.raises(ValueError, match=r"sweep run 0 \(load.force=-1.0\)"):
        vibrissa.sweep("solve", case, grid={"load.force": [-1.0, -2.0]}, scheduler="serial")
