from os import PathLike
from typing import Any, Callable, Dict, Optional, Sequence, Tuple, Union

from ._vibrissa import Trial

_Path = Union[str, PathLike]
# a path, a pandas DataFrame in DeepLabCut's layout, or a (frames, points, 2|3) array
_Tracks = Union[str, PathLike, Any]

def reconstruct(top: _Tracks, front: _Tracks, calibration: _Path, *, peg_m: Optional[Any] = None,
                edge_m: Optional[Any] = None, top_camera: str = "top", front_camera: str = "front",
                bodyparts: Union[str, Sequence[str]] = (), individual: str = "", whisker_id: int = 0,
                top_measurements: _Path = "", front_measurements: _Path = "", min_likelihood: float = 0.5,
                max_reprojection_px: float = 2.0, contact_threshold: float = 300e-6, base_jump: float = 1e-3,
                fit_segments: int = 6, nodes: int = 40, frame_rate: float = 1000.0, source: Optional[str] = None,
                progress: Optional[Callable[[int, int], Any]] = None, peg: Optional[Any] = None,
                edge: Optional[Any] = None) -> Tuple[Trial, Dict[str, Any]]: ...
