"""The interactive 3D viewer (docs/viewer.md): one self-contained HTML page per result.

``vibrissa view RESULT`` (``python -m vibrissa view``), ``ArrayResult.view()`` and :func:`view` write a page
that opens from disk with no network: three.js and its OrbitControls from Debian's
libjs-three (``/usr/share/javascript/three``, r111; ``$VIBRISSA_THREE_DIR`` elsewhere) and the viewer's own
scripts (``viewer/*.js``, installed as ``vibrissa/viewer/``) are inlined when the page is written, and the data
are compressed base64 binary arrays (Float32 signals, Int16 shapes quantised to 1/16000 of the scene's
extent, Uint8 states; see _Blobs), decoded by the page per head pitch when it is shown.

A trial (its file and the output directory of ``vibrissa trial``; ``TrialResult.view()``) is shown too:
see write_trial_view. The source of an array page is an array result (``ArrayResult``, or a ``vibrissa array`` output directory with ``array.h5``
and ``config.json``): every whisker at every frame and head pitch. ``array.h5`` keeps deflected shapes only
for ``output.render_count`` frames of one pitch, so the shapes are simulated again from the configuration,
one pitch at a time with every frame rendered (the same deterministic simulation); the signals are those of
the result. Sweep and solve outputs are not shown yet (docs/viewer.md, "Limits").
"""

import argparse
import base64
import json
import os
import pathlib
import sys
import zlib

import numpy as np

__all__ = ["view", "write_array_view", "write_trial_view", "main"]

PACKAGE = pathlib.Path(__file__).resolve().parent
NODES = 16  # points along each whisker in the page (the simulation's 100 links are resampled)
PLAY_FPS = 30
STATE_NAMES = ["free", "in contact", "pushed past"]


def _assets_dir():
    """viewer/*.js and page.html: the package's copy (build tree, install), else the source tree's."""
    for candidate in (PACKAGE / "viewer", PACKAGE.parents[1] / "viewer"):
        if (candidate / "viewer.js").is_file():
            return candidate
    raise FileNotFoundError(f"the viewer's page scripts were not found (looked in {PACKAGE / 'viewer'})")


def _three_dir():
    directory = pathlib.Path(os.environ.get("VIBRISSA_THREE_DIR", "/usr/share/javascript/three"))
    if not (directory / "three.min.js").is_file():
        raise FileNotFoundError(f"three.js not found: {directory / 'three.min.js'} (apt-get install libjs-three, "
                                "or set VIBRISSA_THREE_DIR to a directory with three.min.js and "
                                "examples/js/controls/OrbitControls.js)")
    return directory


class _Blobs:
    """The page's binary arrays: each becomes a <script type="application/octet-stream"> element holding the
    base64 of the array's bytes, optionally differenced along its first axis (`delta`: Int16 codes of shapes
    change little from frame to frame), split into byte planes (all first bytes, then all second bytes, ...)
    and deflate-compressed (zlib, level 1); viewer.js undoes the three steps (DecompressionStream)."""

    DTYPES = {np.dtype(np.float32): "float32", np.dtype(np.int16): "int16", np.dtype(np.uint8): "uint8",
              np.dtype(np.uint32): "uint32"}

    def __init__(self):
        self.elements = []

    def add(self, array, delta=False):
        array = np.ascontiguousarray(array)
        dtype = self.DTYPES[array.dtype]
        ident = f"b{len(self.elements)}"
        attrs = f'id="{ident}" data-dtype="{dtype}" data-encoding="deflate"'
        if delta and array.ndim > 1 and array.shape[0] > 1:
            if array.dtype != np.int16:
                raise ValueError("delta coding is for Int16 codes")
            d = array.copy()
            d[1:] = array[1:] - array[:-1]  # wraps modulo 2^16, as the page's Int16Array sum does
            stride = array[0].size
            array = d
            attrs += f' data-delta="{stride}"'
        planes = array.reshape(-1).view(np.uint8).reshape(-1, array.itemsize).T.tobytes()
        data = base64.b64encode(zlib.compress(planes, 1)).decode("ascii")
        self.elements.append(f'<script type="application/octet-stream" {attrs}>{data}</script>')
        return ident


def _inline_script(text):
    return text.replace("</script", "<\\/script")


