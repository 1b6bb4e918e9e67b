"""Type stubs of vibrissa.sweeps (docs/sweeps.md)."""

import os
from typing import Any, Callable, Mapping, Optional, Sequence, Union

PathLike = Union[str, os.PathLike[str]]

def sweep(kind: str, base: Union[Mapping[str, Any], PathLike, None] = None, *,
          grid: Optional[Mapping[str, Sequence[Any]]] = None, runs: Optional[Sequence[Mapping[str, Any]]] = None,
          out: Optional[PathLike] = None, variables: Optional[Sequence[str]] = None,
          scheduler: Optional[str] = None, workers: Optional[int] = None, chunk_size: Optional[int] = None,
          progress: Optional[Callable[[int, int], Any]] = None,
          client: Any = None) -> Any: ...  # xarray.Dataset
def main(argv: Optional[Sequence[str]] = None) -> int: ...

__all__: list[str]
