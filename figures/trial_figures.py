#!/usr/bin/env python3
"""Figures of `vibrissa trial` mirroring Huet & Hartmann 2016 Figs. 2b-f, 3a-e and 4b.

usage: trial_figures.py FRAMES.h5 SUMMARY.json OUTDIR [--window START_S,END_S | --whisk N] [--dpi DPI]
                        [--all] [--jobs N] [--start-on-stdin]

Reads the per-frame table written by `vibrissa trial` (frames.h5, one dataset per column) and its
summary.json. Fit lines and their numbers are those of summary.json (never refitted here). Time series (Figs. 2b-d, 3a, 3b) show a time
window: --window START_S,END_S (seconds, trial clock), --whisk N (contact period N, from 1), or by default the
whole trial if it lasts at most OVERVIEW_MAX_S, else WINDOW_S from the first contact. fig3b_per_whisk.png
overlays every whisk of the trial, aligned at contact onset. F_D and M_D are unwrapped within each whisk.
fig3a_world_signals.png and fig2bcd_shape_height_arclength.png are drawn with --all only (EXTRA_FIGURES).
"""
import json
import os
import sys

import h5py
import numpy as np
import style
from matplotlib import pyplot as plt
from matplotlib.collections import LineCollection

OVERVIEW_MAX_S = 2.0  # longer trials: time series in a window, plus the per-whisk overlay
WINDOW_S = 1.0
WHISK_PAD = 0.25  # --whisk: margin on each side, as a fraction of the contact period's duration

# Rows of the time-series figures: (column without mode prefix, unit, label).
SHAPE_ROWS = (("shape_error", "mm", "mean shape error"), ("height", "mm", "contact height"),
              ("s_applied", "mm", "$s_{applied}$"))
WORLD_ROWS = (("Fx_world", "mN", "$F_x$"), ("Fy_world", "mN", "$F_y$"), ("Fz_world", "mN", "$F_z$"),
              ("Mx_world", "µN·m", "$M_x$"), ("My_world", "µN·m", "$M_y$"), ("Mz_world", "µN·m", "$M_z$"))
WHISKER_ROWS = (("Fx_B", "mN", "$F_x$"), ("FT", "mN", "$F_T$"), ("FD", "deg", "$F_D$"),
                ("Mx_B", "µN·m", "$M_x$"), ("MB", "µN·m", "$M_B$"), ("MD", "deg", "$M_D$"))
OVERLAY_ROWS = (("FT", "mN", "$F_T$"), ("MB", "µN·m", "$M_B$"), ("FD", "deg", "$F_D$"),
                ("MD", "deg", "$M_D$"))
ANGLES = ("FD", "MD")  # [rad] in frames.h5, drawn in degrees
TITLE_MAX_CHARS = 90  # of a 9 pt title line across a figure 7 in wide


def load(path):
    with h5py.File(path, "r") as f:
        return {k: f[k][()] for k in f.keys()}


def present_modes(d):
    return [m for m in style.MODES if m["prefix"] + "s_applied" in d]


# F_D and M_D are directions of the force and moment in the base's plane: undefined where these vanish. At
# contact onset and release they are tiny, and the direction of a near-zero vector swings freely (a jump of
# ~30° per frame at onset, a plunge at release). Such frames are masked (not drawn): the first and last two
# frames of every contact period (`period_edge`, also left out of the paper's analyses, spec §2.4) and frames
# whose magnitude (F_T for F_D, M_B for M_D) is below ANGLE_MIN_FRACTION of its peak in that period.
ANGLE_MAGNITUDE = {"FD": "FT", "MD": "MB"}
ANGLE_MIN_FRACTION = 0.05
ANGLE_MASK_NOTE = "F_D, M_D masked where undefined: first/last 2 frames of a contact, |F_T| or |M_B| < 5 % of its peak"


