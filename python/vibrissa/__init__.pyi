"""Type stubs of the `vibrissa` package (see docs/python.md)."""

from ._vibrissa import BaseJoint as BaseJoint
from ._vibrissa import Case as Case
from ._vibrissa import ContactMode as ContactMode
from ._vibrissa import ContactState as ContactState
from ._vibrissa import ContactTracker as ContactTracker
from ._vibrissa import Edge as Edge
from ._vibrissa import FrictionState as FrictionState
from ._vibrissa import LoadState as LoadState
from ._vibrissa import Pose as Pose
from ._vibrissa import Scheme as Scheme
from ._vibrissa import Solution as Solution
from ._vibrissa import SolveOptions as SolveOptions
from ._vibrissa import Status as Status
from ._vibrissa import Whisker as Whisker
from ._vibrissa import WhiskerFrameSignals as WhiskerFrameSignals
from ._vibrissa import WhiskerProperties as WhiskerProperties
from ._vibrissa import __version__ as __version__
from ._vibrissa import max_threads as max_threads
from ._vibrissa import nearest_rest_point as nearest_rest_point
from ._vibrissa import pose_from_rotation as pose_from_rotation
from ._vibrissa import rotation_from_angles as rotation_from_angles
from ._vibrissa import solution_to_json as solution_to_json
from ._vibrissa import solve_case as solve_case
from ._vibrissa import solve_dead_load as solve_dead_load
from ._vibrissa import solve_edge as solve_edge
from ._vibrissa import solve_force as solve_force
from ._vibrissa import solve_frictional_edge as solve_frictional_edge
from ._vibrissa import solve_point as solve_point
from ._vibrissa import status_from_string as status_from_string
from ._vibrissa import write_result as write_result
from .batch import STATUS_NAMES as STATUS_NAMES
from .batch import BatchResult as BatchResult
from .batch import solve_edge_batch as solve_edge_batch
from .batch import solve_force_batch as solve_force_batch
from .batch import solve_frictional_edge_batch as solve_frictional_edge_batch
from .batch import solve_point_batch as solve_point_batch
from .case import case_from_dict as case_from_dict
from .case import load_case as load_case
from .case import make_whisker as make_whisker
from .case import solve_case_file as solve_case_file

from .pipeline import ArrayResult as ArrayResult
from .pipeline import Trial as Trial
from .pipeline import TrialResult as TrialResult
from .pipeline import analyze_trial as analyze_trial
from .pipeline import default_array_config as default_array_config
from .pipeline import read_trial as read_trial
from .pipeline import simulate_array as simulate_array
from .pipeline import synthesize_trial as synthesize_trial
from .pipeline import synthesize_trial_defaults as synthesize_trial_defaults

__all__: list[str]
