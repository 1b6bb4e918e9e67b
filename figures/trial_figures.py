#!/usr/bin/env python3
"""Figures of `vibrissa trial` mirroring Huet & Hartmann 2016 Figs. 2b-f, 3a-e and 4b.

usage: trial_figures.py FRAMES.h5 SUMMARY.json OUTDIR
Reads the per-frame table written by `vibrissa trial` (group /frames) and its summary.json.
"""
import json
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from atomic_save import save_figure  # noqa: E402

CP, EDGE, FRIC = "tab:cyan", "tab:purple", "tab:orange"


def load(path):
    with h5py.File(path, "r") as f:
        g = f["frames"]
        return {k: g[k][()] for k in g.keys()}


def col(d, name):
    return d[name] if name in d else None


def fit_line(ax, x, y):
    ok = np.isfinite(x) & np.isfinite(y)
    if ok.sum() < 3:
        return
    m, b = np.polyfit(x[ok], y[ok], 1)
    lo, hi = np.nanmin(np.r_[x[ok], y[ok]]), np.nanmax(np.r_[x[ok], y[ok]])
    xs = np.array([lo, hi])
    ax.plot(xs, xs, "k-", lw=1, label="identity")
    ax.plot(xs, m * xs + b, "r-", lw=1.2, label=f"fit y = {m:.2f}x + {b:.2f}")
    ax.legend(fontsize=8)


def save(fig, out, name):
    fig.tight_layout()
    save_figure(fig, os.path.join(out, name), dpi=110)
    plt.close(fig)