def _write_page(meta, blobs, out):
    assets, three = _assets_dir(), _three_dir()
    page = (assets / "page.html").read_text(encoding="utf-8")
    parts = {
        "@TITLE@": meta["title"].replace("&", "&amp;").replace("<", "&lt;"),
        "@META@": _inline_script(json.dumps(meta, separators=(",", ":"), allow_nan=False)),
        "@BLOBS@": "\n".join(blobs.elements),
        "@THREE@": _inline_script((three / "three.min.js").read_text(encoding="utf-8")),
        "@ORBIT@": _inline_script((three / "examples/js/controls/OrbitControls.js").read_text(encoding="utf-8")),
        "@VIEWER@": _inline_script((assets / "viewer.js").read_text(encoding="utf-8")),
    }
    for key in ("@TITLE@", "@META@", "@BLOBS@", "@VIEWER@", "@ORBIT@", "@THREE@"):
        head, sep, tail = page.partition(key)
        if not sep:
            raise ValueError(f"viewer page template lacks {key}")
        page = head + parts[key] + tail
    out = pathlib.Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_name(f".tmp-{out.name}")
    tmp.write_text(page, encoding="utf-8")
    os.replace(tmp, out)  # atomic, as every output (docs/formats.md, "Atomic outputs")
    return out


def _resample(shapes, nodes=NODES):
    """shapes [..., N, 3] -> [..., nodes, 3] at evenly spaced node indices (base and tip kept)."""
    n = shapes.shape[-2]
    if n <= nodes:
        return shapes
    x = np.linspace(0, n - 1, nodes)
    i0 = np.minimum(np.floor(x).astype(int), n - 2)
    f = (x - i0)[:, None]
    return shapes[..., i0, :] * (1 - f) + shapes[..., i0 + 1, :] * f


def _quantise(shapes_mm, lo, hi):
    """Int16 codes of positions [mm] in the box [lo, hi]: step = extent / 16000 per axis (4 µm in a 60 mm
    scene, a tenth of a whisker's tip diameter: finer than the eye sees, and it compresses well)."""
    step = np.maximum((hi - lo) / 16000.0, 1e-9)
    offset = 0.5 * (lo + hi)
    q = np.round((shapes_mm - offset) / step)
    q = np.where(np.isfinite(q), q, 0)
    return np.clip(q, -32767, 32767).astype(np.int16), offset, step


def _ranges(signals):
    """Per signal over one group: min, max, max |value| (colour scales)."""
    out = []
    for s in signals:
        finite = s[np.isfinite(s)]
        out.append([float(finite.min()), float(finite.max()), float(np.abs(finite).max())] if finite.size
                   else [0.0, 1.0, 1.0])
    return out


def _view_box(points_mm):
    p = points_mm.reshape(-1, 3)
    p = p[np.isfinite(p).all(axis=1)]
    lo, hi = p.min(axis=0), p.max(axis=0)
    return lo, hi


