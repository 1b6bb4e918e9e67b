from os import PathLike
from typing import Any, Dict, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._vibrissa import Shape, Whisker

class _ModesView:
    frequency: npt.NDArray[np.float64]
    damped_frequency: npt.NDArray[np.float64]
    damping_ratio: npt.NDArray[np.float64]
    torsion_fraction: npt.NDArray[np.float64]
    omega: npt.NDArray[np.float64]
    joint_shapes: npt.NDArray[np.float64]
    node_shapes: npt.NDArray[np.float64]
    joint_damping_time: float
    equilibrium: Optional[Dict[str, Any]]
    def __len__(self) -> int: ...

class DynamicsResult:
    datasets: Dict[str, npt.NDArray[Any]]
    summary: Dict[str, Any]
    status: str
    modes: _ModesView
    def __getattr__(self, name: str) -> npt.NDArray[Any]: ...
    def __getitem__(self, name: str) -> npt.NDArray[Any]: ...
    def to_xarray(self) -> Any: ...
    def write(self, directory: Union[str, PathLike]) -> None: ...

def modes(whisker: Whisker, count: int = 10, *, load: Optional[Mapping[str, Any]] = None,
          hold: Optional[str] = None, density: Optional[float] = None,
          damping_ratio: Optional[float] = None, joint_damping_time: Optional[float] = None) -> _ModesView: ...
def simulate_dynamics(whisker: Whisker, duration: float = 1.0, output_rate: float = 1000.0, *,
                      whisking: Optional[Mapping[str, Any]] = None, tip_force: Optional[Sequence[float]] = None,
                      force: Optional[Sequence[float]] = None, arc_length: Optional[float] = None,
                      density: Optional[float] = None, damping_ratio: Optional[float] = None,
                      joint_damping_time: Optional[float] = None, gravity: Optional[Sequence[float]] = None,
                      relative_tolerance: Optional[float] = None,
                      absolute_tolerance: Optional[float] = None,
                      objects: Optional[Sequence[Union[Mapping[str, Any], Shape]]] = None,
                      contact: Optional[Mapping[str, Any]] = None,
                      model: Optional[str] = None) -> DynamicsResult: ...
