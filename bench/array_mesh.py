#!/usr/bin/env python3
"""`vibrissa array` against a 20,480-triangle mesh beside the same run against a peg (issue 24: the mesh run's
target is <= 3x the peg's). Writes into DIR a 3 mm sphere tessellated into 20,480 triangles (ball.ply, in mm:
an icosahedron subdivided 5 times, vertices on the sphere), the default scene's config over FRAMES frames
(peg.json: its peg at (20, -8, -3) mm) and the same with the ball there instead (mesh.json), runs both and
prints the simulation times they report and their ratio.
Usage: /usr/bin/python3 bench/array_mesh.py [--vibrissa build/bin/vibrissa] [--dir /tmp/array_mesh] [--frames 1000]"""
import argparse
import json
import pathlib
import re
import subprocess
import sys

import numpy as np


def icosphere(subdivisions: int):
    g = (1.0 + 5.0 ** 0.5) / 2.0
    vertices = [np.array(v, float) for v in [(-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0), (0, -1, g), (0, 1, g),
                                             (0, -1, -g), (0, 1, -g), (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1)]]
    vertices = [v / np.linalg.norm(v) for v in vertices]
    triangles = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
                 (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
                 (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p = vertices[a] + vertices[b]
                vertices.append(p / np.linalg.norm(p))
                middle[key] = len(vertices) - 1
            return middle[key]

        finer = []
        for a, b, c in triangles:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        triangles = finer
    return np.array(vertices), triangles


def write_ply(path: pathlib.Path, vertices, triangles) -> None:
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(vertices)}\nproperty float x\nproperty float y\n"
                f"property float z\nelement face {len(triangles)}\nproperty list uchar int vertex_indices\nend_header\n")
        for v in vertices:
            f.write("%.9f %.9f %.9f\n" % tuple(v))
        for t in triangles:
            f.write("3 %d %d %d\n" % t)


def simulated_seconds(vibrissa: str, config: pathlib.Path, out: pathlib.Path) -> float:
    run = subprocess.run([vibrissa, "array", str(config), "--no-figures", "--out", str(out)], capture_output=True,
                         text=True, check=True)
    match = re.search(r"simulated \d+ whisker-frames in ([0-9.]+) s", run.stdout + run.stderr)
    if not match:
        raise RuntimeError(f"no simulation time in the output of {config}")
    return float(match.group(1))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vibrissa", default="build/bin/vibrissa")
    parser.add_argument("--dir", default="/tmp/array_mesh")
    parser.add_argument("--frames", type=int, default=1000)
    args = parser.parse_args()
    folder = pathlib.Path(args.dir)
    folder.mkdir(parents=True, exist_ok=True)
    vertices, triangles = icosphere(5)
    write_ply(folder / "ball.ply", 3.0 * vertices, triangles)  # radius 3 mm
    base = {"time": {"start_s": 0, "end_s": 0.25 * args.frames / 1000, "frames": args.frames}}
    scenes = {
        "peg": {"type": "peg", "frame": "world", "point_mm": [20, -8, -3]},
        "mesh": {"type": "mesh", "frame": "world", "file": "ball.ply", "file_unit": "mm", "translation_mm": [20, -8, -3]},
    }
    seconds = {}
    for name, scene in scenes.items():
        config = folder / f"{name}.json"
        config.write_text(json.dumps(dict(base, objects=[scene]), indent=1))
        seconds[name] = simulated_seconds(args.vibrissa, config, folder / f"out_{name}")
    print(f"31 whiskers x {args.frames} frames: peg {seconds['peg']:.2f} s, {len(triangles)}-triangle mesh "
          f"{seconds['mesh']:.2f} s, ratio {seconds['mesh'] / seconds['peg']:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
