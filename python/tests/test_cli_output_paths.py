"""Issue 23: outputs of the CLI go where a Unix user expects (docs/formats.md, "Output paths"), a write that
fails (full disk, file size limit, unwritable folder) is an error with exit status 1 and no crash or library
noise, and an output folder holds one complete set after `kill -9` at any moment."""

import json
import os
import random
import resource
import signal
import stat
import subprocess
import time

import pytest

from test_cli_outputs import SMALL_ARRAY, array_config, default_signals, leftovers

CASE = {"whisker": {"length": 0.03, "curvature": 20.0}, "load": {"mode": "point", "point": [0.02, 0.004, 0.001]}}
NOBODY = 65534


def run(cli, *args, preexec_fn=default_signals, timeout=120, **kw):
    return subprocess.run([cli, *map(str, args)], capture_output=True, text=True, preexec_fn=preexec_fn,
                          timeout=timeout, **kw)


def as_nobody():
    default_signals()
    os.setgid(NOBODY)
    os.setuid(NOBODY)


def with_file_size_limit(limit_bytes):
    def limit():
        default_signals()
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # writes past the limit fail with EFBIG, as on a full disk
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))
    return limit


@pytest.fixture
def public_tmp():
    """A folder that user nobody can enter and read (pytest's tmp_path is private to root)."""
    import shutil
    import tempfile
    path = tempfile.mkdtemp(prefix="vibrissa-public-")
    os.chmod(path, 0o755)
    yield __import__("pathlib").Path(path)
    shutil.rmtree(path)


@pytest.fixture
def case_file(tmp_path):
    path = tmp_path / "case.json"
    path.write_text(json.dumps(CASE))
    return path


def test_dev_null_is_written_not_replaced(cli, case_file, tmp_path):
    # Root: a private null device, so that a bug could not replace the machine's /dev/null.
    device = "/dev/null"
    if os.geteuid() == 0:
        device = tmp_path / "null"
        os.mknod(device, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    for args in (["solve", case_file, "-o", device], ["demo", "-o", device],
                 ["synth", device, "--duration", "0.05"]):
        done = run(cli, *args)
        # synth names its format by the extension: a device has none, which is an error naming the path
        assert done.returncode == (1 if args[0] == "synth" else 0), done.stderr
        assert stat.S_ISCHR(os.lstat(device).st_mode)
    assert leftovers(tmp_path) == []


@pytest.mark.skipif(os.geteuid() != 0, reason="needs root to run the CLI as another user")
def test_dev_null_works_for_a_normal_user(cli, public_tmp):
    case_file = public_tmp / "case.json"
    case_file.write_text(json.dumps(CASE))
    os.chmod(case_file, 0o644)
    done = run(cli, "solve", case_file, "-o", "/dev/null", preexec_fn=as_nobody)
    assert done.returncode == 0, done.stderr
    assert done.stdout == ""
    assert stat.S_ISCHR(os.lstat("/dev/null").st_mode)


def test_a_fifo_receives_the_result_and_stays_a_fifo(cli, case_file, tmp_path):
    fifo = tmp_path / "result.json"
    os.mkfifo(fifo)
    proc = subprocess.Popen([cli, "solve", str(case_file), "-o", str(fifo)], stderr=subprocess.PIPE,
                            preexec_fn=default_signals)
    with open(fifo) as f:  # opening the reading end lets the writer's open return
        result = json.load(f)
    assert proc.wait(timeout=60) == 0
    assert result["status"] == "converged"
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_a_symlink_is_followed_and_stays_a_link(cli, case_file, tmp_path):
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "result.json").write_text("old")
    os.symlink("data/result.json", tmp_path / "result.json")
    os.symlink("made.json", tmp_path / "dangling.json")
    for out in ("result.json", "dangling.json"):
        done = run(cli, "solve", case_file, "-o", tmp_path / out)
        assert done.returncode == 0, done.stderr
        assert os.path.islink(tmp_path / out)
    assert json.loads((tmp_path / "data" / "result.json").read_text())["status"] == "converged"
    assert json.loads((tmp_path / "made.json").read_text())["status"] == "converged"


