"""Reconstruction of a trial from two tracked camera views (docs/reconstruction.md, docs/python.md).

:func:`reconstruct` runs the library call of ``vibrissa reconstruct`` (same files, same options, same
numbers) with progress and Ctrl-C, and returns the :class:`~vibrissa.Trial` with the report as a dict.
"""
import json
import os

from . import _vibrissa


def reconstruct(top, front, calibration, *, peg=None, edge=None, top_camera="top", front_camera="front",
                bodyparts=(), individual="", whisker_id=0, top_measurements="", front_measurements="",
                min_likelihood=0.5, max_reprojection_px=2.0, contact_threshold=300e-6, base_jump=1e-3,
                fit_segments=6, nodes=40, frame_rate=1000.0, source=None, progress=None):
    """Reconstructs a trial as ``vibrissa reconstruct`` does. SI units (the CLI's ``--peg-mm``, ``--edge-mm``,
    ``--contact-threshold-um`` and ``--base-jump-um`` are in mm / µm; here metres).

    ``top``, ``front``: track files (plain or DeepLabCut CSV, Janelia ``.whiskers`` with ``*_measurements``);
    ``calibration``: the cameras JSON; ``peg``: vertical peg(s) through (3,) or (k, 3) points [m]; ``edge``:
    (6,) or (k, 6) rows of point [m] and direction. ``progress(done, total)`` counts frames.
    Returns ``(trial, report)``: a :class:`~vibrissa.Trial` (flagged frames have ``reconstructed`` 0 and NaN
    values) and the ``--report`` JSON as a dict.
    """
    paths = [os.fspath(p) for p in (top, front, calibration)]
    if isinstance(bodyparts, str):
        bodyparts = [b for b in bodyparts.split(",") if b]
    trial, report = _vibrissa._reconstruct(
        paths[0], paths[1], paths[2], peg, edge, str(top_camera), str(front_camera), list(bodyparts),
        str(individual), int(whisker_id), os.fspath(top_measurements), os.fspath(front_measurements),
        float(min_likelihood), float(max_reprojection_px), float(contact_threshold), float(base_jump),
        int(fit_segments), int(nodes), float(frame_rate), paths[0] if source is None else str(source), progress)
    return trial, json.loads(report)
