"""Matplotlib helpers (imported lazily: ``import vibrissa.plot`` needs matplotlib, ``import vibrissa`` does not)."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from ._vibrissa import Solution, Whisker

_AXES = {"x": 0, "y": 1, "z": 2}


def plot_solution(solution: Solution, whisker: Optional[Whisker] = None, *, ax: Any = None, plane: str = "xy",
                  scale: float = 1e3, unit: str = "mm", show_force: bool = True) -> Any:
    """Plots the deflected shape (world frame) projected on ``plane`` ('xy', 'xz' or 'yz'), with the rest shape
    of ``whisker`` (if given), the contact point and the contact force direction. Lengths are multiplied by
    ``scale`` (default: metres -> millimetres). Returns the matplotlib Axes."""
    import matplotlib.pyplot as plt

    if len(plane) != 2 or any(c not in _AXES for c in plane):
        raise ValueError(f"plane must be two of 'x', 'y', 'z' (e.g. 'xy'), got {plane!r}")
    i, j = _AXES[plane[0]], _AXES[plane[1]]
    if ax is None:
        _, ax = plt.subplots()
    if whisker is not None:
        rest = whisker.rest_nodes_W * scale
        ax.plot(rest[:, i], rest[:, j], color="0.6", linestyle="--", label="rest")
    if solution.shape_W.shape[0]:
        shape = solution.shape_W * scale
        ax.plot(shape[:, i], shape[:, j], color="C0", label="deflected")
    c = solution.contact_point_W * scale
    ax.plot([c[i]], [c[j]], "o", color="C3", label="contact")
    if show_force and solution.force_magnitude > 0.0:
        f = solution.force_W / solution.force_magnitude
        length = 0.15 * (whisker.length if whisker is not None else solution.arc_length) * scale
        ax.annotate("", xy=(c[i] + length * f[i], c[j] + length * f[j]), xytext=(c[i], c[j]),
                    arrowprops={"arrowstyle": "->", "color": "C3"})
    ax.set_xlabel(f"{plane[0]} [{unit}]")
    ax.set_ylabel(f"{plane[1]} [{unit}]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(loc="best")
    return ax


def plot_batch(result: Any, *, key: str = "force_magnitude", ax: Any = None, time: Optional[np.ndarray] = None,
               label: Optional[str] = None) -> Any:
    """Plots one per-frame field of a :class:`BatchResult` (``'FT'``, ``'MB'`` ... look in ``whisker_frame``)
    against the frame index or ``time``; frames that did not converge are left as gaps. Returns the Axes."""
    import matplotlib.pyplot as plt

    values = getattr(result.whisker_frame, key) if key in ("FT", "MB", "FD", "MD") else getattr(result, key)
    values = np.where(result.converged, values, np.nan)
    if ax is None:
        _, ax = plt.subplots()
    x = np.arange(values.shape[-1]) if time is None else np.asarray(time)
    ax.plot(x, values.T if values.ndim == 2 else values, label=label)
    ax.set_xlabel("frame" if time is None else "time [s]")
    ax.set_ylabel(key)
    return ax
