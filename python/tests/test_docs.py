"""The tutorial (docs/python.md) and the example scripts run as written."""

import os
import pathlib
import re
import subprocess
import sys

import pytest

import vibrissa

REPO = pathlib.Path(__file__).resolve().parents[2]
PACKAGE_PARENT = str(pathlib.Path(vibrissa.__file__).resolve().parents[1])  # the directory on PYTHONPATH


def python_blocks(markdown):
    return re.findall(r"```python\n(.*?)```", markdown, flags=re.S)


def test_tutorial_code_blocks_run_in_order(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    blocks = python_blocks((REPO / "docs" / "python.md").read_text())
    assert len(blocks) >= 6
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__tutorial__"}
    for i, block in enumerate(blocks):
        try:
            exec(compile(block, f"docs/python.md block {i + 1}", "exec"), namespace)
        except Exception as error:  # name the block that broke
            pytest.fail(f"docs/python.md python block {i + 1} failed: {error!r}\n{block}")
    assert (tmp_path / "peg.png").stat().st_size > 10_000
    assert (tmp_path / "result.json").is_file()
    assert (tmp_path / "synthetic_results" / "summary.json").is_file()
    assert len(list((tmp_path / "synthetic_results" / "figures").glob("*.png"))) >= 5
    assert (tmp_path / "array_results" / "array.h5").is_file()


def test_peg_example_script(tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "peg.png"
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=PACKAGE_PARENT)
    done = subprocess.run([sys.executable, str(REPO / "examples" / "peg_contact.py"), "--output", str(out)],
                          capture_output=True, text=True, env=env, cwd=tmp_path, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "F_T =" in done.stdout and "M_B =" in done.stdout
    assert out.stat().st_size > 10_000


def test_scaling_script_runs(tmp_path):
    done = subprocess.run([sys.executable, str(REPO / "examples" / "batch_scaling.py"), "--frames", "64",
                           "--series", "4", "--repeats", "1", "--max-threads", "2"],
                          capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, PYTHONPATH=PACKAGE_PARENT))
    assert done.returncode == 0, done.stderr
    assert "speed-up" in done.stdout
