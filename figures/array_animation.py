#!/usr/bin/python3
"""Animation of the whisker array in 3D (Fig. 4a style): whiskers in contact red and thick, whiskers that
pushed past the object green, the others light grey; the object's edges black.

usage: array_animation.py ARRAY_H5 OUT.(mp4|gif)
Writes MP4 through matplotlib's FFMpegWriter (Debian ffmpeg) or GIF through PillowWriter, and a still
PNG of the frame with the most contacts next to it (OUT stem + "_frame.png").
"""
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from atomic_save import save_animation, save_figure  # noqa: E402
from matplotlib import animation  # noqa: E402

COLOURS = {0: "0.72", 1: "red", 2: "green"}
WIDTHS = {0: 0.8, 1: 2.4, 2: 1.4}


def load(path):
    with h5py.File(path, "r") as f:
        r = f["render"]
        return dict(
            frames=r["frame"][()],
            deflected=r["deflected"][()] * 1e3,
            edges=r["edges"][()] * 1e3,
            pitch_index=int(r.attrs["pitch_index"]),
            state=f["state"][()],
            time=f["time"][()],
            pitch=f["pitch"][()],
        )


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    d = load(sys.argv[1])
    out = sys.argv[2]
    if len(d["frames"]) == 0:
        print("array_animation: no rendered frames (output.render_count = 0)")
        return
    p = d["pitch_index"]
    states = d["state"][p][:, d["frames"]]  # [whisker][render]
    shapes = d["deflected"]  # [render][whisker][node][3]
    edges = d["edges"]

    fig = plt.figure(figsize=(6.4, 5.6), dpi=100)
    ax = fig.add_subplot(projection="3d")
    pts = shapes.reshape(-1, 3)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2 * 1.05
    lines = [ax.plot([], [], [], lw=0.8, color="0.7")[0] for _ in range(shapes.shape[1])]
    edge_lines = [ax.plot([], [], [], lw=2.5, color="black")[0] for _ in range(edges.shape[1])]
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel("z [mm]")
    ax.view_init(elev=35, azim=-120)
    title = ax.set_title("")

    def draw(i):
        for w, line in enumerate(lines):
            s = int(states[w, i])
            xyz = shapes[i, w]
            line.set_data(xyz[:, 0], xyz[:, 1])
            line.set_3d_properties(xyz[:, 2])
            line.set_color(COLOURS[s])
            line.set_linewidth(WIDTHS[s])
            line.set_zorder(3 if s else 1)
        for e, line in enumerate(edge_lines):
            seg = edges[i, e]
            line.set_data(seg[:, 0], seg[:, 1])
            line.set_3d_properties(seg[:, 2])
        t = d["time"][d["frames"][i]] * 1e3
        n_c = int((states[:, i] == 1).sum())
        n_p = int((states[:, i] == 2).sum())
        title.set_text(f"t = {t:5.1f} ms   pitch {np.degrees(d['pitch'][p]):+.0f}°   "
                       f"contact {n_c} (red), pushed past {n_p} (green)")
        return lines + edge_lines + [title]

    best = int(np.argmax((states == 1).sum(axis=0)))
    draw(best)
    save_figure(fig, os.path.splitext(out)[0] + "_frame.png")

    anim = animation.FuncAnimation(fig, draw, frames=len(d["frames"]), blit=False)
    if out.endswith(".mp4") and animation.FFMpegWriter.isAvailable():
        save_animation(anim, out, animation.FFMpegWriter(fps=12, bitrate=1800))
    else:
        if out.endswith(".mp4"):
            out = out[:-4] + ".gif"
            print("array_animation: ffmpeg not found, writing GIF instead")
        save_animation(anim, out, animation.PillowWriter(fps=12))
    print("wrote", out)


if __name__ == "__main__":
    main()