def main():
    frames_path, summary_path, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    d = load(frames_path)
    with open(summary_path) as f:
        summary = json.load(f)
    t_ms = d["time"] * 1e3
    modes = [(p, c, n) for p, c, n in (("cp_", CP, "contact-point mode"), ("edge_", EDGE, "edge mode"),
                                         ("fric_", FRIC, "frictional edge mode")) if p + "s_applied" in d]

    # Fig. 2b-d: shape error, contact height, s_applied.
    fig, axes = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
    for p, c, n in modes:
        axes[0].plot(t_ms, d[p + "shape_error"] * 1e3, color=c, lw=1, label=n)
        axes[1].plot(t_ms, d[p + "height"] * 1e3, color=c, lw=1, label=n)
        axes[2].plot(t_ms, d[p + "s_applied"] * 1e3, color=c, lw=1, label=n)
    axes[0].set_ylabel("mean shape error [mm]")
    axes[0].set_title("Fig. 2b: shape error (NaN if no tracked shapes)", fontsize=9)
    axes[1].set_ylabel("contact height [mm]")
    axes[1].set_title("Fig. 2c: vertical location of contact", fontsize=9)
    axes[2].set_ylabel("s_applied [mm]")
    axes[2].set_title("Fig. 2d: arc length of contact", fontsize=9)
    axes[2].set_xlabel("time [ms]")
    axes[0].legend(fontsize=8)
    save(fig, out, "fig2bcd_shape_height_arclength.png")

    # Fig. 2e / 4b: z_error vs eqs. (6), (7).
    if "z_error" in d:
        for eq, name, title in (("z_error_eq6", "fig2e_z_error_eq6.png", "Fig. 2e: eq. (6)"),
                                ("z_error_eq7", "fig4b_z_error_eq7.png", "Fig. 4b: eq. (7)")):
            fig, ax = plt.subplots(figsize=(5, 5))
            x, y = d["z_error"] * 1e3, d[eq] * 1e3
            ax.scatter(x, y, s=6, alpha=0.3, color="k")
            fit_line(ax, x, y)
            ax.set_xlabel("measured z_error = z_edge - z_cp [mm]")
            ax.set_ylabel("predicted z_error [mm]")
            ax.set_title(title, fontsize=10)
            save(fig, out, name)

    # Fig. 2f: kinematic prediction of contact height.
    if "tracked_height" in d:
        fig, ax = plt.subplots(figsize=(5, 5))
        x, y = d["tracked_height"] * 1e3, d["kinematic_height"] * 1e3
        ax.scatter(x, y, s=6, alpha=0.3, color="k")
        fit_line(ax, x, y)
        ax.set_xlabel("tracked contact height [mm]")
        ax.set_ylabel("kinematic prediction [mm]")
        ax.set_title("Fig. 2f: non-contact kinematics projected front-on", fontsize=10)
        save(fig, out, "fig2f_kinematic_prediction.png")

    # Fig. 3a: world forces and moments.
    fig, axes = plt.subplots(6, 1, figsize=(8, 10), sharex=True)
    names = [("Fx_world", 1e3, "Fx [mN]"), ("Fy_world", 1e3, "Fy [mN]"), ("Fz_world", 1e3, "Fz [mN]"),
             ("Mx_world", 1e6, "Mx [uN m]"), ("My_world", 1e6, "My [uN m]"), ("Mz_world", 1e6, "Mz [uN m]")]
    for ax, (k, s, label) in zip(axes, names):
        for p, c, n in modes:
            ax.plot(t_ms, d[p + k] * s, color=c, lw=1, label=n)
        ax.set_ylabel(label, fontsize=8)
    axes[0].set_title("Fig. 3a: forces and moments, world frame", fontsize=10)
    axes[0].legend(fontsize=7)
    axes[-1].set_xlabel("time [ms]")
    save(fig, out, "fig3a_world_signals.png")

    # Fig. 3b: whisker-frame signals.
    fig, axes = plt.subplots(6, 1, figsize=(8, 10), sharex=True)
    names = [("Fx_B", 1e3, "Fx [mN]"), ("FT", 1e3, "F_T [mN]"), ("FD_deg", 1, "F_D [deg]"),
             ("Mx_B", 1e6, "Mx [uN m]"), ("MB", 1e6, "M_B [uN m]"), ("MD_deg", 1, "M_D [deg]")]
    for ax, (k, s, label) in zip(axes, names):
        for p, c, n in modes:
            v = d[p + k] * s
            if p != "fric_" or "cp_" + k not in d:
                ax.plot(t_ms, v, color=c, lw=1, label=n)
            else:
                ax.plot(t_ms, v, color=c, lw=0.8, ls="--", label=n)
        ax.set_ylabel(label, fontsize=8)
    axes[0].set_title("Fig. 3b: base signals, whisker-centred frame", fontsize=10)
    axes[0].legend(fontsize=7)
    axes[-1].set_xlabel("time [ms]")
    save(fig, out, "fig3b_whisker_signals.png")

    # Fig. 3c-e: friction coefficient.
    if "mu" in d:
        mu, outl, used = d["mu"], d["mu_outlier"] > 0.5, d["mu_used"] > 0.5
        fn = d["cp_normal_force"] * 1e3
        fig, axes = plt.subplots(1, 3, figsize=(14, 4))
        ax = axes[0]
        ax.plot(t_ms[used], mu[used], ".", ms=3, color="tab:blue", label="used")
        ax.plot(t_ms[outl], np.minimum(mu[outl], 3.0), ".", ms=3, color="red", label="outlier (F_N < 0.1 mN)")
        ax.set_xlabel("time [ms]")
        ax.set_ylabel("mu")
        ax.set_ylim(0, 3.1)
        ax.set_title("Fig. 3c: mu over time (>3 plotted at 3)", fontsize=10)
        ax.legend(fontsize=8)
        ax = axes[1]
        ok = np.isfinite(mu)
        ax.plot(fn[ok], np.minimum(mu[ok], 3.0), ".", ms=3, color="gray", alpha=0.5)
        fr = summary.get("friction", {})
        centers = np.array(fr.get("normal_force_bins_N", [])) * 1e3
        means = np.array([np.nan if v is None else v for v in fr.get("mu_mean_per_bin", [])], dtype=float)
        sds = np.array([np.nan if v is None else v for v in fr.get("mu_sd_per_bin", [])], dtype=float)
        if centers.size:
            ax.plot(centers, means, "-", color="tab:cyan", label="mean")
            ax.fill_between(centers, means - sds, means + sds, color="lightblue", alpha=0.5, label="± sd")
        ax.axvline(0.1, color="k", lw=1)
        ax.set_xlabel("normal force [mN]")
        ax.set_ylabel("mu")
        ax.set_ylim(0, 3.1)
        ax.set_title("Fig. 3d: mu vs normal force", fontsize=10)
        ax.legend(fontsize=8)
        ax = axes[2]
        edges = np.array(fr.get("histogram_edges", []))
        counts = np.array(fr.get("histogram_counts", []))
        if counts.size:
            ax.bar(edges[:-1], counts, width=np.diff(edges), align="edge", color="tab:blue", edgecolor="k")
        med = fr.get("median")
        if med is not None:
            ax.axvline(med, color="r", label=f"median {med:.3f}")
            ax.legend(fontsize=8)
        ax.set_xlabel("mu")
        ax.set_ylabel("frames")
        ax.set_title("Fig. 3e: histogram of mu (outliers excluded)", fontsize=10)
        save(fig, out, "fig3cde_friction.png")


if __name__ == "__main__":
    main()