def test_dash_is_standard_output(cli, case_file, tmp_path):
    done = run(cli, "solve", case_file, "-o", "-", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["status"] == "converged"
    assert not (tmp_path / "-").exists()


@pytest.mark.parametrize("what", ["directory", "missing folder"])
def test_an_output_that_cannot_be_a_file_is_an_error_naming_it(cli, case_file, tmp_path, what):
    out = tmp_path if what == "directory" else tmp_path / "no" / "such.json"
    done = run(cli, "solve", case_file, "-o", out)
    assert done.returncode == 1
    assert done.stderr.startswith(f"vibrissa: error: cannot write '{out}': ")
    assert leftovers(tmp_path) == []


def test_an_output_folder_given_as_a_link_is_filled_and_stays_a_link(cli, tmp_path):
    (tmp_path / "disk").mkdir()
    os.symlink("disk", tmp_path / "out")
    done = run(cli, "array", array_config(tmp_path, 10), "--out", tmp_path / "out", "--no-figures")
    assert done.returncode == 0, done.stderr
    assert os.path.islink(tmp_path / "out")
    assert (tmp_path / "disk" / "array.h5").is_file()


@pytest.mark.parametrize("command", ["synth_h5", "synth_mat", "synth_csv", "array", "trial"])
def test_a_write_past_a_file_size_limit_is_an_error_not_a_crash(cli, tmp_path, command):
    # As on a full disk: the writer meets EFBIG. libhdf5 1.10 crashed in its clean-up after such a write (issue
    # 23, defect 8); matio reports no failed write at all.
    trial = tmp_path / "trial.csv"
    assert run(cli, "synth", trial, "--duration", "0.2").returncode == 0
    args = {"synth_h5": ["synth", tmp_path / "x.h5", "--duration", "3.3", "--shapes"],
            "synth_mat": ["synth", tmp_path / "x.mat", "--duration", "3.3", "--shapes"],
            "synth_csv": ["synth", tmp_path / "x.csv", "--duration", "3.3", "--shapes"],
            "array": ["array", "--out", tmp_path / "arr", "--no-figures", "--csv"],
            "trial": ["trial", trial, "--out", tmp_path / "res", "--no-figures"]}[command]
    done = run(cli, *args, preexec_fn=with_file_size_limit(20_000 if command == "trial" else 100_000))
    assert done.returncode == 1, (done.returncode, done.stderr)
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith("vibrissa: error: cannot write '") and ("File too large" in last or "incomplete" in last), last
    assert "HDF5" not in done.stderr
    assert leftovers(tmp_path) == []


@pytest.mark.skipif(os.geteuid() != 0, reason="needs root to run the CLI as another user")
def test_array_into_an_unwritable_folder_is_a_clean_error(cli, public_tmp):
    # The HDF5 writer runs on a second thread; its error used to make libhdf5 print "HDF5: infinite loop closing
    # library" and junk at exit (issue 23, defect 8).
    locked = public_tmp / "locked"
    locked.mkdir(mode=0o555)
    config = array_config(public_tmp, 10)
    os.chmod(config, 0o644)
    for out in (locked, locked / "sub"):
        done = run(cli, "array", config, "--out", out, "--no-figures", preexec_fn=as_nobody)
        assert done.returncode == 1
        last = done.stderr.strip().splitlines()[-1]
        assert last.startswith("vibrissa: error: ") and "Permission denied" in last, done.stderr
        assert "HDF5" not in done.stderr


def test_kill_9_of_array_leaves_one_complete_set(cli, tmp_path):
    """Issue 23, defect 10: `array --csv` over an older run, killed with SIGKILL at random moments (seeded). Every
    folder must hold the files of one run: the frames in array.h5, config.json and summary.json agree."""
    h5py = pytest.importorskip("h5py")
    out = tmp_path / "out"
    (tmp_path / "keep").mkdir()
    configs = [array_config(tmp_path, frames) for frames in (12, 16)]
    assert run(cli, "array", configs[0], "--out", out, "--csv", "--no-figures").returncode == 0
    (out / "notes.txt").write_text("mine")
    started = time.monotonic()
    assert run(cli, "array", configs[1], "--out", out, "--csv", "--no-figures").returncode == 0
    duration = time.monotonic() - started
    rng = random.Random(23)
    for k in range(12):
        proc = subprocess.Popen([cli, "array", str(configs[k % 2]), "--out", str(out), "--csv", "--no-figures"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, preexec_fn=default_signals)
        time.sleep(rng.uniform(0.3, 1.1) * duration)
        proc.kill()
        proc.wait()
        frames = json.loads((out / "summary.json").read_text())["frames"]
        assert json.loads((out / "config.json").read_text())["time"]["frames"] == frames, f"kill {k}"
        with h5py.File(out / "array.h5", "r") as f:
            assert f["MB"].shape[2] == frames, f"kill {k}: array.h5 of another run"
        rows = (out / "array.csv").read_text().count("\n") - 1
        assert rows == 3 * frames, f"kill {k}: array.csv of another run"
        assert (out / "notes.txt").read_text() == "mine"
        for stale in tmp_path.glob(".tmp-*"):  # only SIGKILL leaves these; safe to delete (docs/formats.md)
            subprocess.run(["rm", "-rf", str(stale)], check=True)
