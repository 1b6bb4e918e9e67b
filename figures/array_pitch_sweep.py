#!/usr/bin/python3
"""How the base signals change across the array with head pitch (spec §3.4): peak M_B per whisker and pitch
(heat map), and the number of whiskers touching / pushed past and the mean peak M_B per pitch.

usage: array_pitch_sweep.py ARRAY_H5 OUT.png
"""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from atomic_save import save_figure  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with h5py.File(sys.argv[1], "r") as f:
        names = [n.decode() if isinstance(n, bytes) else n for n in f["whisker"][()]]
        state = f["state"][()]
        MB = f["MB"][()] * 1e6
        pitch = np.degrees(f["pitch"][()])
    contact = state == 1
    peak = np.where(contact, MB, 0.0).max(axis=2)  # [pitch][whisker]
    touching = contact.any(axis=2).sum(axis=1)
    pushed = (state == 2).any(axis=2).sum(axis=1)
    mean_peak = np.array([peak[p][contact[p].any(axis=1)].mean() if touching[p] else 0.0 for p in range(len(pitch))])
    keep = peak.max(axis=0) > 0
    fig, (a0, a1) = plt.subplots(1, 2, figsize=(11, 5), gridspec_kw={"width_ratios": [2, 1]})
    im = a0.imshow(peak[:, keep].T, aspect="auto", origin="lower", cmap="magma",
                   extent=(-0.5, len(pitch) - 0.5, -0.5, keep.sum() - 0.5))
    a0.set_xticks(range(len(pitch)), [f"{p:+.0f}" for p in pitch])
    a0.set_yticks(range(keep.sum()), [n for n, k in zip(names, keep) if k], fontsize=7)
    a0.set_xlabel("head pitch [deg]")
    a0.set_title("peak $M_B$ during contact [µN·m]")
    fig.colorbar(im, ax=a0)
    a1.plot(pitch, touching, "o-", label="whiskers touching")
    a1.plot(pitch, pushed, "s-", color="green", label="pushed past")
    a1.set_xlabel("head pitch [deg]")
    a1.set_ylabel("whiskers")
    a2 = a1.twinx()
    a2.plot(pitch, mean_peak, "^-", color="red", label="mean peak $M_B$")
    a2.set_ylabel("mean peak $M_B$ [µN·m]", color="red")
    a1.legend(loc="upper left", fontsize=8)
    a1.set_title("array summary per pitch")
    fig.tight_layout()
    save_figure(fig, sys.argv[2], dpi=110)
    print("wrote", sys.argv[2])


if __name__ == "__main__":
    main()