def _object_meshes(objects, blobs):
    """Surface objects (docs/objects.md) as triangle meshes in their own frame [mm]: the mesh's triangles, a
    plane as a square, other shapes as the convex hull of points on their surface."""
    import object_outline  # figures/, on the path (see _figures_on_path)
    out = []
    for description, vertices in objects:
        kind = description["type"]
        if kind == "mesh" and vertices is not None and "triangles" in description:
            v, tri = np.asarray(vertices), np.asarray(description["triangles"])
        elif kind == "plane":
            _, e1, e2 = object_outline._frame(description["normal"])
            h = object_outline.INFINITE_HALF_LENGTH
            c = np.asarray(description["point"])
            v = np.array([c + h * (a * e1 + b * e2) for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
            tri = np.array([[0, 1, 2], [0, 2, 3]])
        else:
            from scipy.spatial import ConvexHull
            v = object_outline.surface_points(description, vertices, n=32)
            tri = ConvexHull(v).simplices
        out.append({"type": kind, "vertices": blobs.add((np.asarray(v) * 1e3).astype(np.float32)),
                    "triangles": blobs.add(np.asarray(tri).astype(np.uint32))})
    return out


def _figures_on_path():
    for candidate in (PACKAGE / "figures", PACKAGE.parents[1] / "figures"):
        if (candidate / "object_outline.py").is_file():
            if str(candidate) not in sys.path:
                sys.path.insert(0, str(candidate))
            return
    raise FileNotFoundError("figures/object_outline.py not found")


def _base_meta(kind, title, times, whiskers, signals, colour_by, group_label, whisker_label):
    return {"kind": kind, "title": title, "times": [float(t) for t in times], "whiskers": list(whiskers),
            "nodes": NODES, "signals": signals, "colour_by": colour_by, "state_names": STATE_NAMES,
            "group_label": group_label, "whisker_label": whisker_label, "play_fps": PLAY_FPS, "groups": [],
            "objects": [], "edges": 0}


# ---- array ------------------------------------------------------------------------------------------------
ARRAY_SIGNALS = [  # key in array.h5, label, unit, scale from SI
    ("MB", "M_B", "µN·m", 1e6), ("FT", "F_T", "mN", 1e3), ("MD", "M_D", "deg", 180 / np.pi),
    ("FD", "F_D", "deg", 180 / np.pi), ("normal_force", "F_N", "mN", 1e3)]


def _array_source(source):
    """(datasets dict, config dict, objects) of a `vibrissa array` output directory."""
    directory = pathlib.Path(source)
    if directory.is_file():
        directory = directory.parent
    import h5py
    _figures_on_path()
    import object_outline
    with h5py.File(directory / "array.h5", "r") as f:
        data = {k: f[k][()] for k in ["state", "contact_point_W", "time", "pitch", "whisker"] +
                [s[0] for s in ARRAY_SIGNALS]}
        objects = object_outline.load_objects(f)
    data["whisker"] = [n.decode() if isinstance(n, bytes) else str(n) for n in data["whisker"]]
    config = json.loads((directory / "config.json").read_text())
    return data, config, objects


def _array_shapes(config, pitch_rad, frames):
    """Deflected shapes [frame][whisker][node][3] (m), edges [frame][edge][2][3] and object poses of one head
    pitch, simulated again with every frame rendered."""
    from .pipeline import simulate_array
    c = json.loads(json.dumps(config))
    c.setdefault("head", {})["pitches_deg"] = [float(np.degrees(pitch_rad))]
    c["output"] = {"render_count": int(frames), "render_pitch_index": 0}
    r = simulate_array(c)
    d = r.datasets
    poses = d.get("render/object_poses")
    return _resample(d["render/deflected"]), d["render/edges"], poses


def write_array_view(source, out, pitches=None):
    """Writes the viewer page of an array result (ArrayResult or output directory) to `out`; returns the path.
    `pitches`: indices of the head pitches to include (default all)."""
    _figures_on_path()
    data, config, objects = _array_source(source)
    names = [n.decode() if isinstance(n, bytes) else str(n) for n in data["whisker"]]
    times, pitch = np.asarray(data["time"]), np.asarray(data["pitch"])
    pitch_idx = list(range(len(pitch))) if pitches is None else list(pitches)
    blobs = _Blobs()
    signals = [{"key": k, "label": label, "unit": unit} for k, label, unit, _ in ARRAY_SIGNALS]
    colour_by = [{"label": "|M_B|", "kind": "signal", "signal": 0, "abs": True},
                 {"label": "F_T", "kind": "signal", "signal": 1, "abs": True},
                 {"label": "contact state", "kind": "state"}]
    meta = _base_meta("array", "", times, names, signals, colour_by, "head pitch", "whisker")
    shapes_all, groups = [], []
    for p in pitch_idx:
        shapes, edges, poses = _array_shapes(config, pitch[p], len(times))
        shapes_all.append((p, shapes * 1e3, edges * 1e3, poses))
    lo, hi = _view_box(np.stack([s[1] for s in shapes_all]))
    for p, shapes_mm, edges_mm, poses in shapes_all:
        q, offset, step = _quantise(shapes_mm, lo, hi)
        sig = np.stack([np.asarray(data[k][p], dtype=float) * scale for k, _, _, scale in ARRAY_SIGNALS])
        group = {"label": f"{np.degrees(pitch[p]):+.1f}°", "shapes": blobs.add(q, delta=True),
                 "state": blobs.add(np.asarray(data["state"][p]).astype(np.uint8)),
                 "signals": blobs.add(sig.astype(np.float32)),
                 "contact": blobs.add((np.asarray(data["contact_point_W"][p]) * 1e3).astype(np.float32)),
                 "edges": blobs.add(edges_mm.astype(np.float32)), "ranges": _ranges(sig)}
        if objects and poses is not None:
            group["object_poses"] = blobs.add(_poses_mm(poses))
        groups.append(group)
        meta["quant"] = {"offset": offset.tolist(), "step": step.tolist()}
    meta["groups"] = groups
    meta["edges"] = int(shapes_all[0][2].shape[1])
    meta["objects"] = _object_meshes(objects, blobs) if objects else []
    touched = np.asarray(data["state"][pitch_idx[0]] == 1).any(axis=1)
    meta["initial_whisker"] = int(np.argmax(np.asarray(data["MB"][pitch_idx[0]]).max(axis=1))) if touched.any() else 0
    meta["initial_frame"] = int(np.argmax((np.asarray(data["state"][pitch_idx[0]]) == 1).sum(axis=0)))
    _set_view(meta, lo, hi, direction=[0.55, -0.45, 0.7])
    meta["title"] = (f"vibrissa array: {len(names)} whiskers × {len(times)} frames × {len(pitch_idx)} head "
                     f"pitch{'es' if len(pitch_idx) > 1 else ''}")
    meta["whisker_label"] = "whisker"
    return _write_page(meta, blobs, out)


def _poses_mm(poses):
    p = np.array(poses, dtype=float)
    p[..., 9:12] *= 1e3
    return p.astype(np.float32)


def _set_view(meta, lo, hi, direction):
    centre = 0.5 * (lo + hi)
    meta["view"] = {"centre": centre.tolist(), "radius": float(0.5 * np.linalg.norm(hi - lo)),
                    "direction": direction}
    meta["ribbon_width_mm"] = float(max(0.004 * np.linalg.norm(hi - lo), 0.05))
    meta["edge_radius_mm"] = float(max(0.004 * np.linalg.norm(hi - lo), 0.05))


# ---- trial ------------------------------------------------------------------------------------------------
TRIAL_SIGNALS = [  # column of frames.h5 (contact-point mode), label, unit, scale from SI
    ("cp_MB", "M_B", "µN·m", 1e6), ("cp_FT", "F_T", "mN", 1e3), ("cp_MD", "M_D", "deg", 180 / np.pi),
    ("cp_FD", "F_D", "deg", 180 / np.pi), ("cp_normal_force", "F_N", "mN", 1e3)]
EDGE_HALF_LENGTH_M = 0.02  # a trial's edges are infinite lines: drawn +-20 mm about their point


def write_trial_view(trial_path, results, out):
    """Writes the viewer page of a `vibrissa trial` run: the trial file and its output directory (frames.h5).
    The whisker of each frame in contact-point mode, solved again through the contact point of frames.h5
    (`solve_point`, the run's filtered angles, the tracked base point) and the rest shape placed by the pose
    outside contact; signals of contact-point mode from frames.h5."""
    import h5py
    from . import Pose, WhiskerProperties, Whisker, read_trial, solve_point
    trial = read_trial(str(trial_path))
    with h5py.File(pathlib.Path(results) / "frames.h5", "r") as f:
        d = {k: f[k][()] for k in ["time", "theta", "phi", "zeta", "contact", "cp_status", "cp_contact_x",
                                   "cp_contact_y", "cp_contact_z"] + [c for c, *_ in TRIAL_SIGNALS]}
    keep = np.isin(trial.time, d["time"])
    base = np.asarray(trial.base_W)[keep]
    if len(base) != len(d["time"]):
        raise ValueError(f"{results}: frames.h5 does not belong to {trial_path} (its times differ)")
    m = trial.material
    whisker = Whisker.from_points(trial.rest_shape, properties=WhiskerProperties(
        links=int(m["links"]), base_radius=m["base_radius"], taper_ratio=m["taper_ratio"],
        youngs_modulus=m["youngs_modulus_Pa"], poisson_ratio=m["poisson_ratio"]))
    converged = np.asarray(d["cp_status"]) == 0  # frames.h5 status codes: 0 converged (docs/formats.md)
    contact_W = np.column_stack([d["cp_contact_x"], d["cp_contact_y"], d["cp_contact_z"]])
    n = len(d["time"])
    shapes = np.empty((n, 1, NODES, 3))
    state = np.zeros((1, n), np.uint8)
    for i in range(n):
        pose = Pose(base=base[i], theta=float(d["theta"][i]), phi=float(d["phi"][i]), zeta=float(d["zeta"][i]))
        placed = whisker.placed(pose)
        line = np.asarray(placed.rest_nodes_W)
        if converged[i] and np.isfinite(contact_W[i]).all():
            sol = solve_point(placed, contact_W[i])
            if sol.converged:
                line, state[0, i] = np.asarray(sol.shape_W), 1
        shapes[i, 0] = _resample(line[None])[0]
    shapes_mm, contact_mm = shapes * 1e3, contact_W * 1e3
    edges = np.asarray(trial.edges)
    seg = np.stack([np.stack([e[:3] - EDGE_HALF_LENGTH_M * e[3:] / np.linalg.norm(e[3:]),
                              e[:3] + EDGE_HALF_LENGTH_M * e[3:] / np.linalg.norm(e[3:])]) for e in edges]) * 1e3
    lo, hi = _view_box(np.concatenate([shapes_mm.reshape(-1, 3), seg.reshape(-1, 3)]))
    q, offset, step = _quantise(shapes_mm, lo, hi)
    blobs = _Blobs()
    signals = [{"key": k, "label": label, "unit": unit} for k, label, unit, _ in TRIAL_SIGNALS]
    colour_by = [{"label": "|M_B|", "kind": "signal", "signal": 0, "abs": True},
                 {"label": "F_T", "kind": "signal", "signal": 1, "abs": True},
                 {"label": "contact state", "kind": "state"}]
    meta = _base_meta("trial", f"vibrissa trial: {pathlib.Path(trial_path).name}, {n} frames, contact-point mode",
                      d["time"], ["whisker"], signals, colour_by, "", "")
    sig = np.stack([np.asarray(d[k], float)[None] * scale for k, _, _, scale in TRIAL_SIGNALS])
    meta["groups"] = [{"label": "trial", "shapes": blobs.add(q, delta=True), "state": blobs.add(state),
                       "signals": blobs.add(sig.astype(np.float32)),
                       "contact": blobs.add(contact_mm[None].astype(np.float32)),
                       "edges": blobs.add(np.broadcast_to(seg, (n,) + seg.shape).astype(np.float32)),
                       "ranges": _ranges(sig)}]
    meta["quant"] = {"offset": offset.tolist(), "step": step.tolist()}
    meta["edges"] = len(edges)
    meta["initial_frame"] = int(np.argmax(np.nan_to_num(d["cp_MB"])))
    _set_view(meta, lo, hi, direction=[0.2, -0.5, 0.85])
    return _write_page(meta, blobs, out)


TRIAL_SUFFIXES = (".csv", ".h5", ".hdf5", ".mat")


def view(source, out=None, results=None):
    """Writes the viewer page of `source` (an ArrayResult, or a ``vibrissa array`` output directory or its
    array.h5) and returns its path (default: ``view.html`` in the result directory)."""
    if hasattr(source, "datasets") and hasattr(source, "config"):  # an ArrayResult: through its files
        import tempfile
        with tempfile.TemporaryDirectory(prefix="vibrissa-view-") as tmp:
            source.write(tmp)
            return write_array_view(tmp, out or "array_view.html")
    path = pathlib.Path(source)
    directory = path if path.is_dir() else path.parent
    if (directory / "array.h5").is_file() and (path.is_dir() or path.name == "array.h5"):
        return write_array_view(directory, out or directory / "view.html")
    if path.is_file() and path.suffix.lower() in TRIAL_SUFFIXES:  # a trial file, its results as `vibrissa trial` names them
        results = pathlib.Path(results) if results else path.parent / f"{path.stem}_results"
        if not (results / "frames.h5").is_file():
            raise ValueError(f"{results / 'frames.h5'} not found: run `vibrissa trial {path}` first, or give "
                             "its output directory with --results")
        return write_trial_view(path, results, out or results / "view.html")
    raise ValueError(f"{source}: not a result vibrissa can show (expected a `vibrissa array` output directory or its "
                     "array.h5, or a trial file; sweep and solve outputs are not shown yet: docs/viewer.md)")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="vibrissa view", description=(
        "Write a self-contained interactive 3D viewer (one HTML file, no network) of an array result "
        "directory or an analysed trial (docs/viewer.md)."))
    parser.add_argument("result", help="a `vibrissa array` output directory (or its array.h5), or a trial file "
                                       "analysed by `vibrissa trial`")
    parser.add_argument("-o", "--out", help="the HTML file to write (default: view.html in the result directory)")
    parser.add_argument("--results", help="trial: the output directory of `vibrissa trial` (default: "
                                          "<trial name>_results next to the trial)")
    args = parser.parse_args(argv)
    try:
        path = view(args.result, args.out, args.results)
    except (OSError, ValueError, KeyError) as error:
        print(f"vibrissa view: error: {error}", file=sys.stderr)
        return 1
    print(f"vibrissa view: wrote {path} ({path.stat().st_size / 1e6:.1f} MB)")
    return 0
