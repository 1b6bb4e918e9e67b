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
the result. A ``vibrissa solve`` result (with its case when known: write_solve_view) and a sweep's folder
(array, trial and solve sweeps: write_sweep_view) are shown too.
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
    """shapes [..., N, 3] -> [..., nodes, 3] at evenly spaced node indices (base and tip kept; linear between
    nodes, so a whisker of fewer nodes is drawn along its own polyline)."""
    n = shapes.shape[-2]
    if n == nodes:
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
            hull = ConvexHull(v)
            tri = hull.simplices.copy()
            # Qhull does not orient its triangles: turn each to face outward (its facet's normal), so that the
            # page's outline (edges between faces at an angle) does not draw the seams of coplanar triangles.
            n = np.cross(v[tri[:, 1]] - v[tri[:, 0]], v[tri[:, 2]] - v[tri[:, 0]])
            flip = np.einsum("ij,ij->i", n, hull.equations[:, :3]) < 0
            tri[flip] = tri[flip][:, ::-1]
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


def _trial_signal(d, key, scale):
    """A trial signal of frames.h5 in the page's units; F_D and M_D as the trial figures draw them
    (trial_figures.signal): masked where undefined and unwrapped within each contact period (stored, they
    wrap at +-180 deg and swing at contact onset and release)."""
    name = key[len("cp_"):]
    if name not in ("FD", "MD"):
        return np.asarray(d[key], float) * scale
    _figures_on_path()
    import style
    import trial_figures
    mode = next(m for m in style.MODES if m["prefix"] == "cp_")
    return np.asarray(trial_figures.signal(d, [mode], mode, name, "deg"), float)


TRIAL_ANGLE_NOTE = "F_D, M_D unwrapped per contact, masked where undefined as in the figures"


def _trial_scene(trial, results):
    """One analysed trial as the page draws it: `trial` a Trial, `results` its output directory (frames.h5).
    The whisker of each frame in contact-point mode, solved again through the contact point of frames.h5
    (`solve_point`, the run's filtered angles, the tracked base point) and the rest shape placed by the pose
    outside contact; signals of contact-point mode from frames.h5 (F_D, M_D as the figures draw them)."""
    import h5py
    from . import Pose, WhiskerProperties, Whisker, solve_point
    with h5py.File(pathlib.Path(results) / "frames.h5", "r") as f:
        d = {k: f[k][()] for k in ["time", "theta", "phi", "zeta", "contact", "cp_status", "cp_contact_x",
                                   "cp_contact_y", "cp_contact_z", "period", "period_edge"] +
             [c for c, *_ in TRIAL_SIGNALS]}
    keep = np.isin(trial.time, d["time"])
    base = np.asarray(trial.base_W)[keep]
    if len(base) != len(d["time"]):
        raise ValueError(f"{results}: frames.h5 does not belong to the trial (its times differ)")
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
    edges = np.asarray(trial.edges)
    seg = np.stack([np.stack([e[:3] - EDGE_HALF_LENGTH_M * e[3:] / np.linalg.norm(e[3:]),
                              e[:3] + EDGE_HALF_LENGTH_M * e[3:] / np.linalg.norm(e[3:])]) for e in edges]) * 1e3
    sig = np.stack([_trial_signal(d, k, scale)[None] for k, _, _, scale in TRIAL_SIGNALS])
    return {"time": d["time"], "shapes_mm": shapes * 1e3, "state": state, "contact_mm": contact_W * 1e3,
            "edges_mm": seg, "signals": sig, "initial_frame": int(np.argmax(np.nan_to_num(d["cp_MB"])))}


