from os import PathLike
from typing import Any, Callable, Dict, Mapping, Optional, Sequence, Tuple, Union

from ._vibrissa import Trial

_Path = Union[str, PathLike]
# a path, a pandas DataFrame in DeepLabCut's layout, or a (frames, points, 2|3) array
_Tracks = Union[str, PathLike, Any]

def reconstruct(top: Optional[_Tracks] = None, front: Optional[_Tracks] = None, calibration: Optional[_Path] = None,
                *, views: Optional[Mapping[str, _Tracks]] = None, cameras: Optional[Mapping[str, str]] = None,
                measurements: Optional[Mapping[str, _Path]] = None, peg_m: Optional[Any] = None,
                edge_m: Optional[Any] = None, top_camera: str = "top", front_camera: str = "front",
                bodyparts: Union[str, Sequence[str]] = (), individual: str = "", whisker_id: int = 0,
                top_measurements: _Path = "", front_measurements: _Path = "", min_likelihood: float = 0.5,
                max_reprojection_px: float = 2.0, contact_threshold_m: Optional[float] = None,
                base_jump_m: Optional[float] = None, fit_segments: int = 6, nodes: int = 40,
                frame_rate: float = 1000.0, front_frame_offset: int = 0,
                frame_offsets: Optional[Mapping[str, int]] = None, min_yield: float = 0.5,
                max_unpaired: float = 0.05, max_epipolar_px: float = 2.0, calibration_unit: str = "",
                whiskers: Optional[Mapping[str, Union[int, str, Sequence[str]]]] = None, source: Optional[str] = None, progress: Optional[Callable[[int, int], Any]] = None,
                peg: Optional[Any] = None, edge: Optional[Any] = None, contact_threshold: Optional[float] = None,
                base_jump: Optional[float] = None) -> Any: ...  # (Trial, report dict); with whiskers=: {name: (Trial, report dict)}
