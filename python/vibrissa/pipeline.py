"""The whole pipeline from Python: synthetic trials, trial analysis and array simulations.

Each function runs the same C++ code as the matching CLI subcommand, so the same inputs give bit-identical
numbers (``vibrissa synth`` -> :func:`synthesize_trial`, ``vibrissa trial`` -> :func:`analyze_trial`,
``vibrissa array`` -> :func:`simulate_array`). Names are those of the CLI flags (with underscores) and of the
output files. Long calls release the GIL, accept ``progress(done, total)`` and stop with
``KeyboardInterrupt`` within a fraction of a second of Ctrl-C. See docs/python.md.
"""

import json
import os
import pathlib
import subprocess
import sys
import tempfile

import warnings

import numpy as np

from . import _vibrissa
from .labelled import to_dataset
from ._vibrissa import Trial, read_trial  # noqa: F401

__all__ = ["ArrayResult", "Trial", "TrialResult", "analyze_trial", "analyze_trials", "default_array_config", "read_trial",
           "simulate_array", "synthesize_trial", "synthesize_trial_defaults"]

_FIGURES_DIR = pathlib.Path(__file__).resolve().parent / "figures"


def _figure_script(name):
    """The CLI's plotting script `name`: $VIBRISSA_FIGURES_DIR (as for the CLI), else the package's copy."""
    directory = pathlib.Path(os.environ.get("VIBRISSA_FIGURES_DIR", _FIGURES_DIR))
    path = directory / name
    if not path.is_file():
        raise FileNotFoundError(f"figure script not found: {path}")
    return path


def synthesize_trial(*, progress=None, **options):
    """A synthetic whisking trial against a peg with friction, exactly as ``vibrissa synth`` writes it.

    Keywords are the ``vibrissa synth`` flags with underscores and their units in the name: ``mu``,
    ``duration`` [s], ``frame_rate`` [Hz], ``whisk_hz``, ``theta_center_deg``, ``theta_amplitude_deg``,
    ``protraction_fraction``, ``phi_slope``, ``zeta_slope``, ``whisker_length_mm``, ``curvature`` [1/m],
    ``peg_distance_mm``, ``peg_azimuth_deg``, ``noise_position_um``, ``noise_angle_deg``, ``seed`` (int) and
    ``shapes`` (bool: also track 3D shapes). Unknown keywords raise TypeError. ``progress(done, total)``
    counts simulated frames.
    """
    return _vibrissa._synthesize_trial(options, progress)


def synthesize_trial_defaults():
    """The numeric options of :func:`synthesize_trial` and their defaults (units as named)."""
    return dict(_vibrissa._synth_parameter_defaults())


class _NamedArrays:
    """Attribute and item access to the named arrays in ``self._arrays`` (file column / dataset names)."""

    _what = "array"

    def __getattr__(self, name):
        arrays = self.__dict__.get("_arrays", {})
        if name in arrays:
            return arrays[name]
        raise AttributeError(f"{type(self).__name__} has no {self._what} or attribute {name!r}")

    def __getitem__(self, name):
        return self._arrays[name]

    def __dir__(self):
        return sorted(set(super().__dir__()) | {k for k in self._arrays if k.isidentifier()})


# Columns renamed in 0.1.x: the force and moment directions are in rad like every output (docs/formats.md, "Units").
_DEGREE_COLUMNS = {f"{prefix}_{name}_deg": f"{prefix}_{name}" for prefix in ("cp", "edge", "fric")
                   for name in ("FD", "MD")}