def _trial_page(scenes, labels, group_dims, title, out):
    """A page of analysed trials (_trial_scene), one group each."""
    n = len(scenes[0]["time"])
    lo, hi = _view_box(np.concatenate([np.concatenate([s["shapes_mm"].reshape(-1, 3), s["edges_mm"].reshape(-1, 3)])
                                       for s in scenes]))
    blobs = _Blobs()
    signals = [{"key": k, "label": label, "unit": unit} for k, label, unit, _ in TRIAL_SIGNALS]
    colour_by = [{"label": "|M_B|", "kind": "signal", "signal": 0, "abs": True},
                 {"label": "F_T", "kind": "signal", "signal": 1, "abs": True},
                 {"label": "contact state", "kind": "state"}]
    meta = _base_meta("trial", f"{title}, contact-point mode ({TRIAL_ANGLE_NOTE})", scenes[0]["time"], ["whisker"],
                      signals, colour_by, group_dims[0]["label"] if group_dims else "", "")
    for scene, label in zip(scenes, labels):
        q, offset, step = _quantise(scene["shapes_mm"], lo, hi)
        meta["groups"].append({
            "label": label, "shapes": blobs.add(q, delta=True), "state": blobs.add(scene["state"]),
            "signals": blobs.add(scene["signals"].astype(np.float32)),
            "contact": blobs.add(scene["contact_mm"][None].astype(np.float32)),
            "edges": blobs.add(np.broadcast_to(scene["edges_mm"], (n,) + scene["edges_mm"].shape).astype(np.float32)),
            "ranges": _ranges(scene["signals"])})
        meta["quant"] = {"offset": offset.tolist(), "step": step.tolist()}
    if group_dims:
        meta["group_dims"] = group_dims
    meta["edges"] = int(scenes[0]["edges_mm"].shape[0])
    meta["initial_frame"] = scenes[0]["initial_frame"]
    _set_view(meta, lo, hi, direction=[0.2, -0.5, 0.85])
    return _write_page(meta, blobs, out)


def write_trial_view(trial_path, results, out):
    """Writes the viewer page of a `vibrissa trial` run: the trial file and its output directory (frames.h5);
    see _trial_scene."""
    from . import read_trial
    scene = _trial_scene(read_trial(str(trial_path)), results)
    title = f"vibrissa trial: {pathlib.Path(trial_path).name}, {len(scene['time'])} frames"
    return _trial_page([scene], ["trial"], None, title, out)


# ---- solve ------------------------------------------------------------------------------------------------
SOLVE_SIGNALS = [  # key of a solve's whisker_frame (normal_force: the result's), label, unit, scale from SI
    ("MB", "M_B", "µN·m", 1e6), ("FT", "F_T", "mN", 1e3), ("MD", "M_D", "deg", 180 / np.pi),
    ("FD", "F_D", "deg", 180 / np.pi), ("normal_force", "F_N", "mN", 1e3)]
SOLVE_ARROWS = [  # drawn vectors of a solve: label, colour (figures/style.py)
    {"label": "contact force on the whisker", "colour": "#D55E00"},
    {"label": "force at the base", "colour": "#0072B2"},
    {"label": "moment at the base", "colour": "#009E73"}]
ARROW_FRACTION = 0.3  # the longest arrow of a page is this fraction of the whisker's length
CONTACT_STATES = {"free": 0, "contact": 1, "pushed_past": 2}
EDGE_MODES = ("point", "edge", "frictional_edge")


def _solve_record(result, case=None):
    """What the page needs of one solve: a result dict (the JSON of `vibrissa solve`) and, when known, its case
    (a load_case source): shape, rest shape, contact point, vectors, signals, the object or edge."""
    from .case import load_case
    frame = result.get("whisker_frame") or {}
    shape = np.asarray(result.get("shape_W") or [], float).reshape(-1, 3)
    rec = {"shape": shape, "rest": None, "edge": None, "object": result.get("object"),
           "state": CONTACT_STATES.get(result.get("contact_state"), 0),
           "contact": np.asarray(result.get("contact_point_W") or [np.nan] * 3, float),
           "force": np.asarray(result.get("force_W") or [0.0] * 3, float),
           "moment": np.asarray(result.get("moment_W") or [0.0] * 3, float),
           "signals": [np.nan if (frame.get(k) if k != "normal_force" else result.get(k)) is None else
                       float(frame.get(k) if k != "normal_force" else result.get(k)) for k, *_ in SOLVE_SIGNALS],
           "result": result}
    if case is not None:
        c = case if hasattr(case, "whisker") and hasattr(case, "solve") else load_case(case)
        rec["rest"] = np.asarray(c.whisker.rest_nodes_W)
        load = c.load
        if c.mode in EDGE_MODES:
            direction = load.get("direction", load.get("edge_direction"))
            if direction is not None:
                rec["edge"] = (np.asarray(load["point"], float), np.asarray(direction, float))
        if rec["object"] is None and c.mode == "object":
            rec["object"] = load.get("object")
    if not len(shape):
        raise ValueError("the solve result has no shape_W (solve with options.compute_shape true)")
    return rec


def _fmt(value, unit):
    if value is None or (isinstance(value, float) and not np.isfinite(value)):
        return "—"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "(" + ", ".join(f"{float(v):.4g}" for v in value) + f") {unit}"
    if isinstance(value, (bool, str)):
        return str(value)
    return f"{float(value):.4g} {unit}".rstrip()


