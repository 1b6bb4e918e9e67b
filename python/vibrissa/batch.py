"""Batch solves: many frames and/or many whiskers per call, computed in C++ with the GIL released.

Layout of the inputs (every array is converted to float64; lists, float32 and non-contiguous views are fine):

* one series of F frames: per-frame vectors have shape ``(F, 3)``, per-frame scalars ``(F,)``;
* S independent series: ``(S, F, 3)`` and ``(S, F)``, or pass ``whisker`` as a sequence of S whiskers;
* an input without a series axis is shared by every series; a ``(3,)`` vector or a plain number is shared by
  every frame.

Results are stacked arrays of shape ``(F, ...)``, or ``(S, F, ...)`` when any input has a series axis.

With ``warm_start=True`` (the default for the contact modes) frame ``f`` starts from frame ``f-1``'s solution
when that one converged, so a series runs in order on one core and series run in parallel; with
``warm_start=False`` every frame is independent and frames run in parallel. The number of threads never
changes the results. ``threads=None`` uses OpenMP's default (``OMP_NUM_THREADS`` or all cores).

A series with warm starts is one :class:`ContactTracker` run in tracked mode (docs/conventions.md, "Contact
tracking"): warm starts, hints and the friction start point follow the same policy as trials and arrays.
Every batch runs with the GIL released; ``progress(done, total)`` (frames) is called from the calling thread
about every 50 ms, and Ctrl-C raises ``KeyboardInterrupt`` within 0.5 s.
"""

from __future__ import annotations

import warnings
from typing import Any, Optional, Sequence, Union

import numpy as np

from . import _vibrissa
from ._vibrissa import Status

#: Status code of a batch frame whose input was refused (one past the :class:`Status` values): its numbers are
#: NaN and :attr:`BatchResult.errors` holds its message.
INVALID_INPUT = len(Status.__members__)

#: Status names indexed by the integer codes in :attr:`BatchResult.status` (the last is ``"invalid_input"``).
STATUS_NAMES = tuple(s.label for s in sorted(Status.__members__.values(), key=int)) + ("invalid_input",)

#: What a batch does with a frame whose input is refused: "record" (the default) solves every other frame and
#: lists it in :attr:`BatchResult.errors` (status ``invalid_input``, NaN numbers, one UserWarning per batch),
#: as ``vibrissa solve --jsonl`` does; "raise" raises the first one's error (ValueError naming the series
#: and frame), the behaviour before issue 23.
ON_ERROR = ("record", "raise")

#: The release that removes the deprecated names (docs/python.md, "Deprecated names").
DEPRECATED_NAMES_REMOVED_IN = "0.2.0"

_UNSET = object()


def _warn_deprecated(old: str, new: str) -> None:
    warnings.warn(f"{old} is deprecated and will be removed in vibrissa {DEPRECATED_NAMES_REMOVED_IN}; use {new}",
                  DeprecationWarning, stacklevel=3)


def _renamed_args(function: str, given: dict, legacy: dict, renames: dict) -> dict:
    """Moves deprecated keyword arguments (``renames``: old name -> new name) from ``legacy`` into ``given``
    with a DeprecationWarning; TypeError for an unknown keyword or a value passed under both names."""
    for old, value in legacy.items():
        new = renames.get(old)
        if new is None:
            raise TypeError(f"{function}() got an unexpected keyword argument '{old}'")
        if given.get(new, _UNSET) is not _UNSET:
            raise TypeError(f"{function}() got '{old}' and its new name '{new}'; pass only '{new}'")
        _warn_deprecated(f"{function}({old}=...)", f"{new}=")
        given[new] = value
    return {k: (None if v is _UNSET else v) for k, v in given.items()}


