"""Reconstruction of a trial from two or more tracked, named camera views (docs/reconstruction.md,
docs/python.md).

:func:`reconstruct` runs the library call of ``vibrissa reconstruct`` (same files, same options, same
numbers) with progress and Ctrl-C, and returns the :class:`~vibrissa.Trial` with the report as a dict.
"""
import json
import os
import tempfile
import warnings

import numpy as np

from . import _vibrissa
from .batch import _warn_deprecated
from ._track_inputs import existing_path, track_file


def _renamed(new_value, old_value, new, old, default, note):
    """The value of ``new=`` given under its deprecated name ``old=`` (DeprecationWarning); TypeError for both."""
    if old_value is None:
        return default if new_value is None else new_value
    if new_value is not None:
        raise TypeError(f"reconstruct() got both {new} and its deprecated name {old}")
    _warn_deprecated(f"reconstruct({old}=...)", f"{new}= ({note})")
    return old_value


def reconstruct(top=None, front=None, calibration=None, *, views=None, cameras=None, measurements=None,
                peg_m=None, edge_m=None, top_camera="top", front_camera="front", bodyparts=(), individual="",
                whisker_id=0, top_measurements="", front_measurements="", min_likelihood=0.5,
                max_reprojection_px=2.0, contact_threshold_m=None, base_jump_m=None, fit_segments=6, nodes=40,
                frame_rate=1000.0, front_frame_offset=0, frame_offsets=None, min_yield=0.5, max_unpaired=0.05,
                max_epipolar_px=2.0, calibration_unit="", whiskers=None, source=None, progress=None, peg=None,
                edge=None, contact_threshold=None, base_jump=None):
    """Reconstructs a trial as ``vibrissa reconstruct`` does. SI units (the CLI's ``--peg-mm``, ``--edge-mm``,
    ``--contact-threshold-um`` and ``--base-jump-um`` are in mm / µm; here metres, as the names say).

    The views: ``views={"top": ..., "front": ..., "side": ...}`` (two or more, named as their cameras in the
    calibration; ``cameras={"side": "cam_2"}`` maps a view to another camera name), or ``top`` and ``front``
    (shorthands for the views named top and front; ``top_camera``/``front_camera`` name their cameras). The
    first view is the reference of the matching. Each view is a track file (plain or DeepLabCut CSV or ``.h5``,
    Janelia ``.whiskers`` with its ``measurements={"top": path}`` or ``top_measurements``), a pandas DataFrame
    in DeepLabCut's layout (columns scorer, [individuals,] bodyparts, coords; an integer index is the frame), or
    a NumPy array (frames, points, 2 or 3) of x_px, y_px [, likelihood] with the points from the base (NaN: not
    tracked). A missing file raises FileNotFoundError. ``calibration``: cameras JSON, anipose TOML (with
    ``calibration_unit``). ``peg_m``: vertical peg(s) through (3,) or (k, 3) points [m]; ``edge_m``: (6,) or
    (k, 6) rows of point [m] and direction.

    The checks of the CLI, with its defaults and errors: ``front_frame_offset`` (``--front-frame-offset``) and
    ``frame_offsets={"side": 3}`` (``--frame-offset side=3``), ``min_yield``, ``max_unpaired``,
    ``max_epipolar_px``; inconsistent inputs raise RuntimeError naming each problem and its likely cause. Deprecated names:
    ``peg=``, ``edge=``, ``contact_threshold=``, ``base_jump=`` (same metres as ``peg_m=``, ``edge_m=``,
    ``contact_threshold_m=``, ``base_jump_m=``). ``progress(done, total)`` counts frames.

    Several whiskers in one video: ``whiskers={"C2": ["c2_0", "c2_1", ...], "C1": [...]}`` (DeepLabCut keypoints
    base to tip, the same names in every view) or ``whiskers={"C2": 3, "C1": 5}`` (Janelia labels, the
    measurements' ``state``); then the result is a dict name -> ``(trial, report)``, in the given order, and a
    whisker that fails raises RuntimeError naming it (the CLI writes the others).

    Returns ``(trial, report)``: a :class:`~vibrissa.Trial` (flagged frames have ``reconstructed`` 0 and NaN
    values) and the ``--report`` JSON as a dict. Likely unit slips of the result (``trial.warnings``: a peg
    out of the whisker's reach, e.g. millimetres given as metres) are raised with ``warnings.warn``.
    """
    peg_m = _renamed(peg_m, peg, "peg_m", "peg", None, "metres; the CLI's --peg-mm is in mm")
    edge_m = _renamed(edge_m, edge, "edge_m", "edge", None, "metres; the CLI's --edge-mm is in mm")
    contact_threshold_m = _renamed(contact_threshold_m, contact_threshold, "contact_threshold_m", "contact_threshold",
                                   300e-6, "metres; the CLI's --contact-threshold-um is in um")
    base_jump_m = _renamed(base_jump_m, base_jump, "base_jump_m", "base_jump", 1e-3,
                           "metres; the CLI's --base-jump-um is in um")
    if calibration is None:
        raise TypeError("reconstruct() needs calibration=")
    if isinstance(bodyparts, str):
        bodyparts = [b for b in bodyparts.split(",") if b]
    named = []  # (name, track input, camera name)
    if top is not None:
        named.append(("top", top, str(top_camera)))
    if front is not None:
        named.append(("front", front, str(front_camera)))
    cameras = dict(cameras or {})
    for name, value in dict(views or {}).items():
        if any(n == str(name) for n, _, _ in named):
            raise ValueError(f"views: the view '{name}' is given twice (as {name}= and in views=)")
        named.append((str(name), value, str(cameras.pop(name, name))))
    if cameras:
        raise ValueError(f"cameras: no view named {sorted(cameras)} (views: {[n for n, _, _ in named]})")
    if len(named) < 2:
        raise ValueError(f"views: at least two camera views are needed (views= or top= and front=), got {len(named)}")
    given = {n: (m, f"measurements['{n}']") for n, m in dict(measurements or {}).items()}
    for n, m in (("top", top_measurements), ("front", front_measurements)):
        if os.fspath(m) and n not in given:
            given[n] = (m, f"{n}_measurements")
    unknown = set(given) - {n for n, _, _ in named}
    if unknown:
        raise ValueError(f"measurements: no view named {sorted(unknown)}")
    given = {n: existing_path(m, label) for n, (m, label) in given.items() if os.fspath(m)}
    offsets = {str(k): int(v) for k, v in dict(frame_offsets or {}).items()}
    selections = []
    for name, spec in dict(whiskers or {}).items():
        if isinstance(spec, (int, np.integer)) and not isinstance(spec, bool):
            selections.append((str(name), [], int(spec)))
        elif isinstance(spec, str):
            selections.append((str(name), [b for b in spec.split(",") if b], -1))
        else:
            selections.append((str(name), [str(b) for b in spec], -1))
        if selections[-1][2] < 0 and len(selections[-1][1]) < 2:
            raise ValueError(f"whiskers['{name}']: {spec!r}: a whisker needs at least two keypoints, base to tip, "
                             "or a Janelia label (int >= 0)")
    with tempfile.TemporaryDirectory(prefix="vibrissa-tracks-") as folder:
        files = [(name, *track_file(value, name, folder), camera) for name, value, camera in named]
        result = _vibrissa._reconstruct(
            [[name, path, camera, given.get(name, "")] for name, path, _, camera in files],
            existing_path(calibration, "calibration"), peg_m, edge_m, list(bodyparts), str(individual),
            int(whisker_id), float(min_likelihood), float(max_reprojection_px), float(contact_threshold_m),
            float(base_jump_m), int(fit_segments), int(nodes), float(frame_rate), int(front_frame_offset), offsets,
            float(min_yield), float(max_unpaired), float(max_epipolar_px), str(calibration_unit), selections,
            files[0][2] if source is None else str(source), progress)
    if not selections:
        return _finish(result[0], json.loads(result[1]))
    failed = [f"whisker '{name}': {error}" for name, t, _, error in result if t is None]
    if failed:
        raise RuntimeError(f"{len(failed)} of {len(result)} whiskers failed:\n  - " + "\n  - ".join(failed))
    return {name: _finish(t, json.loads(r)) for name, t, r, _ in result}


def _finish(trial, report):
    """The report with the trial's likely unit slips, each also raised with warnings.warn."""
    report.setdefault("warnings", [])
    for message in trial.warnings:  # likely unit slips: a peg out of reach, a whisker of implausible size
        warnings.warn(message, stacklevel=3)
        report["warnings"].append(message)  # as the CLI's --report
    return trial, report
