"""vibrissa: quasi-static 3D mechanics of rat whiskers (Huet & Hartmann 2016).

The compiled core (``vibrissa._vibrissa``) mirrors the C++ library one to one: :class:`Whisker`,
:class:`Pose`, :class:`WhiskerProperties`, :class:`Edge`, :class:`SolveOptions`, :class:`Solution`,
:class:`Status` and the solvers :func:`solve_force`, :func:`solve_dead_load`, :func:`solve_point`,
:func:`solve_edge`, :func:`solve_frictional_edge`. This package adds

* batch solves over many frames / whiskers that release the GIL and use every core
  (:func:`solve_point_batch`, :func:`solve_edge_batch`, :func:`solve_frictional_edge_batch`,
  :func:`solve_force_batch`), returning a :class:`BatchResult` of stacked NumPy arrays;
* the inverse: where and how hard the whisker was touched from the force/moment at its base
  (:func:`solve_base_wrench`, :func:`solve_base_wrench_batch`; docs/inverse.md);
* the JSON case round trip of ``vibrissa solve`` (:func:`load_case`, :func:`make_whisker`,
  :func:`solve_case_file`);
* the whole pipeline of the CLI with NumPy arrays out: :func:`synthesize_trial` (``vibrissa synth``),
  :func:`read_trial` / :meth:`Trial.write`, :func:`analyze_trial` (``vibrissa trial``) -> :class:`TrialResult`,
  :func:`simulate_array` (``vibrissa array``) -> :class:`ArrayResult`; bit-identical to the CLI,
  interruptible with Ctrl-C, with ``progress`` callbacks;
* labelled results (``ArrayResult.to_xarray()``, ``TrialResult.to_xarray()``) and parameter sweeps on Dask
  (:func:`sweep`: grids of array, trial or solve runs -> one xarray Dataset; docs/sweeps.md);
* plotting helpers (:mod:`vibrissa.plot`, needs matplotlib).

SI units throughout: m, N, N·m, Pa, rad. World-frame quantities unless the name says otherwise
(``_B``: whisker frame; ``whisker_frame``: the base signals of spec §2.4). See docs/python.md.
"""

from ._vibrissa import (  # noqa: F401
    BaseJoint,
    Box,
    Cylinder,
    Mesh,
    Plane,
    Shape,
    Sphere,
    BaseWrenchIdentifiability,
    BaseWrenchResult,
    BaseWrenchRoot,
    Case,
    ContactMode,
    ContactState,
    ContactTracker,
    Edge,
    FrictionState,
    LoadState,
    Pose,
    Scheme,
    Solution,
    SolveOptions,
    Status,
    Whisker,
    WhiskerFrameSignals,
    WhiskerProperties,
    __version__,
    max_threads,
    nearest_rest_point,
    pose_from_rotation,
    rotation_from_angles,
    solution_to_json,
    solve_case,
    solve_dead_load,
    solve_edge,
    solve_force,
    solve_frictional_edge,
    solve_frictional_object,
    solve_object,
    solve_base_wrench,
    solve_point,
    status_from_string,
    write_result,
)
from .batch import (  # noqa: F401
    STATUS_NAMES,
    BatchResult,
    solve_edge_batch,
    solve_force_batch,
    solve_frictional_edge_batch,
    solve_point_batch,
)
from .inverse import BaseWrenchBatch, solve_base_wrench_batch  # noqa: F401
from .recon import reconstruct  # noqa: F401
from .sweeps import sweep  # noqa: F401
from .dynamics import DynamicsResult, modes, simulate_dynamics  # noqa: F401
from .case import case_from_dict, load_case, make_whisker, solve_case_file  # noqa: F401
from .pipeline import (  # noqa: F401
    ArrayResult,
    Trial,
    TrialResult,
    analyze_trial,
    analyze_trials,
    default_array_config,
    read_trial,
    simulate_array,
    synthesize_trial,
    synthesize_trial_defaults,
)


def _solution_view(self, path="solve_view.html", case=None):
    """Writes the interactive 3D viewer of this solve, one self-contained HTML file (docs/viewer.md; as
    ``vibrissa view RESULT.json``); `case` (the Case, a case file or dict) adds the rest shape and the edge.
    Returns the path."""
    from .viewer import write_solve_view
    return write_solve_view(self, path, case)


Solution.view = _solution_view  # a method of the compiled class, written in Python (the viewer is Python)

__all__ = [
    "ArrayResult", "Trial", "TrialResult", "analyze_trial", "analyze_trials", "default_array_config", "read_trial",
    "simulate_array", "synthesize_trial", "synthesize_trial_defaults",
    "BaseJoint", "BatchResult", "Box", "Case", "Cylinder", "Mesh", "Plane", "Shape", "Sphere", "solve_object",
    "solve_frictional_object", "ContactMode", "ContactState", "ContactTracker", "Edge", "FrictionState", "LoadState", "Pose",
    "STATUS_NAMES", "Scheme", "Solution",
    "SolveOptions", "Status", "Whisker", "WhiskerFrameSignals", "WhiskerProperties", "__version__",
    "case_from_dict", "load_case", "make_whisker", "max_threads", "nearest_rest_point", "pose_from_rotation",
    "rotation_from_angles",
    "solution_to_json", "solve_case", "solve_case_file", "solve_dead_load", "solve_edge", "solve_edge_batch",
    "solve_force", "solve_force_batch", "solve_frictional_edge", "solve_frictional_edge_batch", "solve_point",
    "solve_point_batch", "status_from_string", "write_result",
    "BaseWrenchBatch", "BaseWrenchIdentifiability", "BaseWrenchResult", "BaseWrenchRoot", "solve_base_wrench",
    "solve_base_wrench_batch", "reconstruct", "sweep",
    "DynamicsResult", "modes", "simulate_dynamics",
]
