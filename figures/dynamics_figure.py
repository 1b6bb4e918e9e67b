"""Figure of a `vibrissa dynamics` run (docs/dynamics.md): whisker shapes over time (top view in the whisker's
rest plane), the tip's displacement and the base signals.

    /usr/bin/python3 figures/dynamics_figure.py OUT_DIR [FIGURE.png]

Reads OUT_DIR/dynamics.h5 (xarray, as written by `vibrissa dynamics` or DynamicsResult.write) and saves
OUT_DIR/dynamics.png unless another path is given.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from atomic_save import replacing  # noqa: E402


def main(out_dir, figure=None):
    ds = xr.open_dataset(f"{out_dir}/dynamics.h5")
    t_ms = ds.time.values * 1e3
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    ax = axes[0]
    if "nodes_W" in ds:
        nodes = ds.nodes_W.values  # (time, node, component)
        base = nodes[0, 0]
        picks = np.linspace(0, len(t_ms) - 1, 9).astype(int)
        colors = plt.cm.viridis(np.linspace(0, 1, len(picks)))
        for c, i in zip(colors, picks):
            p = (nodes[i] - base) * 1e3
            ax.plot(p[:, 0], p[:, 1], color=c, lw=1.2, label=f"{t_ms[i]:.1f} ms")
        ax.set_aspect("equal")
        ax.set_xlabel("x_W − base [mm]")
        ax.set_ylabel("y_W − base [mm]")
        ax.set_title("shapes (world x–y)")
        ax.legend(fontsize=7, loc="best")
    ax = axes[1]
    for comp, name in zip(("x", "y", "z"), ("tip_x_B", "tip_y_B", "tip_z_B")):
        ax.plot(t_ms, ds[name].values * 1e3, label=f"tip {comp} (B)")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("tip displacement from rest [mm]")
    ax.set_title("tip, whisker frame")
    ax.legend(fontsize=8)
    ax = axes[2]
    ax.plot(t_ms, ds.My_B.values * 1e6, label="My (B)")
    ax.plot(t_ms, ds.Mz_B.values * 1e6, label="Mz (B)")
    ax.plot(t_ms, ds.Mx_B.values * 1e6, label="Mx (B, twist)")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("moment on the follicle [µN·m]")
    ax.set_title("base moment")
    ax.legend(fontsize=8)
    fig.suptitle(f"vibrissa dynamics: {out_dir} ({ds.attrs.get('status', '')})")
    fig.tight_layout()
    path = figure or f"{out_dir}/dynamics.png"
    with replacing(path) as tmp:
        fig.savefig(tmp, dpi=110)
    print(path)


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    main(*sys.argv[1:])