def angle_mask(d, prefix, name):
    """True where the angle column `name` (FD or MD) of a mode is defined well enough to draw."""
    mag = np.abs(d[prefix + ANGLE_MAGNITUDE[name]])
    ok = d["period_edge"] < 0.5
    for p in np.unique(d["period"][d["period"] >= 0]):
        idx = d["period"] == p
        peak = np.nanmax(mag[idx]) if np.isfinite(mag[idx]).any() else 0.0
        ok[idx] &= mag[idx] >= ANGLE_MIN_FRACTION * peak
    return ok


def mode_signals(d, modes, name, unit):
    """{mode prefix: column `name` of that mode in display units} for the modes that have it; angles masked
    where undefined (angle_mask), unwrapped per contact period, the modes after the first one drawn on the
    first one's branch (its unwrapped angles computed once, as the reference of the others)."""
    out, ref = {}, None
    for m in modes:
        column = m["prefix"] + name
        if column not in d:
            continue
        if name not in ANGLES:
            out[m["prefix"]] = d[column] * style.SCALE[unit]
            continue
        masked = np.where(angle_mask(d, m["prefix"], name), np.degrees(d[column]), np.nan)
        out[m["prefix"]] = style.unwrap_deg(masked, d["period"], reference=ref)
        if m is modes[0]:
            ref = out[m["prefix"]]
    return out


def signal(d, modes, mode, name, unit):
    """mode_signals of one mode (drawn on the branch of modes[0])."""
    return mode_signals(d, [mode] if mode is modes[0] else [modes[0], mode], name, unit)[mode["prefix"]]


# --- time windows ---------------------------------------------------------------------------------------

def parse_window(text):
    try:
        start, end = (float(v) for v in text.split(","))
    except ValueError:
        sys.exit(f"trial_figures: --window must be START_S,END_S in seconds, got '{text}'")
    if not start < end:
        sys.exit(f"trial_figures: --window start must be before end, got '{text}'")
    return start, end


def select_window(d, window=None, whisk=None):
    """(start, end, description) of the time series to draw [s]."""
    t = d["time"]
    if whisk is not None:
        periods = int(np.max(d["period"])) + 1
        if not 1 <= whisk <= periods:
            sys.exit(f"trial_figures: --whisk {whisk}: the trial has {periods} contact periods (1..{periods})")
        tp = t[d["period"] == whisk - 1]
        pad = WHISK_PAD * max(tp[-1] - tp[0], 0.01)
        return tp[0] - pad, tp[-1] + pad, f"whisk {whisk} of {periods}"
    if window is not None:
        if window[1] < t[0] or window[0] > t[-1]:
            sys.exit(f"trial_figures: --window {window[0]},{window[1]} s lies outside the trial "
                     f"({t[0]:g}-{t[-1]:g} s)")
        return window[0], window[1], f"t = {window[0]:g}–{window[1]:g} s"
    if t[-1] - t[0] <= OVERVIEW_MAX_S:
        return t[0], t[-1], "whole trial"
    contact = t[d["period"] >= 0]
    start = max(t[0], (contact[0] if contact.size else t[0]) - 0.05 * WINDOW_S)
    return start, start + WINDOW_S, f"t = {start:.2f}–{start + WINDOW_S:.2f} s (first {WINDOW_S:g} s of contact)"


def time_axis(start, end):
    """Unit in which to show times of the span [start, end] s."""
    return "ms" if end - start <= 5.0 else "s"


# --- drawing pieces -------------------------------------------------------------------------------------

def mode_legend(fig, modes):
    style.legend_below(fig, [plt.Line2D([], [], **style.mode_line(m)) for m in modes])