def _solve_table(result):
    """Rows [label, text] of a solve's numbers (SI, as in the result file)."""
    f = result.get("whisker_frame") or {}
    rows = [("status", result.get("status")), ("contact state", result.get("contact_state")),
            ("friction", result.get("friction")), ("|F| at the contact", _fmt(result.get("force_magnitude"), "N")),
            ("arc length s", _fmt(result.get("arc_length"), "m")),
            ("contact point p_W", _fmt(result.get("contact_point_W"), "m")),
            ("force_W (on the whisker)", _fmt(result.get("force_W"), "N")),
            ("moment_W (about the base)", _fmt(result.get("moment_W"), "N·m")),
            ("base force, whisker frame", _fmt(f.get("force"), "N")),
            ("base moment, whisker frame", _fmt(f.get("moment"), "N·m")),
            ("F_T / M_B", f"{_fmt(f.get('FT'), 'N')} / {_fmt(f.get('MB'), 'N·m')}"),
            ("F_D / M_D", f"{_fmt(None if f.get('FD') is None else np.degrees(f['FD']), '°')} / "
                          f"{_fmt(None if f.get('MD') is None else np.degrees(f['MD']), '°')}"),
            ("normal / edge force", f"{_fmt(result.get('normal_force'), 'N')} / {_fmt(result.get('edge_force'), 'N')}"),
            ("residual, iterations", f"{_fmt(result.get('residual'), '')}, {result.get('iterations')}")]
    return [[k, str(v)] for k, v in rows]


def _solve_object_meshes(records, blobs):
    """The solve's object (world frame, a pose of its own) as a page object: the first record's description.
    Meshes need their vertices: read from the description's file when it is there."""
    description = next((r["object"] for r in records if r["object"]), None)
    if description is None:
        return [], None
    vertices = None
    if description.get("type") == "mesh":
        if "vertices" in description:
            vertices = np.asarray(description["vertices"], float)
        else:
            return [], f"mesh object not drawn (its vertices are not in the result: {description.get('file')})"
    meshes = _object_meshes([(description, vertices)], blobs)
    return meshes, None


def _solve_group(records, blobs, quant, arrow_scale, table=None):
    """One page group of solves: frame i is records[i] (one whisker)."""
    n = len(records)
    shapes_mm = np.stack([_resample(r["shape"][None])[0] for r in records])[:, None] * 1e3
    q, _, _ = _quantise(shapes_mm, *quant)
    sig = np.array([[[r["signals"][k] * SOLVE_SIGNALS[k][3] for r in records]] for k in range(len(SOLVE_SIGNALS))])
    base = np.stack([r["shape"][0] for r in records]) * 1e3
    contact = np.stack([r["contact"] for r in records]) * 1e3
    force = np.stack([r["force"] for r in records])
    moment = np.stack([r["moment"] for r in records])
    arrows = np.zeros((3, n, 6))
    for a, (origin, vec, scale) in enumerate([(contact, force, arrow_scale[0]), (base, force, arrow_scale[0]),
                                              (base, moment, arrow_scale[1])]):
        arrows[a, :, :3] = origin
        arrows[a, :, 3:] = vec * scale
    arrows = np.where(np.isfinite(arrows), arrows, 0.0)
    group = {"shapes": blobs.add(q, delta=True),
             "state": blobs.add(np.array([[r["state"] for r in records]], np.uint8)),
             "signals": blobs.add(sig.astype(np.float32)), "contact": blobs.add(contact[None].astype(np.float32)),
             "edges": blobs.add(np.stack([_edge_segment(r) for r in records]).astype(np.float32)),
             "arrows": blobs.add(arrows.astype(np.float32)), "ranges": _ranges(sig),
             "table": table if table is not None else [_solve_table(r["result"]) for r in records]}
    if records[0]["rest"] is not None:
        group["rest"] = blobs.add((_resample(records[0]["rest"][None]) * 1e3).astype(np.float32))
    return group


def _edge_segment(record):
    """[1][2][3] the record's edge (an infinite line) as a segment of +-EDGE_HALF_LENGTH_M [mm]; NaN without."""
    if record["edge"] is None:
        return np.full((1, 2, 3), np.nan)
    point, direction = record["edge"]
    d = direction / np.linalg.norm(direction)
    return np.stack([point - EDGE_HALF_LENGTH_M * d, point + EDGE_HALF_LENGTH_M * d])[None] * 1e3


