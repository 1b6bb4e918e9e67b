"""Outlines of the array's objects in a view (docs/objects.md): points on each object's surface, in the world,
projected on the view's two axes, and their convex hull drawn as a filled silhouette. The descriptions are
array.h5's /objects (SI, the shape's frame); render/object_poses place them at each rendered frame."""
import json

import numpy as np

INFINITE_HALF_LENGTH = 0.04  # infinite pegs and walls are drawn +-40 mm about their point [m]


def load_objects(f):
    """The /objects group of an array.h5: a list of (description dict, vertices or None), in object order."""
    if "objects" not in f:
        return []
    group = f["objects"]
    out = []
    for name in sorted(group.keys(), key=int):
        g = group[name]
        out.append((json.loads(g.attrs["description"]), g["vertices"][()] if "vertices" in g else None))
    return out


def _unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _frame(axis):
    a = _unit(axis)
    helper = np.array([1.0, 0, 0]) if abs(a[0]) < 0.9 else np.array([0, 1.0, 0])
    e1 = _unit(helper - helper.dot(a) * a)
    return a, e1, np.cross(a, e1)


def surface_points(description, vertices, n=48):
    """Points on the surface in the shape's frame [m]."""
    kind = description["type"]
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    if kind == "sphere":
        u, v = np.meshgrid(t, np.linspace(0, np.pi, n // 2))
        d = np.stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)], -1).reshape(-1, 3)
        return np.asarray(description["centre"]) + description["radius"] * d
    if kind == "cylinder":
        a, e1, e2 = _frame(description["axis"])
        length = description.get("length")
        z = np.array([0.0, length]) if length else np.array([-INFINITE_HALF_LENGTH, INFINITE_HALF_LENGTH])
        ring = description["radius"] * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)
        return np.concatenate([np.asarray(description["point"]) + zi * a + ring for zi in z])
    if kind == "plane":
        _, e1, e2 = _frame(description["normal"])
        s = INFINITE_HALF_LENGTH * np.array([-1, 1])
        return np.array([np.asarray(description["point"]) + x * e1 + y * e2 for x in s for y in s])
    if kind == "box":
        R = np.asarray(description["rotation"])
        h = np.asarray(description["half_extents"])
        corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * h
        return np.asarray(description["centre"]) + corners @ R.T
    if kind == "mesh" and vertices is not None:
        return vertices
    return np.zeros((0, 3))


def hull(points):
    """Convex hull of 2-D points (Andrew's monotone chain), closed."""
    p = np.unique(np.round(points, 12), axis=0)
    if len(p) < 3:
        return p
    p = p[np.lexsort((p[:, 1], p[:, 0]))]

    def half(seq):
        out = []
        for q in seq:
            while len(out) >= 2 and np.cross(out[-1] - out[-2], q - out[-2]) <= 0:
                out.pop()
            out.append(q)
        return out

    lower, upper = half(p), half(p[::-1])
    ring = np.array(lower[:-1] + upper[:-1])
    return np.vstack([ring, ring[:1]])


def outlines(objects, poses, h, v, scale):
    """Per object, the (x, y) of its silhouette in the view of world axes h, v, scaled (e.g. to mm);
    `poses`: [object][12] (R_WO row by row, p_WO) at one rendered frame."""
    out = []
    for (description, vertices), pose in zip(objects, poses):
        R = np.asarray(pose[:9], float).reshape(3, 3)
        p = np.asarray(pose[9:], float)
        world = surface_points(description, vertices) @ R.T + p
        out.append(hull(world[:, [h, v]] * scale) if len(world) else np.zeros((0, 2)))
    return out
