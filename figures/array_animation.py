#!/usr/bin/python3
"""Animation of the whisker array (Fig. 4a style) in two orthographic views side by side: from above (top)
and from the side, so one can tell whether a whisker passes the object. States by colour, line style and
width (see style.STATES; readable in greyscale): free, in contact (with the contact point marked), pushed past;
the object in black.

usage: array_animation.py ARRAY_H5 OUT.(mp4|gif) [--fps FPS] [--dpi DPI]  (DPI: the still and the video)
Draws every rendered frame of array.h5 (group /render; how many is `vibrissa array --frames N`, i.e. the
config's output.render_count). Writes MP4 through matplotlib's FFMpegWriter (Debian ffmpeg) or GIF through
PillowWriter, and a still PNG of the frame with the most contacts next to it (OUT stem + "_frame.png").
"""
import os

import h5py
import numpy as np
import object_outline
import style
from atomic_save import save_animation, save_figure
from matplotlib import animation
from matplotlib import pyplot as plt

DEFAULT_FPS = 12
# (horizontal, vertical) world axes of each view, and the axis names (head frame at rest = world).
VIEWS = (("top view (from above)", 1, 0), ("side view (from the right)", 1, 2))
AXIS_NAMES = ("x, lateral", "y, rostral", "z, dorsal")


def load(path):
    with h5py.File(path, "r") as f:
        r = f["render"]
        return dict(
            frames=r["frame"][()],
            deflected=r["deflected"][()] * style.SCALE["mm"],
            edges=r["edges"][()] * style.SCALE["mm"],
            objects=object_outline.load_objects(f),
            object_poses=r["object_poses"][()] if "object_poses" in r else np.zeros((len(r["frame"]), 0, 12)),
            pitch_index=int(r.attrs["pitch_index"]),
            state=f["state"][()],
            contact=f["contact_point_W"][()] * style.SCALE["mm"],
            time=f["time"][()],
            pitch=f["pitch"][()],
        )


def legend_handles():
    handles = [plt.Line2D([], [], color=s["color"], ls=s["ls"], lw=s["lw"], label=s["name"],
                          marker="o" if k == 1 else None, ms=4) for k, s in style.STATES.items()]
    handles.append(plt.Line2D([], [], label="object", marker="o", ms=4, **style.OBJECT))
    return handles