def _solve_page(records_by_group, group_dims, times, frame_axis, title, out):
    """Writes a page of solves: records_by_group[g][frame]; times: the frame axis values."""
    _figures_on_path()
    blobs = _Blobs()
    flat = [r for group in records_by_group for r in group]
    length_mm = max(float(np.sum(np.linalg.norm(np.diff(r["shape"], axis=0), axis=1))) for r in flat) * 1e3
    f_max = max([float(np.linalg.norm(r["force"])) for r in flat if np.isfinite(r["force"]).all()] + [0.0])
    m_max = max([float(np.linalg.norm(r["moment"])) for r in flat if np.isfinite(r["moment"]).all()] + [0.0])
    arrow_scale = (ARROW_FRACTION * length_mm / f_max if f_max > 0 else 0.0,
                   ARROW_FRACTION * length_mm / m_max if m_max > 0 else 0.0)
    points = [r["shape"] * 1e3 for r in flat] + [r["rest"] * 1e3 for r in flat if r["rest"] is not None]
    points += [_edge_segment(r).reshape(-1, 3) for r in flat if r["edge"] is not None]
    points += [(r["contact"] * 1e3)[None] for r in flat]
    lo, hi = _view_box(np.concatenate(points))
    pad = 0.15 * max(float(np.max(hi - lo)), 1e-3)
    lo, hi = lo - pad, hi + pad  # room for the arrows
    any_edge = any(r["edge"] is not None for r in flat)
    meta = _base_meta("solve", title, times, ["whisker"],
                      [{"key": k, "label": label, "unit": unit} for k, label, unit, _ in SOLVE_SIGNALS],
                      [{"label": "|M_B|", "kind": "signal", "signal": 0, "abs": True},
                       {"label": "F_T", "kind": "signal", "signal": 1, "abs": True},
                       {"label": "contact state", "kind": "state"}], group_dims[0]["label"] if group_dims else "", "")
    meta["groups"] = []
    for g, records in enumerate(records_by_group):
        group = _solve_group(records, blobs, (lo, hi), arrow_scale)
        if not any_edge:
            group.pop("edges")
        group["label"] = " ".join(d["values"][i] for d, i in zip(group_dims, np.unravel_index(
            g, [len(d["values"]) for d in group_dims]))) if group_dims else "solve"
        meta["groups"].append(group)
    meta["group_dims"] = group_dims or [{"label": "", "values": ["solve"]}]
    meta["edges"] = 1 if any_edge else 0
    meta["objects"], note = _solve_object_meshes(flat, blobs)
    if meta["objects"]:  # the object is fixed in the world: the identity pose at every frame
        identity = np.tile(np.array([1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0], np.float32), (len(times), 1))
        for group in meta["groups"]:
            group["object_poses"] = blobs.add(identity)
    if note:
        meta["title"] += f" ({note})"
    meta["arrows"] = SOLVE_ARROWS
    meta["arrow_scale"] = {"force_mm_per_N": arrow_scale[0], "moment_mm_per_N_m": arrow_scale[1]}
    meta["rest"] = flat[0]["rest"] is not None
    meta["frame_axis"] = frame_axis
    meta["quant"] = {"offset": (0.5 * (lo + hi)).tolist(), "step": np.maximum((hi - lo) / 16000.0, 1e-9).tolist()}
    meta["initial_frame"] = 0
    _set_view(meta, lo, hi, direction=[0.35, -0.6, 0.72])
    return _write_page(meta, blobs, out)


def write_solve_view(result, out, case=None):
    """Writes the viewer page of one solve: `result` the result of ``vibrissa solve`` (a file, a dict, or a
    Solution), `case` (a case file, dict or Case; optional) adds the rest shape and the edge of edge modes. The
    deflected whisker, the object or edge, the contact point, the contact force at the contact point, and the
    force and moment at the base (arrows scaled to 30 % of the whisker's length; the numbers in the table)."""
    if hasattr(result, "shape_W") and hasattr(result, "whisker_frame"):  # a Solution
        from . import _vibrissa
        result = json.loads(_vibrissa.solution_to_json(result))
    elif not isinstance(result, dict):
        path = pathlib.Path(result)
        try:
            result = json.loads(path.read_text())
        except json.JSONDecodeError as error:
            raise ValueError(f"{path}: not a solve result (JSON: {error})") from None
        if case is None:
            case = _case_beside(path)
    if not isinstance(result, dict) or "status" not in result or "shape_W" not in result:
        raise ValueError("not a `vibrissa solve` result (no 'status' and 'shape_W')")
    rec = _solve_record(result, case)
    title = f"vibrissa solve: {result['status']}, {result.get('contact_state', '')}"
    return _solve_page([[rec]], [], [0.0], None, title, out)