class BatchWhiskerFrame:
    """Stacked base signals in the whisker frame (spec §2.4): ``force`` (..., 3) [N], ``moment`` (..., 3)
    [N·m], ``Fx`` = ``force[..., 0]`` [N], ``Mx`` = ``moment[..., 0]`` [N·m], ``FT``, ``MB`` [N, N·m], ``FD``,
    ``MD`` [rad]."""

    __slots__ = ("force", "moment", "Fx", "Mx", "FT", "MB", "FD", "MD")

    def __init__(self, d: dict):
        for k in self.__slots__:
            setattr(self, k, d[k])

    def __repr__(self) -> str:
        return f"BatchWhiskerFrame(frames={self.FT.shape})"


class BatchResult:
    """Stacked results of a batch solve; the fields are named as in :class:`Solution` and the JSON result.

    Per-frame arrays have the batch's leading shape ``L`` = ``(F,)`` or ``(S, F)``:

    * ``status`` (L) int32 codes of :class:`Status` (``STATUS_NAMES[code]`` is the name), ``converged`` (L) bool
    * ``force_magnitude`` [N], ``arc_length`` [m], ``angle`` [rad], ``residual`` [m], ``iterations`` (L)
    * ``contact_point_W`` [m], ``force_W`` [N], ``moment_W`` [N·m]: (L, 3), world frame
    * ``whisker_frame``: ``force``, ``moment`` (L, 3) and ``Fx``, ``Mx``, ``FT``, ``MB``, ``FD``, ``MD`` (L)
    * ``normal_force``, ``edge_force`` [N] (L): NaN where the mode does not define them
    * ``state`` (L, 4): ``(force_x, force_y, force_z, arc_length)``, the warm-start unknowns
    * ``shape_W`` (L, N+1, 3) world [m] when the batch was called with ``shapes=True``, else None
    * ``errors``: one ``(series, frame, message)`` per frame whose input was refused (status
      ``invalid_input``, its numbers NaN); empty when every frame was solved

    ``contact_point``, ``force``, ``moment`` and ``shape`` are deprecated aliases of the ``_W`` names (they
    emit a DeprecationWarning and are removed in 0.2.0).
    """

    __slots__ = ("status", "force_magnitude", "arc_length", "angle", "contact_point_W", "force_W", "moment_W",
                 "whisker_frame", "normal_force", "edge_force", "residual", "iterations", "state", "shape_W",
                 "errors")

    def __init__(self, d: dict):
        for k in self.__slots__:
            v = d.get(k, []) if k == "errors" else d[k]
            setattr(self, k, BatchWhiskerFrame(v) if k == "whisker_frame" else v)

    @property
    def contact_point(self) -> np.ndarray:
        """Deprecated alias of ``contact_point_W`` (removed in 0.2.0)."""
        _warn_deprecated("BatchResult.contact_point", "contact_point_W")
        return self.contact_point_W

    @property
    def force(self) -> np.ndarray:
        """Deprecated alias of ``force_W`` (removed in 0.2.0)."""
        _warn_deprecated("BatchResult.force", "force_W")
        return self.force_W

    @property
    def moment(self) -> np.ndarray:
        """Deprecated alias of ``moment_W`` (removed in 0.2.0)."""
        _warn_deprecated("BatchResult.moment", "moment_W")
        return self.moment_W

    @property
    def shape(self) -> Optional[np.ndarray]:
        """Deprecated alias of ``shape_W`` (removed in 0.2.0)."""
        _warn_deprecated("BatchResult.shape", "shape_W")
        return self.shape_W

    @property
    def converged(self) -> np.ndarray:
        """Boolean array: status == Status.converged."""
        return self.status == int(Status.converged)

    @property
    def status_names(self) -> np.ndarray:
        """The status of every frame as its JSON name (array of str)."""
        return np.asarray(STATUS_NAMES, dtype=object)[self.status]

    @property
    def frames_shape(self) -> tuple:
        """The leading shape ``(F,)`` or ``(S, F)``."""
        return self.status.shape

    def __len__(self) -> int:
        return len(self.status)

    def to_dict(self) -> dict:
        """Plain dict of arrays (``whisker_frame`` as a nested dict)."""
        out = {k: getattr(self, k) for k in self.__slots__}
        wf = self.whisker_frame
        out["whisker_frame"] = {k: getattr(wf, k) for k in BatchWhiskerFrame.__slots__}
        return out

    def __repr__(self) -> str:
        n = int(self.converged.sum())
        return f"BatchResult(frames={self.frames_shape}, converged={n}/{self.status.size})"