def time_series(d, modes, rows, window, title):
    start, end, what = window
    unit = time_axis(start, end)
    sel = (d["time"] >= start) & (d["time"] <= end)
    t = d["time"][sel] * style.SCALE[unit]
    fig, axes = plt.subplots(len(rows), 1, figsize=(style.PAPER_WIDTH_IN, 1.45 * len(rows) + 0.9), sharex=True)
    # the title's lines: title and span (on two lines when one would not fit 7 in), and the note on masked angles
    lines = [f"{title} — {what}"] if len(title) + len(what) <= TITLE_MAX_CHARS else [title, what]
    if any(name in ANGLES for name, _, _ in rows):
        lines.append(f"({ANGLE_MASK_NOTE})")
    style.fixed_layout(fig, top_in=0.2 + 0.17 * len(lines), hspace=0.18)
    for ax, (name, u, quantity) in zip(axes, rows):
        drawn = False
        ys = mode_signals(d, modes, name, u)
        for m in modes:
            if m["prefix"] in ys:
                y = ys[m["prefix"]][sel]
                ax.plot(t, y, **style.mode_line(m))
                drawn |= bool(np.isfinite(y).any())
        if not drawn:
            ax.text(0.5, 0.5, "no data in this span" + (" (the trial has no tracked shapes)"
                                                        if name == "shape_error" else ""),
                    transform=ax.transAxes, ha="center", va="center", color=style.GREY)
            ax.set_yticks([])
        ax.set_ylabel(style.label(quantity, u))
    axes[-1].set_xlabel(style.label("time", unit))
    axes[-1].set_xlim(start * style.SCALE[unit], end * style.SCALE[unit])
    fig.suptitle("\n".join(lines), fontsize=9)
    mode_legend(fig, modes)
    return fig


def fit_text(name, fit):
    sign = "+" if fit["intercept"] >= 0 else "−"
    return (f"{name}: y = {fit['slope']:.3f}x {sign} {abs(fit['intercept']) * style.SCALE['mm']:.3f} mm\n"
            f"$r^2$ = {fit['r2']:.3f}, about identity {fit['r2_identity']:.3f}, n = {fit['points']}")


def draw_fit(ax, fit, xlim, name, **line):
    """The line y = slope·x + intercept of a summary.json fit (SI) across xlim [mm]; returns the Line2D."""
    xs = np.asarray(xlim, dtype=float)
    ys = fit["slope"] * xs + fit["intercept"] * style.SCALE["mm"]
    (ln,) = ax.plot(xs, ys, label=fit_text(name, fit), **line)
    ln.set_gid("fit")
    return ln


def scatter_fit(x, y, used, fits, labels, title):
    """Fig. 2e/2f/4b: predicted vs measured [mm] with the summary's fit(s) and the identity line; axes span
    the data. `used` marks the points the fit used; the others are drawn as excluded. A fit that is None
    is left out."""
    # fixed margins (no tight-layout passes): a square axes, the legend (up to seven lines) in the 1.9 in below it
    width = 0.6 * style.PAPER_WIDTH_IN
    top = 0.35 + 0.17 * title.count("\n")
    fig, ax = plt.subplots(figsize=(width, width - 0.85 + top + 1.9))
    style.fixed_layout(fig, left_in=0.7, right_in=0.15, top_in=top, bottom_in=1.9, legend_in=0.0)
    ok = np.isfinite(x) & np.isfinite(y)
    ax.scatter(x[ok & used], y[ok & used], s=7, alpha=0.45, lw=0, color=style.DATA["color"],
               marker=style.DATA["marker"], label=f"frames in the fit ({int((ok & used).sum())})", gid="used")
    if (ok & ~used).any():
        ax.scatter(x[ok & ~used], y[ok & ~used], s=12, lw=0.7, color=style.EXCLUDED["color"],
                   marker=style.EXCLUDED["marker"], label=f"not fitted: first/last 2 frames of a contact "
                   f"({int((ok & ~used).sum())})", gid="excluded")
    # one scale on both axes, so that the identity line is the diagonal and slopes read true
    xlim = ylim = style.data_limits(x[ok], y[ok])
    ax.plot(xlim, xlim, label="identity", **style.IDENTITY)
    second = dict(style.FIT, color=style.OKABE_ITO["bluish_green"], ls=(0, (1, 1)), lw=1.8)
    for fit, name, line in zip(fits, labels, (style.FIT, second)):
        if fit:
            draw_fit(ax, fit, xlim, name, **line)
    ax.set_xlim(xlim)
    ax.set_ylim(ylim)
    ax.set_aspect("equal", adjustable="box")
    ax.set_title(title)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), fontsize=7, frameon=False)
    return fig, ax


