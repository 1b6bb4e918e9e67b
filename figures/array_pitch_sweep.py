#!/usr/bin/python3
"""How the base signals change across the array with head pitch (spec §3.4): peak M_B per whisker and pitch
(heat map), and the number of whiskers touching / pushed past and the mean peak M_B per pitch.

usage: array_pitch_sweep.py ARRAY_H5 OUT.png [--dpi DPI]
"""
import h5py
import numpy as np
import style
from matplotlib import pyplot as plt


def load(path):
    with h5py.File(path, "r") as f:
        return dict(names=[n.decode() if isinstance(n, bytes) else n for n in f["whisker"][()]],
                    state=f["state"][()], MB=f["MB"][()], pitch=f["pitch"][()])


def build(d):
    names, state, pitch = d["names"], d["state"], np.degrees(d["pitch"])
    MB = d["MB"] * style.SCALE["µN·m"]
    contact = state == 1
    peak = np.where(contact, MB, 0.0).max(axis=2)  # [pitch][whisker]
    touching = contact.any(axis=2).sum(axis=1)
    pushed = (state == 2).any(axis=2).sum(axis=1)
    mean_peak = np.array([peak[p][contact[p].any(axis=1)].mean() if touching[p] else 0.0 for p in range(len(pitch))])
    keep = peak.max(axis=0) > 0
    # one whisker name per row at 7 pt (print size): the figure grows with the number of whiskers drawn
    height_in = max(4.2, 0.125 * int(keep.sum()) + 1.6)
    fig, (a0, a1) = plt.subplots(1, 2, figsize=(style.PAPER_WIDTH_IN, height_in),
                                 gridspec_kw={"width_ratios": [1.4, 1]})
    im = a0.imshow(peak[:, keep].T, aspect="auto", origin="lower", cmap=style.SEQUENTIAL_CMAP,
                   extent=(-0.5, len(pitch) - 0.5, -0.5, keep.sum() - 0.5))
    a0.set_xticks(range(len(pitch)), [f"{p:+.0f}" if round(p) else "0" for p in pitch])
    a0.set_yticks(range(keep.sum()), [n for n, k in zip(names, keep) if k], fontsize=7)
    a0.set_xlabel(style.label("head pitch", "deg"))
    a0.set_ylabel("whisker")
    a0.grid(False)
    a0.set_title("peak $M_B$ during contact")
    fig.colorbar(im, ax=a0, label=style.label("peak $M_B$", "µN·m"))
    c_touch, c_push, c_mb = style.OKABE_ITO["blue"], style.OKABE_ITO["vermillion"], style.OKABE_ITO["bluish_green"]
    a1.plot(pitch, touching, "o-", color=c_touch, label="whiskers touching")
    a1.plot(pitch, pushed, "s--", color=c_push, label="whiskers pushed past")
    a1.set_xlabel(style.label("head pitch", "deg"))
    a1.set_ylabel("whiskers")
    a1.set_ylim(bottom=0)
    style.integer_ticks(a1.yaxis)
    a2 = a1.twinx()
    a2.plot(pitch, mean_peak, "^:", color=c_mb, label="mean peak $M_B$ (right axis)")
    a2.set_ylabel(style.label("mean peak $M_B$", "µN·m"))
    a2.set_ylim(bottom=0)
    a2.grid(False)
    handles = a1.get_legend_handles_labels()[0] + a2.get_legend_handles_labels()[0]
    a1.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, 1.02), fontsize=7, frameon=False)
    a1.set_xticks(pitch)
    fig.suptitle("Whisker array across head pitch")
    return fig, (a0, a1, a2)


def main(argv=None):
    style.one_png_main(__doc__, load, build, argv)


if __name__ == "__main__":
    main()