def _case_beside(result_path):
    """The case of a result file when it is known: `case.json` beside it (`vibrissa solve case.json -o
    out.json` in one folder), else None."""
    candidate = result_path.with_name("case.json")
    if candidate.is_file() and candidate != result_path:
        return candidate
    return None


# ---- sweep ------------------------------------------------------------------------------------------------
MAX_SWEEP_ARRAY_GROUPS = 64  # array runs x pitches simulated again for one page (--runs picks fewer)


def _sweep_source(source):
    """(dataset, spec, folder or None) of a sweep: an xarray.Dataset of vibrissa.sweep, its folder or sweep.nc."""
    import xarray as xr
    if hasattr(source, "attrs") and hasattr(source, "data_vars"):
        ds = source
        folder = pathlib.Path(ds.encoding["source"]).parent if ds.encoding.get("source") else None
    else:
        path = pathlib.Path(source)
        nc = path / "sweep.nc" if path.is_dir() else path
        if not nc.is_file():
            raise ValueError(f"{nc} not found: the sweep is not finished (run the same `vibrissa sweep` again to "
                             "resume it)")
        ds, folder = xr.open_dataset(nc, engine="h5netcdf"), nc.parent
    if ds.attrs.get("format") != "vibrissa-sweep":
        raise ValueError(f"{source}: not a vibrissa sweep (attribute format is {ds.attrs.get('format')!r})")
    return ds, json.loads(ds.attrs["sweep"]), folder


def _label(value):
    return f"{value:g}" if isinstance(value, float) else str(value)


def _sweep_dims(spec, runs):
    """The page's group dimensions of a sweep: one per grid parameter, or 'run' for a list of runs."""
    if spec.get("grid"):
        return [{"label": path, "values": [_label(v) for v in values]} for path, values in spec["grid"].items()]
    return [{"label": "run", "values": [", ".join(f"{p}={_label(v)}" for p, v in r.items()) or "base" for r in runs]}]


