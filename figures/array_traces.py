#!/usr/bin/python3
"""Base-signal traces per whisker (first head pitch): F_T, M_B, M_D, F_x and the magnitude of eq. (7)
z_error while in contact, one line per whisker that touched the object, each in its own colour
(style.distinct_styles). M_D is unwrapped within each contact. z_error is drawn as |z_error|: its sign,
sgn(z_edge - z_onset), flips where edge mode's contact point passes the onset height, and the signed curve
jumps there by twice the bound (the bound itself is continuous); the panel says so.
A `vibrissa array --dynamics` file (it has tip_displacement_B): every whisker at every frame (whisking, touching
the objects or not), F_T and F_x in µN, and the tip's displacement from rest instead of z_error.

usage: array_traces.py ARRAY_H5 OUT.png [--dpi DPI]
"""
import h5py
import numpy as np
import style
from matplotlib import pyplot as plt

ROWS = (("FT", "mN", "$F_T$"), ("MB", "µN·m", "$M_B$"), ("MD", "deg", "$M_D$"), ("Fx", "mN", "$F_x$"),
        ("z_error", "mm", "eq. (7) $|z_{error}|$"))
DYNAMICS_ROWS = (("FT", "µN", "$F_T$"), ("MB", "µN·m", "$M_B$"), ("MD", "deg", "$M_D$"), ("Fx", "µN", "$F_x$"),
                 ("tip", "mm", "tip displacement"))
SCALE = dict(style.SCALE, **{"µN": 1e6})


def load(path):
    with h5py.File(path, "r") as f:
        d = dict(time=f["time"][()], names=[n.decode() if isinstance(n, bytes) else n for n in f["whisker"][()]],
                 state=f["state"][0], FT=f["FT"][0], MB=f["MB"][0], MD=f["MD"][0], Fx=f["force_B"][0][..., 0],
                 z_error=f["z_error"][0], pitch=f["pitch"][0], dynamics="tip_displacement_B" in f)
        if d["dynamics"]:
            d["tip"] = np.linalg.norm(f["tip_displacement_B"][0], axis=-1)
        return d


def build(d):
    t = d["time"] * style.SCALE["ms"]
    rows = DYNAMICS_ROWS if d["dynamics"] else ROWS
    if d["dynamics"]:  # every whisker, every frame
        touched = list(range(len(d["names"])))
    else:
        touched = [w for w in range(len(d["names"])) if (d["state"][w] == 1).any()]
    fig, axes = plt.subplots(len(rows), 1, figsize=(style.PAPER_WIDTH_IN, 8.5), sharex=True)
    styles = style.distinct_styles(len(touched))
    for k, w in enumerate(touched):
        on = np.ones_like(d["state"][w], dtype=bool) if d["dynamics"] else d["state"][w] == 1
        for ax, (name, unit, _) in zip(axes, rows):
            y = d[name][w] * SCALE[unit]
            if name == "MD":
                y = style.unwrap_deg(y, style.contact_runs(on))
            elif name == "z_error":  # the magnitude: the sign term of eq. (7) flips (docstring)
                y = np.abs(y)
            ax.plot(t, np.where(on, y, np.nan), lw=1.2, label=d["names"][w], **styles[k])
    for ax, (_, unit, quantity) in zip(axes, rows):
        ax.set_ylabel(style.label(quantity, unit))
    axes[-1].set_xlabel(style.label("time", "ms"))
    if not d["dynamics"]:
        axes[-1].set_title("magnitude of the bound; its sign, sgn($z_{edge} - z_{onset}$), is left out (it flips "
                           "where the edge-mode contact passes the onset height)", fontsize=7, loc="left")
    if d["dynamics"]:
        what = f"({len(touched)} whiskers, dynamics; {int((d['state'] == 1).any(axis=1).sum())} touched)"
    else:
        what = f"({len(touched)} whiskers touched)"
    axes[0].set_title(f"Base signals {'while whisking' if d['dynamics'] else 'during contact'}, head pitch "
                      f"{np.degrees(d['pitch']):+.0f}° {what}", pad=8 + 12 * ((len(touched) + 7) // 8))
    if touched:
        axes[0].legend(ncol=8, fontsize=7, loc="lower left", bbox_to_anchor=(0, 1.02), frameon=False)
    return fig, axes


def main(argv=None):
    style.one_png_main(__doc__, load, build, argv)


if __name__ == "__main__":
    main()
