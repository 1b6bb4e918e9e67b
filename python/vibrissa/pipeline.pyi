"""Type stubs of vibrissa.pipeline (docs/python.md: trials and arrays)."""

import os
import pathlib
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._vibrissa import Trial as Trial
from ._vibrissa import read_trial as read_trial

Progress = Optional[Callable[[int, int], Any]]
PathLike = Union[str, os.PathLike[str]]

def synthesize_trial(*, progress: Progress = None, mu: float = ..., duration: float = ..., frame_rate: float = ...,
                     whisk_hz: float = ..., theta_center_deg: float = ..., theta_amplitude_deg: float = ...,
                     protraction_fraction: float = ..., phi_slope: float = ..., zeta_slope: float = ...,
                     whisker_length_mm: float = ..., curvature: float = ..., peg_distance_mm: float = ...,
                     peg_azimuth_deg: float = ..., noise_position_um: float = ..., noise_angle_deg: float = ...,
                     seed: int = ..., shapes: bool = ...) -> Trial: ...
def synthesize_trial_defaults() -> dict[str, float]: ...

class TrialResult:
    trial: Trial
    columns: dict[str, npt.NDArray[Any]]  # the columns of frames.h5
    summary: dict[str, Any]  # summary.json
    def __getattr__(self, name: str) -> npt.NDArray[Any]: ...
    def __getitem__(self, name: str) -> npt.NDArray[Any]: ...
    def __len__(self) -> int: ...
    def to_dataframe(self) -> Any: ...  # pandas.DataFrame
    def to_xarray(self) -> Any: ...  # xarray.Dataset, = xarray.open_dataset("frames.h5")
    def write(self, directory: PathLike) -> pathlib.Path: ...
    def figures(self, directory: PathLike, window: Optional[tuple[float, float]] = None, whisk: Optional[int] = None,
                dpi: Optional[int] = None, all_figures: bool = False) -> list[pathlib.Path]: ...
    def view(self, path: PathLike = "trial_view.html") -> pathlib.Path: ...  # docs/viewer.md

def analyze_trial(trial: Union[Trial, PathLike], mu: Optional[float] = None, cutoff: float = 85.0,
                  filter_order: int = 2, no_filter: bool = False, *, mu_eq7: Optional[float] = None,
                  no_roll_fit: bool = False, rest_shape_per_contact: bool = False,
                  progress: Progress = None) -> TrialResult: ...

def analyze_trials(trials: Union[dict[str, Any], Sequence[PathLike]], **options: Any
                   ) -> tuple[dict[str, TrialResult], Any]: ...  # (results, pandas.DataFrame)

def default_array_config() -> dict[str, Any]: ...

class ArrayResult:
    datasets: dict[str, npt.NDArray[Any]]  # the datasets of array.h5 ("render/..." for the render group)
    summary: dict[str, Any]  # summary.json
    config: dict[str, Any]  # config.json
    wall_seconds: float
    def __getattr__(self, name: str) -> npt.NDArray[Any]: ...
    def __getitem__(self, name: str) -> npt.NDArray[Any]: ...
    def to_xarray(self, group: str = "") -> Any: ...  # xarray.Dataset, = xarray.open_dataset("array.h5", group=group)
    def write(self, directory: PathLike, csv: bool = False) -> pathlib.Path: ...
    def view(self, path: PathLike = "array_view.html") -> pathlib.Path: ...  # docs/viewer.md

def simulate_array(config: Union[dict[str, Any], PathLike, None] = None, progress: Progress = None,
                   threads: Optional[int] = None, dynamics: bool = False) -> ArrayResult: ...

__all__: list[str]
