"""The one place for how vibrissa's figures look: palette, line styles, quantity labels with units, paper
sizes, integer ticks for counts, angle unwrapping and saving. Every script in figures/ draws through it.

Colours are the Okabe–Ito palette (Okabe & Ito 2008, "Color Universal Design"), safe for the common forms of
colour blindness; every series that shares an axis with another also differs in line style, width or marker,
so the figures stay readable in greyscale print. Data are SI inside; SCALE and UNIT convert for display.
"""
import argparse
import gc
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from atomic_save import save_figure  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

# Okabe–Ito, in the published order.
OKABE_ITO = {
    "black": "#000000",
    "orange": "#E69F00",
    "sky_blue": "#56B4E9",
    "bluish_green": "#009E73",
    "yellow": "#F0E442",
    "blue": "#0072B2",
    "vermillion": "#D55E00",
    "reddish_purple": "#CC79A7",
}
GREY = "#BBBBBB"  # context (non-data) elements: free whiskers, excluded points
SEQUENTIAL_CMAP = "cividis"  # heat maps: perceptually uniform, monotonic in greyscale, CVD-safe

# Simulation modes of `vibrissa trial` (paper Fig. 2/3: contact-point cyan, edge purple). Contact-point mode
# is drawn first and widest, the others on top of it with dashes, so coinciding lines stay visible.
MODES = (
    dict(prefix="cp_", key="contact_point", name="contact-point mode",
         color=OKABE_ITO["sky_blue"], ls="-", lw=2.4, marker="o", zorder=2),
    dict(prefix="edge_", key="edge", name="edge mode",
         color=OKABE_ITO["reddish_purple"], ls="-.", lw=1.3, marker="s", zorder=3),
    dict(prefix="fric_", key="frictional_edge", name="frictional edge mode",
         color=OKABE_ITO["vermillion"], ls=(0, (4, 2)), lw=1.1, marker="^", zorder=4),
)

# Series of a scatter plot with its fit (Figs. 2e, 2f, 4b, 3c).
DATA = dict(color=OKABE_ITO["blue"], marker="o")
EXCLUDED = dict(color=GREY, marker="x")
FIT = dict(color=OKABE_ITO["vermillion"], ls="-", lw=1.6)
IDENTITY = dict(color=OKABE_ITO["black"], ls="--", lw=1.0)

# Contact states of `vibrissa array` (state 0 free, 1 contact, 2 pushed past). Greyscale: free light and
# thin, contact mid-dark, thick and solid with a filled marker at the contact point, pushed past darkest
# and dashed.
STATES = {
    0: dict(name="free", color=GREY, ls="-", lw=0.7, zorder=1),
    1: dict(name="in contact", color=OKABE_ITO["vermillion"], ls="-", lw=2.4, zorder=3),
    2: dict(name="pushed past", color=OKABE_ITO["blue"], ls=(0, (3, 1.5)), lw=1.6, zorder=2),
}
OBJECT = dict(color=OKABE_ITO["black"], lw=2.5)

# Display units: value_shown = value_SI * SCALE[unit].
SCALE = {"mN": 1e3, "µN·m": 1e6, "mm": 1e3, "ms": 1e3, "s": 1.0, "deg": 180.0 / np.pi, "": 1.0}

PAPER_WIDTH_IN = 7.0  # a two-column journal figure
DEFAULT_DPI = 150


def label(quantity, unit=""):
    """Axis label "quantity [unit]" (quantities in mathtext where they are symbols, e.g. "$M_B$")."""
    return f"{quantity} [{unit}]" if unit else quantity


def mode_line(mode):
    """Line2D keyword arguments of a simulation mode (an entry of MODES)."""
    return dict(color=mode["color"], ls=mode["ls"], lw=mode["lw"], zorder=mode["zorder"], label=mode["name"])


def series_styles():
    """Colour and line-style pairs for many series of equal rank (one per whisker): the seven Okabe–Ito
    colours, then the same colours with other dashes, so neighbours differ in greyscale too."""
    colours = [c for k, c in OKABE_ITO.items() if k != "yellow"]  # yellow is invisible on white
    dashes = ["-", "--", ":", "-."]
    return [dict(color=c, ls=d) for d in dashes for c in colours]


