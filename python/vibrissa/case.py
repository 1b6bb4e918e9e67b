"""The JSON case contract of ``vibrissa solve`` (docs/formats.md), from Python.

Everything here goes through the CLI's own C++ reader, solver and writer, so a case solved in Python gives
the CLI's result bit for bit.
"""

from __future__ import annotations

import json
import os
import warnings
from typing import Any, Mapping, Optional, Union

import numpy as np

from . import _vibrissa


def _jsonable(obj: Any) -> Any:
    """NumPy arrays and scalars to lists and floats, recursively (json.dumps cannot take them)."""
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, Mapping):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, (_vibrissa.Scheme, _vibrissa.BaseJoint)):
        return obj.name
    return obj


def case_from_dict(case: Mapping[str, Any]) -> _vibrissa.Case:
    """A :class:`Case` from a dict with the JSON case's fields (``whisker``, ``load``, optional ``options``);
    NumPy arrays are accepted wherever the JSON has arrays. ValueError names the offending field."""
    return _vibrissa.Case.from_json(json.dumps(_jsonable(case)))


def load_case(source: Union[str, os.PathLike, Mapping[str, Any]]) -> _vibrissa.Case:
    """A :class:`Case` from a case file path, a JSON string (starting with ``{``) or a dict."""
    if isinstance(source, Mapping):
        return case_from_dict(source)
    text = os.fspath(source)
    if text.lstrip().startswith("{"):
        return _vibrissa.Case.from_json(text)
    return _vibrissa.Case.from_file(text)


def make_whisker(*, points: Any = None, length: Optional[float] = None, curvature: Optional[float] = None,
                 cubic: Any = None, pose: Union[None, _vibrissa.Pose, Mapping[str, Any]] = None,
                 **properties: Any) -> _vibrissa.Whisker:
    """A :class:`Whisker` from the fields of a case's ``"whisker"`` object, as keyword arguments.

    Give ``points`` ((M, 3) world [m], base first) or ``length`` [m] with ``curvature`` (y = a x^2, a [1/m])
    or ``cubic`` = (A, B) (y = A x^3 + B x^2). ``pose`` is a :class:`Pose` or a dict with ``base`` [m],
    ``theta``, ``phi``, ``zeta`` [rad]. Other keywords: ``links``, ``base_radius`` [m], ``taper_ratio``,
    ``radii`` [m], ``youngs_modulus`` [Pa] (number or per-node list), ``poisson_ratio``, ``base``
    ('elastic' | 'rigid'), ``base_stiffness`` [N·m/rad], ``scheme`` ('second_order' | 'paper').

    Example: ``make_whisker(length=0.03, curvature=20.0, base_radius=80e-6, pose={"theta": 0.2})``."""
    fields: dict = dict(properties)
    if points is not None:
        fields["points"] = points
    if length is not None:
        fields["length"] = length
    if curvature is not None:
        fields["curvature"] = curvature
    if cubic is not None:
        fields["cubic"] = cubic
    if pose is not None:
        if isinstance(pose, _vibrissa.Pose):
            pose = {"base": pose.base, "theta": pose.theta, "phi": pose.phi, "zeta": pose.zeta}
        fields["pose"] = pose
    return _vibrissa.whisker_from_json(json.dumps(_jsonable(fields)))


def solve_case_file(case_path: Union[str, os.PathLike], result_path: Union[str, os.PathLike, None] = None
                    ) -> _vibrissa.Solution:
    """``vibrissa solve CASE [-o RESULT]`` from Python: reads, solves, and (if ``result_path``) writes the
    result file exactly as the CLI does. Returns the :class:`Solution`."""
    case = _vibrissa.Case.from_file(os.fspath(case_path))
    for message in case.warnings:  # likely unit slips, as the CLI prints them
        warnings.warn(message, stacklevel=2)
    solution = case.solve()
    if result_path is not None:
        _vibrissa.write_case_result(os.fspath(result_path), case, solution)
    return solution
