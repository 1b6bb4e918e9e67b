#!/usr/bin/python3
"""Base-signal traces per whisker (first head pitch): F_T, M_B, M_D, F_x and the contact state, one
coloured line per whisker that touched the object.

usage: array_traces.py ARRAY_H5 OUT.png
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
        t = f["time"][()] * 1e3
        names = [n.decode() if isinstance(n, bytes) else n for n in f["whisker"][()]]
        state = f["state"][0]
        FT = f["FT"][0] * 1e3
        MB = f["MB"][0] * 1e6
        MD = np.degrees(f["MD"][0])
        Fx = f["force_B"][0][..., 0] * 1e3
        zerr = f["z_error"][0] * 1e3
        pitch = np.degrees(f["pitch"][0])
    touched = [w for w in range(len(names)) if (state[w] == 1).any()]
    fig, axes = plt.subplots(5, 1, figsize=(8, 10), sharex=True)
    cmap = plt.get_cmap("tab20")
    for k, w in enumerate(touched):
        c = cmap(k % 20)
        on = state[w] == 1
        for ax, y in zip(axes[:4], (FT, MB, MD, Fx)):
            ax.plot(t, np.where(on, y[w], np.nan), color=c, lw=1.2, label=names[w] if ax is axes[0] else None)
        axes[4].plot(t, np.where(on, zerr[w], np.nan), color=c, lw=1.2)
    for ax, label in zip(axes, ("$F_T$ [mN]", "$M_B$ [µN·m]", "$M_D$ [deg]", "$F_x$ [mN]", "eq. (7) $z_{error}$ [mm]")):
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("time [ms]")
    axes[0].set_title(f"Base signals during contact, head pitch {pitch:+.0f}° ({len(touched)} whiskers touched)")
    if touched:
        axes[0].legend(ncol=6, fontsize=7, loc="upper left")
    fig.tight_layout()
    save_figure(fig, sys.argv[2], dpi=110)
    print("wrote", sys.argv[2])


if __name__ == "__main__":
    main()