def write_sweep_view(source, out, runs=None):
    """Writes the viewer page of a sweep (docs/sweeps.md): `source` its folder, sweep.nc or the Dataset
    ``vibrissa.sweep`` returned. A list for each swept parameter picks the run by its grid coordinates.
    Array sweeps: every whisker of the picked run and head pitch over time, simulated again from the run's
    configuration (sweep.json) as `vibrissa view` does for an array; `runs` (flat run indices) limits the
    runs included (default all, at most MAX_SWEEP_ARRAY_GROUPS runs x pitches). Solve sweeps: the slider
    steps through the last parameter's values (a list of runs: through the runs), the other parameters are
    lists; each run solved again for its shape (a solve result keeps none). Trial sweeps: the picked run's
    trial (synthesised or read again) analysed again, drawn as `vibrissa view TRIAL` draws it (at most
    MAX_SWEEP_ARRAY_GROUPS runs; `runs` picks fewer)."""
    from .sweeps import _plan
    from .sweep_runs import configured
    ds, spec, _ = _sweep_source(source)
    kind = spec["kind"]
    _, run_list = _plan(spec.get("grid"), spec.get("runs"))
    if kind == "solve":
        return _write_solve_sweep(ds, spec, run_list, out)
    if kind not in ("array", "trial"):
        raise ValueError(f"a sweep of {kind!r} runs cannot be shown (array, trial and solve sweeps can)")
    picked = list(range(len(run_list))) if runs is None else sorted(set(int(r) for r in runs))
    if any(not 0 <= r < len(run_list) for r in picked):
        raise ValueError(f"runs: indices must be in [0, {len(run_list) - 1}], got {runs}")
    if kind == "trial":
        return _write_trial_sweep(spec, run_list, picked, runs is not None, out)
    n_pitch = ds.sizes.get("pitch", 1)
    if len(picked) * n_pitch > MAX_SWEEP_ARRAY_GROUPS:
        raise ValueError(f"{len(picked)} runs x {n_pitch} head pitches is more than the {MAX_SWEEP_ARRAY_GROUPS} "
                         "array simulations one page holds: pick runs with --runs (flat indices, the first "
                         "parameter slowest)")
    dims = _sweep_dims(spec, run_list)
    shape = [len(d["values"]) for d in dims]
    if runs is not None:  # one list of the picked runs instead of the grid
        dims = [{"label": "run", "values": [", ".join(f"{p}={_label(v)}" for p, v in run_list[r].items()) or "base"
                                            for r in picked]}]
    _figures_on_path()
    blobs = _Blobs()
    signals = [{"key": k, "label": label, "unit": unit} for k, label, unit, _ in ARRAY_SIGNALS]
    sims = []
    for r in picked:
        config = configured(spec["base"], run_list[r])
        index = dict(zip([d for d in (spec.get("grid") or {"run": None})], np.unravel_index(r, shape)))
        for p in range(n_pitch):
            pitch_rad = float(ds["pitch"].values[p]) if "pitch" in ds.coords else 0.0
            result = _array_result(config, pitch_rad, ds.sizes.get("time"))
            sims.append((r, index, p, result))
    names = [n.decode() if isinstance(n, bytes) else n for n in sims[0][3].datasets["whisker"]]
    times = np.asarray(sims[0][3].datasets["time"])
    shapes = np.stack([_resample(s[3].datasets["render/deflected"]) * 1e3 for s in sims])
    lo, hi = _view_box(shapes)
    groups = []
    for (r, index, p, result), shapes_mm in zip(sims, shapes):
        d = result.datasets
        where = {k: int(v) for k, v in index.items() if k in ds.dims}
        if "pitch" in ds.dims:
            where["pitch"] = p
        sig = []
        for key, _, _, scale in ARRAY_SIGNALS:  # the sweep's values where it kept them, else the simulation's
            values = ds[key].isel(where).values if key in ds else np.asarray(d[key][0])
            sig.append(np.asarray(values, float) * scale)
        sig = np.stack(sig)
        state = ds["state"].isel(where).values if "state" in ds else np.asarray(d["state"][0])
        contact = ds["contact_point_W"].isel(where).values if "contact_point_W" in ds else np.asarray(d["contact_point_W"][0])
        q, offset, step = _quantise(shapes_mm, lo, hi)
        group = {"label": f"run {r}, {np.degrees(ds['pitch'].values[p]):+.1f}°" if "pitch" in ds.coords else f"run {r}",
                 "shapes": blobs.add(q, delta=True), "state": blobs.add(np.asarray(state).astype(np.uint8)),
                 "signals": blobs.add(sig.astype(np.float32)),
                 "contact": blobs.add((np.asarray(contact) * 1e3).astype(np.float32)),
                 "edges": blobs.add((d["render/edges"] * 1e3).astype(np.float32)), "ranges": _ranges(sig)}
        groups.append(group)
        meta_quant = {"offset": offset.tolist(), "step": step.tolist()}
    if "pitch" in ds.coords and n_pitch > 1:
        dims = dims + [{"label": "head pitch", "values": [f"{np.degrees(v):+.1f}°" for v in ds["pitch"].values]}]
    meta = _base_meta("array", "", times, names, signals,
                      [{"label": "|M_B|", "kind": "signal", "signal": 0, "abs": True},
                       {"label": "F_T", "kind": "signal", "signal": 1, "abs": True},
                       {"label": "contact state", "kind": "state"}], dims[0]["label"], "whisker")
    meta["groups"], meta["group_dims"], meta["quant"] = groups, dims, meta_quant
    meta["edges"] = int(sims[0][3].datasets["render/edges"].shape[1])
    # The objects of every run (a sweep may change them: a radius, a mesh): each distinct one drawn once, placed
    # by its pose in the groups of the runs that have it and collapsed (a zero matrix) in the others.
    distinct, placed = [], []
    for sim in sims:
        where = []
        for description, vertices in _result_objects(sim[3]):
            key = json.dumps(description, sort_keys=True) + (str(np.asarray(vertices).tobytes()) if vertices is not None else "")
            keys = [json.dumps(d, sort_keys=True) + (str(np.asarray(v).tobytes()) if v is not None else "") for d, v in distinct]
            if key not in keys:
                distinct.append((description, vertices))
                keys.append(key)
            where.append(keys.index(key))
        placed.append(where)
    if distinct:
        meta["objects"] = _object_meshes(distinct, blobs)
        for group, sim, where in zip(groups, sims, placed):
            own = _poses_mm(sim[3].datasets["render/object_poses"])  # [frame][own object][12]
            poses = np.zeros((own.shape[0], len(distinct), 12), np.float32)
            poses[:, where] = own
            group["object_poses"] = blobs.add(poses)
    state0 = np.asarray(sims[0][3].datasets["state"][0])
    meta["initial_frame"] = int(np.argmax((state0 == 1).sum(axis=0)))
    meta["initial_whisker"] = int(np.argmax(np.nan_to_num(np.asarray(sims[0][3].datasets["MB"][0])).max(axis=1)))
    _set_view(meta, lo, hi, direction=[0.55, -0.45, 0.7])
    meta["title"] = (f"vibrissa sweep of {len(run_list)} array runs ({len(picked)} shown): {len(names)} whiskers × "
                     f"{len(times)} frames")
    return _write_page(meta, blobs, out)