WhiskerArg = Union["_vibrissa.Whisker", Sequence["_vibrissa.Whisker"]]


def _where(series: int, frame: int) -> str:
    return f"series {series}, frame {frame}"


def _finish(d: dict, on_error: str, function: str) -> BatchResult:
    """The batch's result, or (on_error="raise") the first refused frame's error."""
    raw, kinds = d.pop("errors"), d.pop("error_kinds")
    errors = [(int(s), int(f), str(m)) for s, f, m in raw]
    if errors and on_error == "raise":
        s, f, message = errors[0]
        raise (ValueError if kinds[0] == "ValueError" else RuntimeError)(
            f"{message} ({_where(s, f)})")
    d["errors"] = errors
    if errors:
        s, f, message = errors[0]
        warnings.warn(f"{function}: {len(errors)} of {np.size(d['status'])} frames refused (status "
                      f"invalid_input, see BatchResult.errors); the first, {_where(s, f)}: {message}",
                      UserWarning, stacklevel=3)
    return BatchResult(d)


def _check_on_error(on_error: str) -> str:
    if on_error not in ON_ERROR:
        raise ValueError(f"on_error must be one of {list(ON_ERROR)}, got {on_error!r}")
    return on_error


def solve_force_batch(whisker: WhiskerArg, force: Any, arc_length: Any, angle: Any = None, *,
                      pose_base: Any = None, pose_angles: Any = None,
                      options: Optional[_vibrissa.SolveOptions] = None, shapes: bool = False,
                      threads: Optional[int] = None, progress: Any = None, on_error: str = "record") -> BatchResult:
    """Force mode for many frames (see :func:`solve_force`): ``force`` [N], ``arc_length`` [m] and ``angle``
    [rad] are numbers, (F,) or (S, F). Frames are independent and run in parallel.

    ``pose_base`` (..., 3) [m] and ``pose_angles`` (..., 3) = (theta, phi, zeta) [rad] re-place the whisker
    per frame. ``shapes=True`` also returns the deflected shapes."""
    _check_on_error(on_error)
    return _finish(_vibrissa.solve_force_batch(
        whisker, force, arc_length, angle, pose_base=pose_base, pose_angles=pose_angles, options=options,
        shapes=shapes, threads=threads, progress=progress), on_error, "solve_force_batch")


def solve_point_batch(whisker: WhiskerArg, points_W: Any = _UNSET, *, arc_length_hint: Any = None,
                      edge_direction_W: Any = _UNSET, pose_base: Any = None, pose_angles: Any = None,
                      options: Optional[_vibrissa.SolveOptions] = None, warm_start: bool = True,
                      shapes: bool = False, threads: Optional[int] = None, progress: Any = None, on_error: str = "record",
                      **deprecated: Any) -> BatchResult:
    """Contact-point mode for many frames (see :func:`solve_point`): ``points_W`` (F, 3) or (S, F, 3) world
    [m]. ``arc_length_hint`` [m] (number, (F,) or (S, F)); ``edge_direction_W`` ((3,), (F, 3) ...) splits the
    force into normal_force / edge_force. With ``warm_start`` each frame starts from the previous one.
    The keywords ``points`` and ``edge_direction`` are deprecated aliases (removed in 0.2.0)."""
    a = _renamed_args("solve_point_batch", {"points_W": points_W, "edge_direction_W": edge_direction_W},
                      deprecated, {"points": "points_W", "edge_direction": "edge_direction_W"})
    _check_on_error(on_error)
    return _finish(_vibrissa.solve_point_batch(
        whisker, a["points_W"], arc_length_hint=arc_length_hint, edge_direction_W=a["edge_direction_W"],
        pose_base=pose_base, pose_angles=pose_angles, options=options, warm_start=warm_start, shapes=shapes,
        threads=threads, progress=progress), on_error, "solve_point_batch")