def z_error_figure(d, summary, eq, title):
    zs = (summary.get("z_error") or {}).get(eq) or {}
    outliers = zs.get("outliers", 0)
    fits, labels = [zs.get("all")], ["fit"]
    if outliers:  # else the same fit
        fits.append(zs.get("without_iqr_outliers"))
        labels.append(f"fit without the {outliers} IQR outliers")
    fig, ax = scatter_fit(d["z_error"] * style.SCALE["mm"], d["z_error_" + eq] * style.SCALE["mm"],
                          d["period_edge"] < 0.5, fits, labels, title)
    ax.set_xlabel(style.label("measured $z_{error} = z_{edge} - z_{cp}$", "mm"))
    ax.set_ylabel(style.label(f"$z_{{error}}$ predicted by eq. ({eq[2:]})", "mm"))
    return fig


def kinematic_figure(d, summary):
    fit = (summary.get("kinematic_prediction") or {}).get("fit")
    fig, ax = scatter_fit(d["tracked_height"] * style.SCALE["mm"], d["kinematic_height"] * style.SCALE["mm"],
                          d["period"] >= 0, (fit,), ("fit",),
                          "Fig. 2f: contact height predicted\nfrom non-contact kinematics")
    ax.set_xlabel(style.label("tracked contact height", "mm"))
    ax.set_ylabel(style.label("kinematic prediction", "mm"))
    return fig


def per_whisk_figure(d, modes):
    """Every whisk of the trial overlaid, time from its first contact frame (the full-trial overview)."""
    periods = int(np.max(d["period"])) + 1
    fig, axes = plt.subplots(2, 2, figsize=(style.PAPER_WIDTH_IN, 5.6), sharex=True)
    style.fixed_layout(fig, top_in=0.55, bottom_in=0.55, hspace=0.12, wspace=0.28)
    axes = axes.ravel()
    alpha = float(np.clip(6.0 / max(periods, 1), 0.12, 0.8))
    starts = [np.flatnonzero(d["period"] == p) for p in range(periods)]
    for ax, (name, unit, quantity) in zip(axes, OVERLAY_ROWS):
        vs = mode_signals(d, modes, name, unit)
        for m in modes:
            v = vs[m["prefix"]]
            # one LineCollection per mode and panel (not a Line2D per whisk): drawn in one pass
            segments = [np.column_stack([(d["time"][idx] - d["time"][idx[0]]) * style.SCALE["ms"], v[idx]])
                        for idx in starts if idx.size]
            ax.add_collection(LineCollection(segments, colors=m["color"], linestyles=m["ls"], linewidths=m["lw"] * 0.6,
                                             alpha=alpha, zorder=m["zorder"]))
        ax.autoscale_view()
        ax.set_ylabel(style.label(quantity, unit))
    for ax in axes[2:]:
        ax.set_xlabel(style.label("time since contact onset", "ms"))
    fig.suptitle(f"Fig. 3b per whisk: all {periods} contact periods overlaid, aligned at contact onset\n"
                 f"({ANGLE_MASK_NOTE})", fontsize=8)
    mode_legend(fig, modes)
    return fig


