"""Track inputs as Python users hold them (docs/python.md, "Reconstruction"): a path, a pandas DataFrame in
DeepLabCut's layout, or a NumPy array. Tables and arrays are written to a temporary file in a format the C++
readers already take (docs/reconstruction.md, "Track files"), so every input goes through the same reader,
checks and messages as ``vibrissa reconstruct``."""
import errno
import math
import os

import numpy as np

# DeepLabCut's column levels, outermost first (3: single animal, 4: multi-animal).
_DLC_LEVELS = {3: ("scorer", "bodyparts", "coords"), 4: ("scorer", "individuals", "bodyparts", "coords")}


def existing_path(value, name):
    """``os.fspath(value)``; FileNotFoundError naming ``name`` if no such file exists."""
    path = os.fspath(value)
    if not os.path.exists(path):
        raise FileNotFoundError(errno.ENOENT, f"{name}: no such file", path)
    return path


def _cell(v):
    v = float(v)
    return "" if math.isnan(v) else repr(v)


def _is_dataframe(value):
    cls = type(value)
    return cls.__name__ == "DataFrame" and cls.__module__.split(".")[0] == "pandas"


def _write_dataframe(frame, path, name):
    columns = frame.columns
    levels = getattr(columns, "nlevels", 1)
    if levels == 2:  # (bodyparts, coords) without the scorer level
        keys = [("vibrissa",) + tuple(c) for c in columns]
        levels = 3
    elif levels in _DLC_LEVELS:
        keys = [tuple(c) for c in columns]
    else:
        raise ValueError(f"{name}: a DataFrame in DeepLabCut's layout has column levels scorer, [individuals,] "
                         f"bodyparts, coords; got {levels} level(s) {list(getattr(columns, 'names', []))}")
    coords = {k[-1] for k in keys}
    if not {"x", "y"} <= coords:
        raise ValueError(f"{name}: the DataFrame's coords level must hold x and y (and likelihood), got "
                         f"{sorted(map(str, coords))}")
    for key in keys:
        for cell in key:
            if any(ch in str(cell) for ch in ',"\n'):
                raise ValueError(f"{name}: column label {str(cell)!r} holds a comma, quote or newline")
    values = np.asarray(frame.to_numpy(), dtype=float)
    index = frame.index
    integer_index = index.nlevels == 1 and np.issubdtype(np.asarray(index).dtype, np.integer)
    frames = np.asarray(index) if integer_index else np.arange(len(frame))  # else: row order, as the CLI
    with open(path, "w", encoding="utf-8") as out:
        for level, label in enumerate(_DLC_LEVELS[levels]):
            out.write(",".join([label] + [str(k[level]) for k in keys]) + "\n")
        for k, row in zip(frames, values):
            out.write(",".join([str(int(k))] + [_cell(v) for v in row]) + "\n")


def _write_array(array, path, name):
    a = np.asarray(array, dtype=float)
    if a.ndim != 3 or a.shape[2] not in (2, 3):
        raise ValueError(f"{name}: a NumPy track array has shape (frames, points, 2) with x_px, y_px or "
                         f"(frames, points, 3) with x_px, y_px, likelihood (points from the base); got {a.shape}")
    with open(path, "w", encoding="utf-8") as out:
        out.write("frame,point,x_px,y_px" + (",likelihood" if a.shape[2] == 3 else "") + "\n")
        for f in range(a.shape[0]):
            for p in range(a.shape[1]):
                out.write(",".join([str(f), str(p)] + [_cell(v) for v in a[f, p]]) + "\n")


def track_file(value, name, folder):
    """A path for the track reader: ``value`` itself if it is a path (FileNotFoundError if missing), else a
    DeepLabCut CSV (DataFrame) or plain CSV (NumPy array) written into ``folder``. Returns (path, label):
    label describes the input for the trial's ``source``."""
    if isinstance(value, (str, bytes, os.PathLike)):
        path = existing_path(value, name)
        return path, path
    path = os.path.join(folder, f"{name}.csv")
    if _is_dataframe(value):
        _write_dataframe(value, path, name)
        return path, f"{name}: pandas DataFrame"
    if isinstance(value, np.ndarray) or isinstance(value, (list, tuple)):
        _write_array(value, path, name)
        return path, f"{name}: NumPy array"
    raise TypeError(f"{name}: expected a path, a pandas DataFrame in DeepLabCut's layout or a NumPy array, got "
                    f"{type(value).__name__}")
