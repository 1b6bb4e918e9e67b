"""Reconstruction of a trial from two tracked camera views (docs/reconstruction.md, docs/python.md).

:func:`reconstruct` runs the library call of ``vibrissa reconstruct`` (same files, same options, same
numbers) with progress and Ctrl-C, and returns the :class:`~vibrissa.Trial` with the report as a dict.
"""
import json
import os
import tempfile
import warnings

from . import _vibrissa
from .batch import _warn_deprecated
from ._track_inputs import existing_path, track_file


def reconstruct(top, front, calibration, *, peg_m=None, edge_m=None, top_camera="top", front_camera="front",
                bodyparts=(), individual="", whisker_id=0, top_measurements="", front_measurements="",
                min_likelihood=0.5, max_reprojection_px=2.0, contact_threshold=300e-6, base_jump=1e-3,
                fit_segments=6, nodes=40, frame_rate=1000.0, source=None, progress=None, peg=None, edge=None):
    """Reconstructs a trial as ``vibrissa reconstruct`` does. SI units (the CLI's ``--peg-mm``, ``--edge-mm``,
    ``--contact-threshold-um`` and ``--base-jump-um`` are in mm / µm; here metres).

    ``top``, ``front``: track files (plain or DeepLabCut CSV or ``.h5``, Janelia ``.whiskers`` with
    ``*_measurements``), pandas DataFrames in DeepLabCut's layout (columns scorer, [individuals,] bodyparts,
    coords; an integer index is the frame), or NumPy arrays (frames, points, 2 or 3) of x_px, y_px
    [, likelihood] with the points from the base (NaN: not tracked). A missing file raises FileNotFoundError.
    ``calibration``: the cameras JSON; ``peg_m``: vertical peg(s) through (3,) or (k, 3) points [m] (the CLI's
    ``--peg-mm`` in mm); ``edge_m``: (6,) or (k, 6) rows of point [m] and direction. ``peg=`` and ``edge=``
    are deprecated names of ``peg_m=`` and ``edge_m=`` (same metres). ``progress(done, total)`` counts frames.
    Returns ``(trial, report)``: a :class:`~vibrissa.Trial` (flagged frames have ``reconstructed`` 0 and NaN
    values) and the ``--report`` JSON as a dict. Likely unit slips of the result (``trial.warnings``: a peg
    out of the whisker's reach, e.g. millimetres given as metres) are raised with ``warnings.warn``.
    """
    if peg is not None:
        if peg_m is not None:
            raise TypeError("reconstruct() got both peg_m and its deprecated name peg")
        _warn_deprecated("reconstruct(peg=...)", "peg_m= (metres; the CLI's --peg-mm is in mm)")
        peg_m = peg
    if edge is not None:
        if edge_m is not None:
            raise TypeError("reconstruct() got both edge_m and its deprecated name edge")
        _warn_deprecated("reconstruct(edge=...)", "edge_m= (metres; the CLI's --edge-mm is in mm)")
        edge_m = edge
    if isinstance(bodyparts, str):
        bodyparts = [b for b in bodyparts.split(",") if b]
    measurements = [existing_path(m, n) if os.fspath(m) else ""
                    for m, n in ((top_measurements, "top_measurements"), (front_measurements, "front_measurements"))]
    with tempfile.TemporaryDirectory(prefix="vibrissa-tracks-") as folder:
        (top_path, top_label), (front_path, _) = (track_file(top, "top", folder), track_file(front, "front", folder))
        trial, report = _vibrissa._reconstruct(
            top_path, front_path, existing_path(calibration, "calibration"), peg_m, edge_m, str(top_camera),
            str(front_camera), list(bodyparts), str(individual), int(whisker_id), measurements[0], measurements[1],
            float(min_likelihood), float(max_reprojection_px), float(contact_threshold), float(base_jump),
            int(fit_segments), int(nodes), float(frame_rate), top_label if source is None else str(source), progress)
    report = json.loads(report)
    report.setdefault("warnings", [])
    for message in trial.warnings:  # likely unit slips: a peg out of reach, a whisker of implausible size
        warnings.warn(message, stacklevel=2)
        report["warnings"].append(message)  # as the CLI's --report
    return trial, report