def friction_figure(d, summary, window):
    """Fig. 3c over the time series' span; Figs. 3d, 3e over the whole trial (the summary's analysis)."""
    start, end, what = window
    t = d["time"]
    sel = (t >= start) & (t <= end)
    mu, outl, used = d["mu"], (d["mu_outlier"] > 0.5) & sel, (d["mu_used"] > 0.5) & sel
    fr = summary.get("friction") or {}
    unit = time_axis(start, end)
    fig, axes = plt.subplots(1, 3, figsize=(style.PAPER_WIDTH_IN, 2.8))
    style.fixed_layout(fig, left_in=0.6, right_in=0.3, top_in=0.5, bottom_in=0.45, legend_in=0.0, wspace=0.5)
    ax = axes[0]
    ax.plot(t[used] * style.SCALE[unit], mu[used], ls="none", marker="o", ms=2, color=style.OKABE_ITO["blue"],
            label="used")
    ax.plot(t[outl] * style.SCALE[unit], np.minimum(mu[outl], 3.0), ls="none", marker="x", ms=3, mew=0.6,
            color=style.OKABE_ITO["vermillion"], label="outlier ($F_N$ < 0.1 mN)")
    ax.set_xlabel(style.label("time", unit))
    ax.set_ylabel("μ")
    ax.set_ylim(0, 3.1)
    ax.set_xlim(start * style.SCALE[unit], end * style.SCALE[unit])
    ax.set_title(f"Fig. 3c: μ (> 3 drawn at 3)\n{what}")
    ax.legend(loc="upper right")
    ax = axes[1]
    fn = d["cp_normal_force"] * style.SCALE["mN"]
    ok = np.isfinite(mu) & np.isfinite(fn)
    ax.plot(fn[ok], np.minimum(mu[ok], 3.0), ls="none", marker="o", ms=2, color=style.GREY, label="frames")
    centers = np.array(fr.get("normal_force_bins_N", []), dtype=float) * style.SCALE["mN"]
    means = np.array([np.nan if v is None else v for v in fr.get("mu_mean_per_bin", [])], dtype=float)
    sds = np.array([np.nan if v is None else v for v in fr.get("mu_sd_per_bin", [])], dtype=float)
    if centers.size:
        ax.plot(centers, means, color=style.OKABE_ITO["sky_blue"], lw=2, label="mean per bin")
        ax.fill_between(centers, means - sds, means + sds, color=style.OKABE_ITO["sky_blue"], alpha=0.3, lw=0,
                        label="± sd")
    ax.axvline(0.1, **style.IDENTITY, label="0.1 mN")
    ax.set_xlim(0, max(style.data_limits(fn[ok])[1], 0.11))  # the 0.1 mN threshold stays in view
    ax.set_ylim(0, 3.1)
    ax.set_xlabel(style.label("normal force $F_N$", "mN"))
    ax.set_ylabel("μ")
    ax.set_title("Fig. 3d: μ vs normal force\nwhole trial")
    ax.legend(loc="upper right")
    ax = axes[2]
    # Binned over the span of the used values (summary.json's histogram is fixed at 0-3 in 0.1 steps, one
    # bar when mu is well defined): 25 bins between the 0.5th and 99.5th percentiles (values beyond clipped to them).
    all_used = d["mu_used"] > 0.5
    mu_used = mu[all_used & np.isfinite(mu)]
    if mu_used.size:
        lo, hi = np.percentile(mu_used, [0.5, 99.5])
        if not hi > lo:
            lo, hi = lo - 0.01, hi + 0.01
        width = (hi - lo) / 25
        edges = np.linspace(lo - width, hi + width, 28)  # an empty-looking bin either side: no bar on the frame
        counts, _ = np.histogram(np.clip(mu_used, lo, hi), bins=edges)
        ax.bar(edges[:-1], counts, width=np.diff(edges), align="edge", color=style.OKABE_ITO["blue"],
               edgecolor="white", lw=0.5, label=f"frames used ({mu_used.size})")
        ax.set_xlim(edges[0], edges[-1])
    if fr.get("median") is not None:
        ax.axvline(fr["median"], color=style.OKABE_ITO["vermillion"], ls="--", lw=1.5,
                   label=f"median {fr['median']:.3f}")
    style.integer_ticks(ax.yaxis)
    ax.set_xlabel("μ")
    ax.set_ylabel("frames")
    ax.set_title("Fig. 3e: μ, outliers excluded\nwhole trial")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper right")
    else:  # no frame passed the normal-force threshold: say so instead of an empty legend box
        ax.text(0.5, 0.5, "no frame with\n$F_N$ ≥ 0.1 mN:\nμ not estimated",
                transform=ax.transAxes, ha="center", va="center", fontsize=8)
    return fig