class TrialResult(_NamedArrays):
    """The outputs of ``vibrissa trial``: per-frame arrays named as the columns of ``frames.h5``
    (``result.cp_FT``, ``result["mu"]``; status columns are string arrays), ``summary`` (the dict of
    ``summary.json``), :meth:`to_dataframe`, :meth:`to_xarray`, :meth:`write` and :meth:`figures`."""

    def __init__(self, outputs, trial):
        self._outputs = outputs
        self.trial = trial
        self.columns = dict(outputs.columns())
        self._arrays = self.columns
        self.summary = json.loads(outputs.summary_json())

    _what = "column"

    def __getattr__(self, name):
        if name in _DEGREE_COLUMNS and _DEGREE_COLUMNS[name] in self.__dict__.get("_arrays", {}):
            return self._degrees(name)
        return super().__getattr__(name)

    def __getitem__(self, name):
        if name in _DEGREE_COLUMNS and name not in self._arrays:
            return self._degrees(name)
        return super().__getitem__(name)

    def _degrees(self, name):
        new = _DEGREE_COLUMNS[name]
        warnings.warn(f"TrialResult column {name!r} is deprecated: use {new!r} (rad); vibrissa 0.2.0 removes it",
                      DeprecationWarning, stacklevel=3)
        return np.degrees(self._arrays[new])

    def __len__(self):
        return len(self.columns["time"])

    def __repr__(self):
        friction = self.summary.get("friction") or {}
        median = friction.get("median")
        mu = f", median_mu={median:.4g}" if isinstance(median, float) else ""
        return (f"TrialResult(frames={len(self)}, contact_frames={self.summary['contact_frames']}, "
                f"periods={self.summary['contact_periods']}{mu})")

    def to_dataframe(self):
        """The per-frame table as a pandas DataFrame (columns in frames.csv order; needs python3-pandas)."""
        import pandas as pd
        return pd.DataFrame(self.columns)

    def to_xarray(self):
        """The per-frame table as an ``xarray.Dataset`` over dimension ``time`` (its coordinate), every column
        with ``units`` and ``long_name``; status columns as int8 codes with their ``codes`` table. Identical to
        ``xarray.open_dataset`` of the ``frames.h5`` that :meth:`write` writes (needs python3-xarray)."""
        return to_dataset(self._outputs.labelled())

    def write(self, directory):
        """Writes frames.csv, frames.h5 and summary.json into `directory` (created), exactly as
        ``vibrissa trial --out DIR --no-figures`` does. Returns the directory as a pathlib.Path."""
        directory = pathlib.Path(directory)
        self._outputs.write(str(directory))
        return directory

    def view(self, path="trial_view.html"):
        """Writes the interactive 3D viewer of this trial, one self-contained HTML file (docs/viewer.md; as
        ``vibrissa view TRIAL``), and returns its path."""
        import tempfile
        from .viewer import write_trial_view
        with tempfile.TemporaryDirectory(prefix="vibrissa-view-") as tmp:
            tmp = pathlib.Path(tmp)
            self.trial.write(str(tmp / "trial.h5"))
            self.write(tmp / "results")
            return write_trial_view(tmp / "trial.h5", tmp / "results", path)

    def figures(self, directory, window=None, whisk=None, dpi=None, all_figures=False):
        """Draws the figures of ``vibrissa trial`` (figures/trial_figures.py, matplotlib and h5py) into
        `directory`; returns the PNG paths. ``window=(start_s, end_s)`` or ``whisk=N`` (contact period, from
        1) choose the span of the time series, ``dpi`` the resolution and ``all_figures`` adds the world-frame
        and shape/height figures, as ``vibrissa trial --window``, ``--whisk``, ``--figure-dpi`` and
        ``--all-figures`` do. Raises RuntimeError with the script's output if it fails."""
        directory = pathlib.Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        flags = []
        if window is not None:
            start, end = (float(v) for v in window)
            flags += ["--window", f"{start!r},{end!r}"]
        if whisk is not None:
            flags += ["--whisk", str(int(whisk))]
        if dpi is not None:
            flags += ["--dpi", str(int(dpi))]
        if all_figures:
            flags.append("--all")
        with tempfile.TemporaryDirectory() as tmp:
            self.write(tmp)
            done = subprocess.run([sys.executable, str(_figure_script("trial_figures.py")),
                                   os.path.join(tmp, "frames.h5"), os.path.join(tmp, "summary.json"),
                                   str(directory), *flags], capture_output=True, text=True,
                                  env=dict(os.environ, MPLBACKEND="Agg"))
        if done.returncode != 0:
            raise RuntimeError(f"trial_figures.py failed (exit {done.returncode}):\n{done.stderr}")
        return sorted(directory.glob("*.png"))


def analyze_trial(trial, mu=None, cutoff=85.0, filter_order=2, no_filter=False, *, mu_eq7=None,
                  no_roll_fit=False, rest_shape_per_contact=False, progress=None):
    """Analyses a trial (a :class:`Trial` or a path) exactly as ``vibrissa trial`` does.

    Options are its flags: ``mu`` (also run frictional edge mode), ``mu_eq7``, ``cutoff`` [Hz],
    ``filter_order`` (2 or 4), ``no_filter``, ``no_roll_fit``, ``rest_shape_per_contact``.
    ``progress(done, total)`` counts solved contact frames. Returns a :class:`TrialResult`.
    """
    if isinstance(trial, (str, os.PathLike)):
        trial = read_trial(os.fspath(trial))  # warns about likely unit slips
    elif isinstance(trial, Trial):
        for message in trial.warnings:  # likely unit slips, as `vibrissa trial` prints them
            warnings.warn(message, stacklevel=2)
    else:
        raise TypeError(f"trial must be a vibrissa.Trial or a path, got {type(trial).__name__}")
    outputs = _vibrissa._analyze_trial(trial, mu, mu_eq7, float(cutoff), int(filter_order), bool(no_filter),
                                       bool(no_roll_fit), bool(rest_shape_per_contact), progress)
    return TrialResult(outputs, trial)