def solve_edge_batch(whisker: WhiskerArg, edge_points_W: Any = _UNSET, edge_directions_W: Any = _UNSET, *,
                     arc_length_hint: Any = None, approach_W: Any = _UNSET, pose_base: Any = None,
                     pose_angles: Any = None, options: Optional[_vibrissa.SolveOptions] = None,
                     warm_start: bool = True, shapes: bool = False, threads: Optional[int] = None,
                     progress: Any = None, on_error: str = "record", **deprecated: Any) -> BatchResult:
    """Edge mode (frictionless) for many frames (see :func:`solve_edge`): the edge of frame f passes through
    ``edge_points_W[f]`` [m] along ``edge_directions_W[f]`` (default world +z; (3,) for a fixed direction).
    ``approach_W`` gives the direction the whisker moves into the edge (else no_contact). The keywords
    ``edge_points``, ``edge_directions`` and ``approach`` are deprecated aliases (removed in 0.2.0)."""
    a = _renamed_args("solve_edge_batch", {"edge_points_W": edge_points_W, "edge_directions_W": edge_directions_W,
                                           "approach_W": approach_W},
                      deprecated, {"edge_points": "edge_points_W", "edge_directions": "edge_directions_W",
                                   "approach": "approach_W"})
    _check_on_error(on_error)
    return _finish(_vibrissa.solve_edge_batch(
        whisker, a["edge_points_W"], a["edge_directions_W"], arc_length_hint=arc_length_hint,
        approach_W=a["approach_W"], pose_base=pose_base, pose_angles=pose_angles, options=options,
        warm_start=warm_start, shapes=shapes, threads=threads, progress=progress), on_error, "solve_edge_batch")


def solve_frictional_edge_batch(whisker: WhiskerArg, edge_points_W: Any = _UNSET, edge_directions_W: Any = _UNSET,
                                mu: float = 0.0, *, initial_contact_W: Any = _UNSET, approach_W: Any = _UNSET,
                                pose_base: Any = None, pose_angles: Any = None,
                                options: Optional[_vibrissa.SolveOptions] = None, shapes: bool = False,
                                threads: Optional[int] = None, progress: Any = None, on_error: str = "record",
                                **deprecated: Any) -> BatchResult:
    """Frictional edge mode (Coulomb ``mu``) along time series (see :func:`solve_frictional_edge`).

    The contact history runs through each series in order: frame f starts from frame f-1's contact point and
    solution. The first touch (and any touch after contact was lost) starts at the frictionless contact,
    unless ``initial_contact_W`` ((3,) or (S, 3), world [m]) gives the first frame's previous contact. The
    keywords ``edge_points``, ``edge_directions``, ``initial_contact`` and ``approach`` are deprecated
    aliases (removed in 0.2.0)."""
    a = _renamed_args("solve_frictional_edge_batch",
                      {"edge_points_W": edge_points_W, "edge_directions_W": edge_directions_W,
                       "initial_contact_W": initial_contact_W, "approach_W": approach_W},
                      deprecated, {"edge_points": "edge_points_W", "edge_directions": "edge_directions_W",
                                   "initial_contact": "initial_contact_W", "approach": "approach_W"})
    _check_on_error(on_error)
    return _finish(_vibrissa.solve_frictional_edge_batch(
        whisker, a["edge_points_W"], a["edge_directions_W"], mu, initial_contact_W=a["initial_contact_W"],
        approach_W=a["approach_W"], pose_base=pose_base, pose_angles=pose_angles, options=options,
        shapes=shapes, threads=threads, progress=progress), on_error, "solve_frictional_edge_batch")