class ArrayAnimation:
    """The figure and its artists; draw(i) shows rendered frame i."""

    def __init__(self, d):
        self.d = d
        p = d["pitch_index"]
        self.states = d["state"][p][:, d["frames"]]  # [whisker][render]
        self.contact = d["contact"][p][:, d["frames"]]  # [whisker][render][3]
        shapes = d["deflected"]  # [render][whisker][node][3]
        pts = shapes.reshape(-1, 3)  # the whiskers set the ranges; a long object runs off the axes
        pts = pts[np.isfinite(pts).all(axis=1)]
        self.fig, self.axes = plt.subplots(1, 2, figsize=(style.PAPER_WIDTH_IN, 3.9))
        self.lines, self.edge_lines, self.markers, self.object_patches = [], [], [], []
        for ax, (name, h, v) in zip(self.axes, VIEWS):
            ax.set_title(name)
            ax.set_xlabel(style.label(AXIS_NAMES[h], "mm"))
            ax.set_ylabel(style.label(AXIS_NAMES[v], "mm"))
            ax.set_xlim(style.data_limits(pts[:, h], pad=0.04))
            ax.set_ylim(style.data_limits(pts[:, v], pad=0.04))
            ax.set_aspect("equal", adjustable="box")
            self.lines.append([ax.plot([], [])[0] for _ in range(shapes.shape[1])])
            self.edge_lines.append([ax.plot([], [], marker="o", ms=4, zorder=5, **style.OBJECT)[0]
                                    for _ in range(d["edges"].shape[1])])
            self.object_patches.append([ax.fill([], [], fc=style.OBJECT["color"], alpha=0.25, ec=style.OBJECT["color"],
                                                lw=0.8, zorder=4)[0] for _ in d["objects"]])
            self.markers.append(ax.plot([], [], ls="none", marker="o", ms=4, mec="white", mew=0.5, zorder=6,
                                        color=style.STATES[1]["color"])[0])
        self.fig.legend(handles=legend_handles(), loc="lower center", ncol=4, frameon=False)
        self.suptitle = self.fig.suptitle("")
        self.fig.tight_layout(rect=(0, 0.07, 1, 0.95))

    def draw(self, i):
        d, states = self.d, self.states
        shapes, edges = d["deflected"][i], d["edges"][i]
        for k, (_, h, v) in enumerate(VIEWS):
            for w, line in enumerate(self.lines[k]):
                s = style.STATES[int(states[w, i])]
                line.set_data(shapes[w][:, h], shapes[w][:, v])
                line.set(color=s["color"], ls=s["ls"], lw=s["lw"], zorder=s["zorder"])
            for e, line in enumerate(self.edge_lines[k]):
                line.set_data(edges[e][:, h], edges[e][:, v])
            shapes_2d = object_outline.outlines(d["objects"], d["object_poses"][i], h, v, style.SCALE["mm"])
            for patch, xy in zip(self.object_patches[k], shapes_2d):
                patch.set_xy(xy if len(xy) else np.zeros((1, 2)))
            touching = states[:, i] == 1
            self.markers[k].set_data(self.contact[touching, i, h], self.contact[touching, i, v])
        t = d["time"][d["frames"][i]] * style.SCALE["ms"]
        n_c, n_p = int((states[:, i] == 1).sum()), int((states[:, i] == 2).sum())
        pitch = np.degrees(d["pitch"][d["pitch_index"]])
        self.suptitle.set_text(f"Whisker array, head pitch {pitch:+.0f}°: t = {t:5.1f} ms, {n_c} in contact, "
                               f"{n_p} pushed past (frame {i + 1}/{len(d['frames'])})")
        return ([a for group in self.lines + self.edge_lines + self.object_patches for a in group] + self.markers +
                [self.suptitle])

    def busiest_frame(self):
        return int(np.argmax((self.states == 1).sum(axis=0)))


def main(argv=None):
    parser = style.parser(__doc__)
    parser.add_argument("array_h5")
    parser.add_argument("out")
    parser.add_argument("--fps", type=float, default=DEFAULT_FPS, help=f"frames per second (default {DEFAULT_FPS})")
    args = parser.parse_args(argv)
    if args.fps <= 0:
        parser.error(f"--fps must be positive, got {args.fps:g}")
    style.apply()
    d = load(args.array_h5)
    out = args.out
    if len(d["frames"]) == 0:
        print("array_animation: no rendered frames (output.render_count = 0)")
        return
    plt.rcParams["axes.grid"] = False
    anim_fig = ArrayAnimation(d)
    anim_fig.draw(anim_fig.busiest_frame())
    # the still keeps the animation's layout (no tight bounding box)
    save_figure(anim_fig.fig, os.path.splitext(out)[0] + "_frame.png", dpi=args.dpi, bbox_inches=None)

    anim_fig.fig.set_dpi(args.dpi)  # the video frames: same pixels as the still
    anim = animation.FuncAnimation(anim_fig.fig, anim_fig.draw, frames=len(d["frames"]), blit=False)
    if out.endswith(".mp4") and animation.FFMpegWriter.isAvailable():
        save_animation(anim, out, animation.FFMpegWriter(fps=args.fps, bitrate=2400))
    else:
        if out.endswith(".mp4"):
            out = out[:-4] + ".gif"
            print("array_animation: ffmpeg not found, writing GIF instead")
        save_animation(anim, out, animation.PillowWriter(fps=args.fps))
    print("wrote", out)


if __name__ == "__main__":
    main()