# Drawn only when asked for (`vibrissa trial --all-figures`, `--all` here, TrialResult.figures(all_figures=True)):
# the world-frame signals and the shape/height/arc-length series, two of the three slowest figures, so that the
# default set is drawn in about the time the trial takes to analyse (docs/performance.md).
EXTRA_FIGURES = ("fig3a_world_signals.png", "fig2bcd_shape_height_arclength.png")


def builders(d, summary, window=None, whisk=None, all_figures=True):
    """{file name: function drawing that Figure} of every figure the data allow (drawn in parallel by main);
    without `all_figures`, those of EXTRA_FIGURES are left out."""
    modes = present_modes(d)
    span = select_window(d, window, whisk)
    # slowest first (save_all's processes take them in this order)
    figs = {
        "fig3b_whisker_signals.png": lambda: time_series(d, modes, WHISKER_ROWS, span, "Fig. 3b: whisker frame"),
        "fig3a_world_signals.png": lambda: time_series(d, modes, WORLD_ROWS, span, "Fig. 3a: world frame"),
    }
    if (d["period"] >= 0).any():
        figs["fig3b_per_whisk.png"] = lambda: per_whisk_figure(d, modes)
    if "mu" in d:
        figs["fig3cde_friction.png"] = lambda: friction_figure(d, summary, span)
    figs["fig2bcd_shape_height_arclength.png"] = lambda: time_series(
        d, modes, SHAPE_ROWS, span, "Figs. 2b–d: shape error, contact height, arc length of contact")
    if "z_error" in d:
        figs["fig2e_z_error_eq6.png"] = lambda: z_error_figure(d, summary, "eq6", "Fig. 2e: eq. (6), contact-point mode")
        figs["fig4b_z_error_eq7.png"] = lambda: z_error_figure(d, summary, "eq7", "Fig. 4b: eq. (7), edge mode only")
    if "tracked_height" in d and np.isfinite(d["kinematic_height"]).any():
        figs["fig2f_kinematic_prediction.png"] = lambda: kinematic_figure(d, summary)
    if not all_figures:
        figs = {name: draw for name, draw in figs.items() if name not in EXTRA_FIGURES}
    return figs


def build(d, summary, window=None, whisk=None):
    """{file name: Figure} of every figure the data allow."""
    return {name: draw() for name, draw in builders(d, summary, window, whisk).items()}


def main(argv=None):
    parser = style.parser(__doc__)
    parser.add_argument("frames_h5")
    parser.add_argument("summary_json")
    parser.add_argument("outdir")
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--window", type=parse_window, help="START_S,END_S: time series over this window [s]")
    group.add_argument("--whisk", type=int, help="time series over contact period N (from 1)")
    parser.add_argument("--jobs", type=int, default=0,
                        help="processes drawing figures side by side (default: one per CPU)")
    parser.add_argument("--all", action="store_true",
                        help="also draw " + " and ".join(EXTRA_FIGURES) + " (left out by default: slower)")
    parser.add_argument("--start-on-stdin", action="store_true",
                        help="wait for the line 'go' on standard input before reading the data (anything else, "
                             "or the end of input, exits drawing nothing): `vibrissa trial` starts this script "
                             "before it solves, so that Python's start-up and imports overlap the solve")
    args = parser.parse_args(argv)
    style.apply()
    if args.start_on_stdin:
        try:
            go = sys.stdin.readline().strip() == "go"
        except KeyboardInterrupt:  # Ctrl-C while vibrissa trial was solving: it reports the interruption
            sys.exit(130)
        if not go:
            return
    d = load(args.frames_h5)
    with open(args.summary_json) as f:
        summary = json.load(f)
    style.save_all(builders(d, summary, args.window, args.whisk, all_figures=args.all), args.outdir, dpi=args.dpi, jobs=args.jobs)


if __name__ == "__main__":
    main()
    # The figures are written (by the processes save_all waited for): leave without tearing down the modules,
    # which takes ~0.05 s of CPU with matplotlib loaded and only delays the caller.
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)