def analyze_trials(trials, **options):
    """Analyses several trials as ``vibrissa trial TRIAL...`` does: `trials` a dict name -> trial (a :class:`Trial`, a
    path, or a ``(trial, report)`` pair as ``reconstruct(..., whiskers=...)`` returns them) or a list of paths (named
    by their paths); `options` those of :func:`analyze_trial`. Returns ``(results, table)``: a dict name ->
    :class:`TrialResult` and a ``pandas.DataFrame`` indexed by name with the columns of ``vibrissa trial``'s summary
    table (frames, contact_periods, contact_frames, median_mu, mu_frames; median_mu NaN where no frame gave one)."""
    import pandas as pd
    if not isinstance(trials, dict):
        trials = {os.fspath(path): path for path in trials}
    if not trials:
        raise ValueError("trials: give at least one trial")
    results, rows = {}, []
    for name, trial in trials.items():
        if isinstance(trial, tuple):
            trial = trial[0]
        result = analyze_trial(trial, **options)
        results[name] = result
        friction = result.summary.get("friction") or {}
        used = int(friction.get("frames_used", 0) or 0)
        rows.append({"name": name, "frames": len(result.time),
                     "contact_periods": int(result.summary["contact_periods"]),
                     "contact_frames": int(result.summary["contact_frames"]),
                     "median_mu": float(friction["median"]) if used and friction.get("median") is not None
                     else float("nan"),
                     "mu_frames": used})
    return results, pd.DataFrame(rows).set_index("name")


def default_array_config():
    """The built-in configuration of ``vibrissa array`` (= ``--print-default-config``) as a dict."""
    return json.loads(_vibrissa.default_array_config_json())


class ArrayResult(_NamedArrays):
    """The outputs of ``vibrissa array``: the datasets of ``array.h5`` by name as NumPy arrays
    (``result.FT`` has shape (pitches, whiskers, frames); the render group as ``result["render/rest"]``),
    ``summary`` (the dict of ``summary.json``), ``config`` (the configuration used), :meth:`to_xarray` and
    :meth:`write`."""

    def __init__(self, run):
        self._run = run
        self.datasets = dict(run.datasets())
        self._arrays = self.datasets
        self.summary = json.loads(run.summary_json())
        self.config = json.loads(run.config_json())
        self.wall_seconds = run.wall_seconds

    _what = "dataset"

    def __repr__(self):
        p, w, f = self.datasets["state"].shape
        touching = int((self.datasets["state"] == 1).any(axis=2).sum())
        return f"ArrayResult(pitches={p}, whiskers={w}, frames={f}, touching={touching})"

    def to_xarray(self, group=""):
        """The results as an ``xarray.Dataset``: dimensions ``pitch``, ``whisker``, ``time``, ``component``
        with their coordinates (head pitch [rad], whisker names, time [s], "x"/"y"/"z"), every variable with
        ``units`` and ``long_name`` (code variables also ``codes``). ``group="render"`` gives the rendered
        shapes (dimensions ``frame``, ``whisker``, ``node``, ``component``; ``edge``, ``end``). Identical to
        ``xarray.open_dataset`` of the ``array.h5`` that :meth:`write` writes (needs python3-xarray)."""
        return to_dataset(self._run.labelled(), group)

    def write(self, directory, csv=False):
        """Writes config.json, array.h5, pitch_summary.csv, summary.json (and array.csv with csv=True) into
        `directory`, as ``vibrissa array --out DIR --no-figures`` does. Returns the directory."""
        directory = pathlib.Path(directory)
        self._run.write(str(directory), bool(csv))
        return directory

    def view(self, path="array_view.html"):
        """Writes the interactive 3D viewer of this result, one self-contained HTML file (docs/viewer.md; as
        ``vibrissa view``), and returns its path."""
        from .viewer import view
        return view(self, path)


def simulate_array(config=None, progress=None, threads=None, dynamics=False):
    """Simulates a whisker array exactly as ``vibrissa array`` does (``dynamics=True``: as ``vibrissa array
    --dynamics``, every whisker through the dynamics integrator, in air; the config's ``"dynamics"`` object sets
    density, damping and air drag; docs/dynamics.md).

    `config` is a dict (same schema as the JSON file, docs/array.md), a path to a JSON file, or None for the
    built-in default. ``threads`` overrides the config's ``threads`` (like ``--threads``).
    ``progress(done, total)`` counts whisker-frames. Returns an :class:`ArrayResult`.
    """
    if config is None:
        text, path = None, None
    elif isinstance(config, (str, os.PathLike)):
        text, path = None, os.fspath(config)
    elif isinstance(config, dict):
        text, path = json.dumps(config, default=_json_default), None
    else:
        raise TypeError(f"config must be a dict, a path or None, got {type(config).__name__}")
    return ArrayResult(_vibrissa._simulate_array(text, path, threads, progress, bool(dynamics)))


def _json_default(value):
    """NumPy arrays and scalars inside a config dict."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"config value of type {type(value).__name__} is not JSON serialisable")