def _write_trial_sweep(spec, run_list, picked, subset, out):
    import tempfile
    from .pipeline import analyze_trial, read_trial, synthesize_trial
    from .sweep_runs import configured
    if len(picked) > MAX_SWEEP_ARRAY_GROUPS:
        raise ValueError(f"{len(picked)} trial runs are more than the {MAX_SWEEP_ARRAY_GROUPS} one page holds: pick "
                         "runs with --runs (flat indices, the first parameter slowest)")
    dims = _sweep_dims(spec, run_list)
    if subset:
        dims = [{"label": "run", "values": [", ".join(f"{p}={_label(v)}" for p, v in run_list[r].items()) or "base"
                                            for r in picked]}]
    scenes = []
    for r in picked:  # each run as sweep_runs._trial_run makes it, analysed again (deterministic: the same numbers)
        config = configured(spec["base"], run_list[r])
        trial = read_trial(str(config["trial"])) if config.get("trial") is not None else \
            synthesize_trial(**config.get("synth", {}))
        with tempfile.TemporaryDirectory(prefix="vibrissa-view-") as tmp:
            analyze_trial(trial, **config.get("analysis", {})).write(tmp)
            scenes.append(_trial_scene(trial, tmp))
    if any(len(s["time"]) != len(scenes[0]["time"]) for s in scenes):
        raise ValueError("the sweep's trials differ in frame count: show them one by one (--runs)")
    title = f"vibrissa sweep of {len(run_list)} trials ({len(picked)} shown), {len(scenes[0]['time'])} frames"
    return _trial_page(scenes, [f"run {r}" for r in picked], dims, title, out)


def _array_result(config, pitch_rad, frames):
    """The array run of `config` at one head pitch with every frame rendered (an ArrayResult)."""
    from .pipeline import simulate_array
    c = json.loads(json.dumps(config))
    c.setdefault("head", {})["pitches_deg"] = [float(np.degrees(pitch_rad))]
    c["output"] = {"render_count": int(frames or c.get("time", {}).get("frames", 2)), "render_pitch_index": 0}
    return simulate_array(c, threads=1)


def _result_objects(result):
    """The objects of an ArrayResult, as object_outline.load_objects reads them from array.h5."""
    import tempfile
    import h5py
    import object_outline
    with tempfile.TemporaryDirectory(prefix="vibrissa-view-") as tmp:
        result.write(tmp)
        with h5py.File(pathlib.Path(tmp) / "array.h5", "r") as f:
            return object_outline.load_objects(f)