def distinct_styles(n):
    """n series that each need their own colour (one per whisker): the Okabe–Ito colours up to 7, else the 20
    colours of matplotlib's tab20 (its ten darker shades first, then the lighter ones), each also with its own
    line style of four in turn so that neighbours differ in greyscale; past 20 the colours repeat with another
    dash pattern."""
    if n <= 7:
        return series_styles()[:n]
    tab20 = plt.get_cmap("tab20").colors
    colours = list(tab20[0::2]) + list(tab20[1::2])
    dashes = ["-", "--", "-.", ":"]
    return [dict(color=colours[k % 20], ls=dashes[(k + k // 20) % 4]) for k in range(n)]


def apply():
    """Matplotlib defaults for paper figures (sizes in points, readable at 7 in wide)."""
    plt.rcParams.update({
        "font.size": 9, "axes.titlesize": 10, "axes.labelsize": 9, "legend.fontsize": 8,
        "xtick.labelsize": 8, "ytick.labelsize": 8, "axes.grid": True, "grid.alpha": 0.25,
        "axes.prop_cycle": matplotlib.cycler(color=[c for k, c in OKABE_ITO.items() if k != "yellow"]),
        "legend.framealpha": 0.85,
        # titles at a fixed height above the axes: with the default (None) every draw measures each axes'
        # tick labels to lift the title over them (~20 % of a figure's drawing time); no figure here has
        # ticks on top
        "axes.titley": 1.0,
    })


def legend_below(fig, handles, ncol=None):
    """One legend for all panels, centred below the figure (kept in the PNG by the tight bounding box; with
    fixed_layout at the bottom edge, in the space it keeps)."""
    if getattr(fig, "vibrissa_fixed_layout", False):
        return fig.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, 0.0), frameon=False,
                          ncol=ncol or len(handles))
    return fig.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, 0.0), frameon=False,
                      ncol=ncol or len(handles))


def fixed_layout(fig, left_in=0.8, right_in=0.15, top_in=0.6, bottom_in=0.5, legend_in=0.35, hspace=None,
                 wspace=None):
    """Margins given in inches instead of computed: save() then skips tight_layout and the tight bounding box,
    which measure every text of the figure twice (about half of the drawing time of a six-panel figure).
    `legend_in` is kept free below the axes for legend_below(fig, ..., inside=True)."""
    w, h = fig.get_size_inches()
    fig.set_size_inches(w, h + legend_in)
    h += legend_in
    fig.subplots_adjust(left=left_in / w, right=1 - right_in / w, top=1 - top_in / h,
                        bottom=(bottom_in + legend_in) / h, hspace=hspace, wspace=wspace)
    fig.vibrissa_fixed_layout = True
    return fig


def integer_ticks(axis):
    """Tick a count axis (ax.xaxis / ax.yaxis) at integers only."""
    axis.set_major_locator(MaxNLocator(integer=True))


def data_limits(*arrays, pad=0.05):
    """(lo, hi) spanning the finite values of all arrays, padded by `pad` of the span on each side."""
    values = np.concatenate([np.ravel(np.asarray(a, dtype=float)) for a in arrays])
    values = values[np.isfinite(values)]
    if values.size == 0:
        return -1.0, 1.0
    lo, hi = float(values.min()), float(values.max())
    margin = pad * (hi - lo) if hi > lo else max(abs(lo), 1.0) * pad
    return lo - margin, hi + margin


def unwrap_deg(values, groups, reference=None):
    """Angles [deg] unwrapped within each group (e.g. a contact period), so they do not jump at ±180°.

    `groups` gives each sample's group (< 0: none, left as is). Each group is unwrapped from its first
    finite sample over its finite samples, then shifted by a multiple of 360° so that its median lies in
    (−180°, 180°] — or, given `reference` (angles of the same samples, already unwrapped), is nearest to the
    median of `reference` over the group, so that two modes of one quantity are drawn on the same branch."""
    values = np.asarray(values, dtype=float)
    groups = np.asarray(groups)
    out = values.copy()
    for g in np.unique(groups[groups >= 0]):
        idx = np.flatnonzero((groups == g) & np.isfinite(values))
        if idx.size == 0:
            continue
        run = np.degrees(np.unwrap(np.radians(values[idx])))
        target = 0.0
        if reference is not None:
            ref = np.asarray(reference, dtype=float)[idx]
            if np.isfinite(ref).any():
                target = float(np.nanmedian(ref))
        out[idx] = run - 360.0 * np.round((np.median(run) - target) / 360.0)
    return out


