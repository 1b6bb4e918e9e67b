"""The base-wrench inverse over time series (docs/inverse.md): where and how hard the whisker was touched,
frame by frame, from the force and moment at its base."""

from __future__ import annotations

import warnings

import numpy as np

from . import _vibrissa
from .batch import INVALID_INPUT, _check_on_error, _warn_deprecated

__all__ = ["BaseWrenchBatch", "solve_base_wrench_batch"]


class BaseWrenchBatch:
    """Stacked results of :func:`solve_base_wrench_batch`, shape (F, ...) or (S, F, ...).

    * ``status`` int32 codes of :class:`Status` (``STATUS_NAMES[code]``), ``converged`` bool (``underdetermined``
      bool: fits that explain the signals but cannot locate the contact; a warning says how many)
    * ``arc_length`` [m], ``force_magnitude`` [N], ``angle`` [rad], ``chi2``
    * ``contact_point_W`` (..., 3) world [m] (``contact_point``: deprecated alias, removed in 0.2.0)
    * ``identifiable`` bool, ``condition_number``, ``covariance`` (..., 3, 3) of (s, f, zeta),
      ``contact_point_covariance`` (..., 3, 3) [m^2]
    * ``results``: the :class:`BaseWrenchResult` objects, nested like the frames (roots and all)
    """

    def __init__(self, results, series_axis: bool, errors=()):
        self.results = results if series_axis else results[0]
        #: one (series, frame, message) per frame whose input was refused (status invalid_input, NaN, result None)
        self.errors = list(errors)
        rows = [r for series in results for r in series]
        shape = (len(results), len(results[0])) if series_axis else (len(results[0]),)

        def stack(get, tail=()):
            nan = np.full(tail, np.nan) if tail else np.nan
            return np.array([nan if r is None else get(r) for r in rows], dtype=float).reshape(shape + tail)

        self.status = np.array([INVALID_INPUT if r is None else int(r.solution.status) for r in rows],
                               dtype=np.int32).reshape(shape)
        self.converged = self.status == int(_vibrissa.Status.converged)
        self.underdetermined = self.status == int(_vibrissa.Status.underdetermined)
        self.arc_length = stack(lambda r: r.solution.arc_length)
        self.force_magnitude = stack(lambda r: r.solution.force_magnitude)
        self.angle = stack(lambda r: r.solution.angle)
        self.chi2 = stack(lambda r: r.chi2)
        self.contact_point_W = stack(lambda r: r.solution.contact_point_W, (3,))
        self.identifiable = np.array([r is not None and r.identifiability.identifiable for r in rows],
                                     dtype=bool).reshape(shape)
        self.condition_number = stack(lambda r: r.identifiability.condition_number)
        self.covariance = stack(lambda r: r.identifiability.covariance, (3, 3))
        self.contact_point_covariance = stack(lambda r: r.identifiability.contact_point_covariance, (3, 3))

    @property
    def contact_point(self) -> np.ndarray:
        """Deprecated alias of ``contact_point_W`` (removed in 0.2.0)."""
        _warn_deprecated("BaseWrenchBatch.contact_point", "contact_point_W")
        return self.contact_point_W

    def __repr__(self) -> str:
        return f"BaseWrenchBatch(shape={self.status.shape}, converged={int(self.converged.sum())})"


def solve_base_wrench_batch(whisker, force_W, moment_W, *, pose=None, signals="all", noise=None, starts=16,
                            options=None, threads=None, progress=None, on_error="record") -> BaseWrenchBatch:
    """:func:`solve_base_wrench` over time series: ``force_W`` and ``moment_W`` of shape (F, 3) for one series
    or (S, F, 3) for S series (world frame, moment about the base). Frame k of a series is warm-started from
    frame k-1's fit (a full scan when that fails); series run in parallel with the GIL released. Ctrl-C
    interrupts; ``progress(done, total)`` counts frames.

    A frame whose input is refused (a NaN or subnormal component, ...) does not stop the batch
    (``on_error="record"``, the default, as the other batches): its status is ``invalid_input``, its numbers
    NaN, its result None, ``errors`` lists (series, frame, message) and a UserWarning gives the count; the
    other frames of its series are then each solved cold. ``on_error="raise"`` raises the first one's
    ValueError naming the series and frame."""
    _check_on_error(on_error)
    series_axis = np.ndim(force_W) == 3
    results, errors = _vibrissa._solve_base_wrench_series(whisker, force_W, moment_W, pose, signals, noise, starts,
                                                          options, threads, progress)
    if errors and on_error == "raise":
        s, f, message = errors[0]
        raise ValueError(f"{message} (series {s}, frame {f})")
    if errors:
        s, f, message = errors[0]
        warnings.warn(f"solve_base_wrench_batch: {len(errors)} of {sum(map(len, results))} frames refused (status "
                      f"invalid_input, see .errors); the first, series {s}, frame {f}: {message}", UserWarning,
                      stacklevel=2)
    batch = BaseWrenchBatch(results, series_axis, errors)
    n = int(batch.underdetermined.sum())
    if n:
        first = next(r for series in results for r in series if r is not None and r.warnings)
        warnings.warn(f"{n} of {batch.status.size} fits are underdetermined (first: {first.warnings[0]})", stacklevel=2)
    return batch