def _write_solve_sweep(ds, spec, run_list, out):
    from .case import load_case
    from .sweep_runs import configured
    grid = spec.get("grid")
    if grid:
        paths = list(grid)
        last, others = paths[-1], paths[:-1]
        shape = [len(grid[p]) for p in paths]
        values = grid[last]
        numeric = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)
        times = [float(v) for v in values] if numeric else list(range(len(values)))
        dims = [{"label": p, "values": [_label(v) for v in grid[p]]} for p in others]
        axis_label, unit = last, ds[last].attrs.get("units", "") if last in ds else ""
    else:
        shape, times, dims = [len(run_list)], list(range(len(run_list))), []
        axis_label, unit = "run", ""
    span = max(abs(t) for t in times) or 1.0
    frame_axis = {"label": axis_label, "unit": "" if unit in ("1", "text") else unit, "scale": 1.0,
                  "digits": int(min(6, max(0, 3 - np.floor(np.log10(span)))))}
    n_frames = shape[-1]
    groups = []
    for g in range(len(run_list) // n_frames):
        records = []
        for i in range(n_frames):
            config = configured(spec["base"], run_list[g * n_frames + i])
            case = load_case(config)
            from . import _vibrissa
            result = json.loads(_vibrissa.solution_to_json(case.solve()))
            records.append(_solve_record(result, case))
        groups.append(records)
    title = f"vibrissa sweep of {len(run_list)} solves"
    return _solve_page(groups, dims, times, frame_axis, title, out)


def _register_accessor():
    """`dataset.vibrissa.view(path)` on the Dataset of vibrissa.sweep (and any sweep.nc opened with xarray)."""
    import xarray as xr
    if hasattr(xr.Dataset, "vibrissa"):
        return

    @xr.register_dataset_accessor("vibrissa")
    class _Accessor:
        def __init__(self, ds):
            self._ds = ds

        def view(self, path="sweep_view.html", runs=None):
            """Writes the interactive 3D viewer of this sweep (docs/viewer.md) and returns its path."""
            return write_sweep_view(self._ds, path, runs)


TRIAL_SUFFIXES = (".csv", ".h5", ".hdf5", ".mat")


def view(source, out=None, results=None, case=None, runs=None):
    """Writes the viewer page of `source` and returns its path (default: ``view.html`` beside the result):
    an ArrayResult, a ``vibrissa array`` output directory or its array.h5; a trial file analysed by
    ``vibrissa trial`` (`results`: its output directory); a ``vibrissa solve`` result file or Solution
    (`case`: its case, for the rest shape and the edge; default ``case.json`` beside the result); a sweep's
    folder, its sweep.nc or the Dataset of ``vibrissa.sweep`` (`runs`: flat indices of the array runs shown)."""
    if hasattr(source, "datasets") and hasattr(source, "config"):  # an ArrayResult: through its files
        import tempfile
        with tempfile.TemporaryDirectory(prefix="vibrissa-view-") as tmp:
            source.write(tmp)
            return write_array_view(tmp, out or "array_view.html")
    if hasattr(source, "shape_W") and hasattr(source, "whisker_frame"):  # a Solution
        return write_solve_view(source, out or "solve_view.html", case)
    if hasattr(source, "data_vars"):  # an xarray.Dataset: a sweep's
        return write_sweep_view(source, out or "sweep_view.html", runs)
    path = pathlib.Path(source)
    directory = path if path.is_dir() else path.parent
    if (directory / "array.h5").is_file() and (path.is_dir() or path.name == "array.h5"):
        return write_array_view(directory, out or directory / "view.html")
    if (path.is_dir() and (path / "sweep.json").is_file()) or (path.is_file() and path.suffix == ".nc"):
        return write_sweep_view(path, out or directory / "view.html", runs)
    if path.is_file() and path.suffix.lower() == ".json":  # a solve result
        return write_solve_view(path, out or path.with_suffix(".html"), case)
    if path.is_file() and path.suffix.lower() in TRIAL_SUFFIXES:  # a trial file, its results as `vibrissa trial` names them
        results = pathlib.Path(results) if results else path.parent / f"{path.stem}_results"
        if not (results / "frames.h5").is_file():
            raise ValueError(f"{results / 'frames.h5'} not found: run `vibrissa trial {path}` first, or give "
                             "its output directory with --results")
        return write_trial_view(path, results, out or results / "view.html")
    raise ValueError(f"{source}: not a result vibrissa can show (expected a `vibrissa array` output directory or its "
                     "array.h5, a trial file, a `vibrissa solve` result (.json), or a sweep folder or its sweep.nc: "
                     "docs/viewer.md)")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="vibrissa view", description=(
        "Write a self-contained interactive 3D viewer (one HTML file, no network) of an array result "
        "directory, an analysed trial, a solve result or a sweep (docs/viewer.md)."))
    parser.add_argument("result", help="a `vibrissa array` output directory (or its array.h5), a trial file "
                                       "analysed by `vibrissa trial`, a `vibrissa solve` result (.json), or a "
                                       "`vibrissa sweep` folder (or its sweep.nc)")
    parser.add_argument("-o", "--out", help="the HTML file to write (default: view.html in the result directory; "
                                            "a solve result: its name with .html)")
    parser.add_argument("--results", help="trial: the output directory of `vibrissa trial` (default: "
                                          "<trial name>_results next to the trial)")
    parser.add_argument("--case", help="solve: the case file solved (default: case.json beside the result); "
                                       "adds the rest shape and the edge")
    parser.add_argument("--runs", help="array or trial sweep: the runs shown, flat indices (first parameter slowest), "
                                       "e.g. 0,3,5 (default all, at most %d runs x pitches)" % MAX_SWEEP_ARRAY_GROUPS)
    args = parser.parse_args(argv)
    try:
        runs = None
        if args.runs:
            try:
                runs = [int(r) for r in args.runs.split(",")]
            except ValueError:
                raise ValueError(f"--runs must be run indices separated by commas, got {args.runs!r}") from None
        path = view(args.result, args.out, args.results, args.case, runs)
    except (OSError, ValueError, KeyError) as error:
        print(f"vibrissa view: error: {error}", file=sys.stderr)
        return 1
    print(f"vibrissa view: wrote {path} ({pathlib.Path(path).stat().st_size / 1e6:.1f} MB)")
    return 0