def contact_runs(mask):
    """Group index per sample: 0, 1, ... for each run of True in `mask`, -1 elsewhere."""
    mask = np.asarray(mask, dtype=bool)
    starts = mask & ~np.r_[False, mask[:-1]]
    return np.where(mask, np.cumsum(starts) - 1, -1)


def add_output_arguments(parser):
    """The --dpi option every script takes."""
    parser.add_argument("--dpi", type=int, default=DEFAULT_DPI, help=f"PNG resolution (default {DEFAULT_DPI})")
    return parser


def parser(doc):
    return add_output_arguments(argparse.ArgumentParser(description=doc.strip().splitlines()[0],
                                                        formatter_class=argparse.RawDescriptionHelpFormatter))


def one_png_main(doc, load, build, argv=None):
    """main() of a script drawing one PNG from array.h5: `SCRIPT ARRAY_H5 OUT.png [--dpi DPI]`, where
    build(load(ARRAY_H5)) returns (figure, axes)."""
    p = parser(doc)
    p.add_argument("array_h5")
    p.add_argument("out")
    args = p.parse_args(argv)
    apply()
    fig, _ = build(load(args.array_h5))
    save(fig, args.out, dpi=args.dpi)
    print("wrote", args.out)


def save_all(drawers, outdir, dpi=DEFAULT_DPI, jobs=0):
    """Draws and saves {file name: function returning a Figure} in `outdir`, in `jobs` processes side by side
    (0: one per CPU). The processes are forked after the data and matplotlib are loaded, so each starts at
    once. They share one queue of figures (a pipe holding one byte per figure; a one-byte read is atomic),
    each taking the next figure when it is done with its last, in the given order (put the slowest first):
    one slow figure, or a process slowed by others on the machine, does not hold the rest back. A figure that
    fails is reported and the others are still drawn; then raises."""
    names = list(drawers)
    jobs = min(len(names), jobs or len(os.sched_getaffinity(0)))
    if jobs <= 1 or not hasattr(os, "fork") or len(names) > 256:
        for name in names:
            save(drawers[name](), os.path.join(outdir, name), dpi=dpi)
        return
    # The parent's objects (modules, data) go to the collector's permanent generation: the children neither
    # scan them nor, by touching their headers, copy the pages they share with the parent. The children then
    # run without the collector (~8 % of their CPU): they are short-lived and each figure is closed.
    gc.freeze()
    queue, feed = os.pipe()
    os.write(feed, bytes(range(len(names))))  # far below the pipe's buffer: never blocks
    os.close(feed)
    children = []
    for j in range(jobs):
        pid = os.fork()
        if pid == 0:  # child: draw figures off the queue, then leave without running the parent's cleanups
            code = 0
            gc.disable()
            try:
                while taken := os.read(queue, 1):
                    name = names[taken[0]]
                    try:
                        save(drawers[name](), os.path.join(outdir, name), dpi=dpi)
                    except Exception as error:  # noqa: BLE001  (reported; the other figures are still drawn)
                        print(f"figure {name}: {error!r}", flush=True)
                        code = 1
            except BaseException as error:  # noqa: BLE001  (interrupted: reported, and the exit status says so)
                print(f"figure process {j}: {error!r}", flush=True)
                code = 1
            os._exit(code)
        children.append(pid)
    os.close(queue)
    gc.unfreeze()
    failed = [pid for pid in children if os.waitpid(pid, 0)[1] != 0]
    if failed:
        raise RuntimeError(f"figures failed in {len(failed)} of {jobs} figure processes")


def save(fig, path, dpi=DEFAULT_DPI):
    """Lays the figure out, writes it atomically (atomic_save) and closes it."""
    fixed = getattr(fig, "vibrissa_fixed_layout", False)
    if not fixed:
        fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    # PNG at zlib level 1: lossless as level 6, a few percent larger, ~0.1 s less per figure. The tight bounding
    # box is asked for here, not through rcParams["savefig.bbox"]: savefig(bbox_inches=None) falls back to that
    # rc value, so a fixed layout would still be drawn twice (once to measure, once to save).
    save_figure(fig, path, dpi=dpi, pil_kwargs={"compress_level": 1}, bbox_inches=None if fixed else "tight")
    plt.close(fig)
