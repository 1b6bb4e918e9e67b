"""What the figure scripts in figures/ draw: the fit lines are summary.json's, angles are unwrapped, counts have
integer ticks, the palette is Okabe–Ito, units are written properly, axis ranges follow the data, time windows
and whisks select the time series, and the array animation has top and side views with greyscale-distinct
states at the requested fps and frame count."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import vibrissa

pytest.importorskip("matplotlib")
pytest.importorskip("h5py")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
FIGURES = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, "figures")
sys.path.insert(0, FIGURES)
import array_animation  # noqa: E402
import array_pitch_sweep  # noqa: E402
import style  # noqa: E402
import trial_figures  # noqa: E402
from matplotlib import pyplot as plt  # noqa: E402


@pytest.fixture(scope="module")
def trial_files(tmp_path_factory):
    """frames.h5 and summary.json of a short synthetic trial with all three modes."""
    out = tmp_path_factory.mktemp("trial")
    trial = vibrissa.synthesize_trial(duration=1.0, mu=0.48, theta_center_deg=12.0, seed=3)
    vibrissa.analyze_trial(trial, mu=0.48).write(out)
    return out


@pytest.fixture(scope="module")
def trial_data(trial_files):
    summary = json.loads((trial_files / "summary.json").read_text())
    return trial_figures.load(trial_files / "frames.h5"), summary


@pytest.fixture(scope="module")
def figs(trial_data):
    style.apply()
    built = trial_figures.build(*trial_data)
    yield built
    for fig in built.values():
        plt.close(fig)


def lines_with_gid(ax, gid):
    return [ln for ln in ax.get_lines() if ln.get_gid() == gid]


def test_palette_is_okabe_ito():
    assert list(style.OKABE_ITO.values()) == ["#000000", "#E69F00", "#56B4E9", "#009E73", "#F0E442", "#0072B2",
                                              "#D55E00", "#CC79A7"]
    used = [m["color"] for m in style.MODES] + [s["color"] for s in style.STATES.values()]
    used += [style.FIT["color"], style.DATA["color"], style.IDENTITY["color"], style.OBJECT["color"]]
    assert set(used) <= set(style.OKABE_ITO.values()) | {style.GREY}
    assert len({(m["color"], str(m["ls"])) for m in style.MODES}) == len({str(m["ls"]) for m in style.MODES}) == 3


@pytest.mark.parametrize("name, eq", [("fig2e_z_error_eq6.png", "eq6"), ("fig4b_z_error_eq7.png", "eq7")])
def test_z_error_fit_lines_are_the_summary_fits(figs, trial_data, name, eq):
    _, summary = trial_data
    ax = figs[name].axes[0]
    fits = lines_with_gid(ax, "fit")
    expected = [summary["z_error"][eq]["all"]]
    if summary["z_error"][eq]["outliers"]:  # else the same fit, drawn once
        expected.append(summary["z_error"][eq]["without_iqr_outliers"])
    assert len(fits) == len(expected)
    for line, fit in zip(fits, expected):
        x, y = line.get_data()
        np.testing.assert_allclose(y, fit["slope"] * x + fit["intercept"] * 1e3, rtol=1e-12, atol=1e-12)
        assert f"{fit['slope']:.3f}x" in line.get_label() and f"{fit['r2']:.3f}" in line.get_label()
    # the points marked as used are exactly the points of the summary's fit
    used = [c for c in ax.collections if c.get_gid() == "used"]
    assert len(used[0].get_offsets()) == expected[0]["points"]


def test_fit_line_follows_the_summary_not_the_data(trial_data):
    d, summary = trial_data
    fake = json.loads(json.dumps(summary))
    fake["z_error"]["eq6"]["all"].update(slope=-2.5, intercept=0.001)
    fake["kinematic_prediction"]["fit"].update(slope=7.0, intercept=-0.002)
    built = trial_figures.build(d, fake)
    x, y = lines_with_gid(built["fig2e_z_error_eq6.png"].axes[0], "fit")[0].get_data()
    np.testing.assert_allclose(y, -2.5 * x + 1.0)
    ax = built["fig2f_kinematic_prediction.png"].axes[0]
    x, y = lines_with_gid(ax, "fit")[0].get_data()
    np.testing.assert_allclose(y, 7.0 * x - 2.0)
    # Fig. 2f's ranges are the data's, whatever the fit line does: one range for both axes, equal scales, so
    # that the identity line is the diagonal
    x, y = d["tracked_height"] * 1e3, d["kinematic_height"] * 1e3
    ok = np.isfinite(x) & np.isfinite(y)
    assert ax.get_ylim() == pytest.approx(style.data_limits(x[ok], y[ok]))
    assert ax.get_xlim() == pytest.approx(style.data_limits(x[ok], y[ok]))
    assert ax.get_aspect() == 1.0
    for fig in built.values():
        plt.close(fig)


def test_direction_angles_are_masked_where_undefined(trial_data):
    d, _ = trial_data
    for m in trial_figures.present_modes(d):
        for q, mag in trial_figures.ANGLE_MAGNITUDE.items():
            y = trial_figures.signal(d, trial_figures.present_modes(d), m, q, "deg")
            drawn = np.isfinite(y)
            assert not (drawn & (d["period_edge"] > 0.5)).any()  # first/last two frames of each contact
            for p in np.unique(d["period"][d["period"] >= 0]):
                idx = (d["period"] == p) & drawn
                peak = np.nanmax(np.abs(d[m["prefix"] + mag][d["period"] == p]))
                assert (np.abs(d[m["prefix"] + mag][idx]) >= trial_figures.ANGLE_MIN_FRACTION * peak).all()
            assert drawn.sum() > 0.5 * (d["period"] >= 0).sum()  # most contact frames still drawn


def test_many_whiskers_get_distinct_colours():
    for n in (5, 13, 20):
        colours = [matplotlib.colors.to_hex(s["color"]) for s in style.distinct_styles(n)]
        assert len(set(colours)) == n


def test_unwrap_deg_removes_jumps_and_follows_a_reference():
    v = np.array([170.0, 179.0, -179.0, -170.0, np.nan, 10.0, -175.0, 175.0])
    g = np.array([0, 0, 0, 0, -1, -1, 1, 1])
    out = style.unwrap_deg(v, g)
    np.testing.assert_allclose(out[:4], [170.0, 179.0, 181.0, 190.0])
    assert np.isnan(out[4]) and out[5] == 10.0  # outside any group: unchanged
    np.testing.assert_allclose(out[6:], [-175.0, -185.0])  # median -180 -> kept on the (-180, 180] side
    ref = np.full_like(v, 540.0)
    np.testing.assert_allclose(style.unwrap_deg(v, g, reference=ref)[:4], [530.0, 539.0, 541.0, 550.0])


def test_direction_traces_have_no_wrap_jumps(figs, trial_data):
    d, _ = trial_data
    fig = figs["fig3b_whisker_signals.png"]
    raw_jumps = max(np.nanmax(np.abs(np.diff(np.degrees(d[m["prefix"] + q]))))  # frames.h5: rad
                    for m in trial_figures.present_modes(d) for q in trial_figures.ANGLES)
    assert raw_jumps > 180.0, "the test trial should wrap F_D or M_D somewhere; choose another seed"
    t = d["time"] * 1e3
    starts = {t[i] for i in np.flatnonzero(np.diff(d["period"]) != 0) + 1}
    for ax in (fig.axes[2], fig.axes[5]):  # F_D, M_D
        assert ax.get_ylabel().endswith("[deg]")
        for line in ax.get_lines():
            x, y = line.get_data()
            steps = np.abs(np.diff(y))
            within = np.isfinite(steps) & ~np.isin(x[1:], list(starts))
            assert steps[within].max() < 90.0


def test_count_axes_have_integer_ticks(figs):
    hist = figs["fig3cde_friction.png"].axes[2]
    assert hist.get_ylabel() == "frames"
    ticks = hist.get_yticks()
    assert np.all(ticks == np.round(ticks))
    state = np.zeros((3, 4, 6), dtype=int)
    state[0, 0, 2:4] = 1
    state[1, :2, 1:3] = 1
    state[2, :3, 2] = 1
    state[2, 3, 4] = 2
    d = dict(names=["A1", "B1", "C1", "D1"], state=state, MB=np.full(state.shape, 2e-6), pitch=np.radians([-5, 0, 5]))
    fig, (_, counts, _) = array_pitch_sweep.build(d)
    fig.canvas.draw()
    ticks = [t for t in counts.get_yticks() if counts.get_ylim()[0] <= t <= counts.get_ylim()[1]]
    assert len(ticks) >= 2 and all(t == round(t) for t in ticks)
    plt.close(fig)


def test_pitch_sweep_text_is_at_least_7_pt_for_62_whiskers():
    rng = np.random.default_rng(0)
    state = (rng.random((3, 62, 20)) > 0.5).astype(int)
    d = dict(names=[f"W{i}" for i in range(62)], state=state, MB=rng.random(state.shape) * 1e-6,
             pitch=np.radians([-5, 0, 5]))
    style.apply()
    fig, _ = array_pitch_sweep.build(d)
    fig.canvas.draw()
    sizes = [t.get_fontsize() for t in fig.findobj(matplotlib.text.Text) if t.get_text()]
    assert min(sizes) >= 7
    heat = fig.axes[0]  # one name per row, and the rows do not overlap at that size
    row_pt = heat.get_window_extent().height / 62 * 72 / fig.dpi
    assert row_pt >= 7
    plt.close(fig)


def test_trial_figures_fit_their_fixed_layouts(figs, trial_data):
    """The trial figures have fixed margins (style.fixed_layout: no tight bounding box when saved, which drew
    every figure twice), so whatever they draw must lie inside the canvas: titles, labels, legends. Fig. 3c's
    title also with the longest window description (a trial longer than OVERVIEW_MAX_S)."""
    style.apply()
    d, summary = trial_data
    modes = trial_figures.present_modes(d)
    span = (0.0, 0.5, "t = 10.01–11.01 s (first 1 s of contact)")
    long_titles = [("fig3cde_friction.png, long window", trial_figures.friction_figure(d, summary, span))]
    for rows, title in ((trial_figures.SHAPE_ROWS, "Figs. 2b–d: shape error, contact height, arc length of contact"),
                        (trial_figures.WHISKER_ROWS, "Fig. 3b: whisker frame")):
        long_titles.append((f"{title}, long window", trial_figures.time_series(d, modes, rows, span, title)))
    for name, fig in list(figs.items()) + long_titles:
        assert getattr(fig, "vibrissa_fixed_layout", False), name
        fig.canvas.draw()
        box = fig.get_tightbbox(fig.canvas.get_renderer())  # inches
        w, h = fig.get_size_inches()
        assert box.x0 >= -0.02 and box.y0 >= -0.02 and box.x1 <= w + 0.02 and box.y1 <= h + 0.02, (name, box)
    for _, fig in long_titles:
        plt.close(fig)


def test_a_fixed_layout_figure_is_drawn_once_when_saved(tmp_path):
    """savefig(bbox_inches=None) falls back to rcParams["savefig.bbox"]; with "tight" there, a fixed layout
    was still measured in a first draw. Counted by draw events: one for a fixed layout, two with tight."""
    style.apply()
    draws = {}
    for fixed in (True, False):
        fig, ax = plt.subplots(figsize=(2, 2))
        if fixed:
            style.fixed_layout(fig)
        ax.plot([0, 1], [0, 1])
        fig.canvas.mpl_connect("draw_event", lambda _event, key=fixed: draws.update({key: draws.get(key, 0) + 1}))
        style.save(fig, str(tmp_path / f"fixed_{fixed}.png"))
    assert draws == {True: 1, False: 2}


def test_save_all_draws_every_figure_once_across_processes(tmp_path):
    """style.save_all's processes share one queue: every figure is drawn exactly once, in a child process; a
    figure that fails does not stop the others, and save_all then raises."""
    log = tmp_path / "drawn.txt"

    def drawer(name, fail=False):
        def draw():
            with open(log, "a") as f:
                f.write(f"{name} {os.getpid()}\n")
            if fail:
                raise ValueError("this figure fails")
            fig, _ = plt.subplots(figsize=(1, 1))
            return style.fixed_layout(fig, left_in=0.1, right_in=0.1, top_in=0.1, bottom_in=0.1, legend_in=0.0)
        return draw

    style.apply()
    names = [f"f{k}.png" for k in range(7)]
    style.save_all({n: drawer(n) for n in names}, str(tmp_path), jobs=3)
    drawn = [line.split() for line in log.read_text().splitlines()]
    assert sorted(n for n, _ in drawn) == names
    assert all(int(pid) != os.getpid() for _, pid in drawn)
    assert all((tmp_path / n).stat().st_size > 0 for n in names)

    log.unlink()
    out = tmp_path / "with_failure"
    with pytest.raises(RuntimeError, match="figures failed"):
        style.save_all({"bad.png": drawer("bad.png", fail=True), "a.png": drawer("a.png"), "b.png": drawer("b.png")},
                       str(out), jobs=2)
    assert sorted(line.split()[0] for line in log.read_text().splitlines()) == ["a.png", "b.png", "bad.png"]
    assert (out / "a.png").exists() and (out / "b.png").exists() and not (out / "bad.png").exists()


@pytest.mark.parametrize("line", ["go\n", "", "stop\n"])
def test_trial_figures_started_early_draw_only_on_go(trial_files, tmp_path, line):
    """`vibrissa trial` starts trial_figures.py --start-on-stdin before solving: it draws once told "go", and
    exits drawing nothing (status 0) at the end of input or any other line (the analysis failed)."""
    out = tmp_path / "figures"
    done = subprocess.run([sys.executable, os.path.join(FIGURES, "trial_figures.py"), str(trial_files / "frames.h5"),
                           str(trial_files / "summary.json"), str(out), "--start-on-stdin"],
                          input=line, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    drawn = sorted(os.listdir(out)) if out.exists() else []
    if line == "go\n":  # the default set
        assert drawn == sorted(trial_figures.builders(*trial_figures_data(trial_files), all_figures=False))
    else:
        assert drawn == []


def trial_figures_data(trial_files):
    return trial_figures.load(trial_files / "frames.h5"), json.loads((trial_files / "summary.json").read_text())


def test_cli_trial_that_fails_draws_no_figures(cli, tmp_path):
    """The figure script started ahead of the solve exits quietly when the trial cannot be analysed."""
    trial = tmp_path / "t.csv"
    trial.write_text("time,theta\n0,0\n")
    done = subprocess.run([cli, "trial", trial, "--out", tmp_path / "r"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 1 and "vibrissa-trial" in done.stderr
    assert "Traceback" not in done.stderr and "figure script" not in done.stderr
    assert not (tmp_path / "r" / "figures").exists()


def test_units_are_written_properly(figs):
    labels = [ax.get_ylabel() + ax.get_xlabel() for fig in figs.values() for ax in fig.axes]
    assert not any("uN" in s or "N m" in s for s in labels)
    assert sum("[µN·m]" in s for s in labels) >= 4 and sum("[mN]" in s for s in labels) >= 4


def test_every_figure_has_a_title_and_labelled_axes(figs):
    for name, fig in figs.items():
        assert fig._suptitle is not None or any(ax.get_title() for ax in fig.axes), name
        for ax in fig.axes:
            assert ax.get_ylabel(), name


def test_time_window_and_whisk_choose_the_time_series(trial_data):
    d, summary = trial_data
    assert trial_figures.select_window(d)[:2] == (d["time"][0], d["time"][-1])  # a short trial: whole
    fig = trial_figures.build(d, summary, window=(0.2, 0.45))["fig3b_whisker_signals.png"]
    assert fig.axes[-1].get_xlim() == pytest.approx((200.0, 450.0))
    assert "t = 0.2–0.45 s" in fig._suptitle.get_text()
    x = fig.axes[1].get_lines()[0].get_xdata()
    assert x.min() >= 200.0 and x.max() <= 450.0
    start, end, what = trial_figures.select_window(d, whisk=2)
    in_whisk = d["time"][d["period"] == 1]
    assert start < in_whisk[0] and end > in_whisk[-1] and end - start < 2 * (in_whisk[-1] - in_whisk[0]) + 0.02
    assert what.startswith("whisk 2 of")
    long = dict(time=np.arange(0, 30, 1e-3), period=np.full(30000, -1))
    long["period"][2500:2560] = 0
    start, end, _ = trial_figures.select_window(long)
    assert end - start == pytest.approx(trial_figures.WINDOW_S) and start == pytest.approx(2.45)
    with pytest.raises(SystemExit, match="contact periods"):
        trial_figures.select_window(d, whisk=999)
    plt.close("all")


def test_python_figures_pass_the_window_to_the_script(tmp_path):
    result = vibrissa.analyze_trial(vibrissa.synthesize_trial(duration=0.3, seed=3))
    with pytest.raises(RuntimeError, match="lies outside the trial"):
        result.figures(tmp_path / "f", window=(100.0, 101.0))


def test_cli_trial_window_flags(cli, tmp_path):
    trial = tmp_path / "t.csv"
    subprocess.run([cli, "synth", trial, "--duration", "0.6"], check=True, capture_output=True)
    done = subprocess.run([cli, "trial", trial, "--window", "0.3,0.1"], capture_output=True, text=True)
    assert done.returncode != 0 and "start must be before end" in done.stderr
    done = subprocess.run([cli, "trial", trial, "--window", "0.1,0.3", "--whisk", "1"], capture_output=True, text=True)
    assert done.returncode != 0 and "excludes" in done.stderr
    done = subprocess.run([cli, "trial", trial, "--whisk", "1", "--figure-dpi", "60", "--out", tmp_path / "r"],
                          capture_output=True, text=True)
    assert done.returncode == 0 and "failed" not in done.stderr, done.stderr
    png = tmp_path / "r" / "figures" / "fig3b_whisker_signals.png"
    width = int.from_bytes(png.read_bytes()[16:20], "big")
    assert width < 7.5 * 60  # drawn at the requested dpi (7 in wide)
    # the default set leaves out the extra figures; --all-figures draws them too
    drawn = {p.name for p in (tmp_path / "r" / "figures").glob("*.png")}
    assert len(drawn) == 6 and not drawn & set(trial_figures.EXTRA_FIGURES)
    done = subprocess.run([cli, "trial", trial, "--all-figures", "--figure-dpi", "60", "--out", tmp_path / "r"],
                          capture_output=True, text=True)
    assert done.returncode == 0 and "failed" not in done.stderr, done.stderr
    assert {p.name for p in (tmp_path / "r" / "figures").glob("*.png")} == drawn | set(trial_figures.EXTRA_FIGURES)


def luminance(hex_colour):
    r, g, b = matplotlib.colors.to_rgb(hex_colour)
    return 0.299 * r + 0.587 * g + 0.114 * b


def test_array_states_differ_in_greyscale_and_line_style():
    grey = sorted(luminance(s["color"]) for s in style.STATES.values())
    assert min(np.diff(grey)) >= 0.1
    assert len({(str(s["ls"]), s["lw"]) for s in style.STATES.values()}) == 3


def test_array_animation_views_fps_and_frames(cli, tmp_path):
    config = vibrissa.default_array_config()
    config["time"]["frames"] = 60
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(config))
    out = tmp_path / "arr"
    done = subprocess.run([cli, "array", path, "--out", out, "--animation", "--frames", "9", "--fps", "5", "--figure-dpi", "60"],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0 and "failed" not in done.stderr, done.stderr
    probe = subprocess.run(["ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
                            "stream=r_frame_rate,nb_read_frames", "-of", "json", out / "array_animation.mp4"],
                           capture_output=True, text=True)
    if probe.returncode != 0:
        pytest.skip("ffprobe is not available")
    stream = json.loads(probe.stdout)["streams"][0]
    assert stream["r_frame_rate"] == "5/1" and int(stream["nb_read_frames"]) == 9

    style.apply()
    anim = array_animation.ArrayAnimation(array_animation.load(out / "array.h5"))
    top, side = anim.axes
    assert "top" in top.get_title() and "side" in side.get_title()
    assert top.get_xlabel().startswith("y") and top.get_ylabel().startswith("x") and side.get_ylabel().startswith("z")
    i = anim.busiest_frame()
    anim.draw(i)
    states = anim.states[:, i]
    assert (states == 1).any()
    for view in anim.lines:
        for w, line in enumerate(view):
            s = style.STATES[int(states[w])]
            assert line.get_linewidth() == s["lw"] and matplotlib.colors.to_hex(line.get_color()) == s["color"].lower()
    assert len(anim.markers[0].get_xdata()) == int((states == 1).sum())
    labels = [t.get_text() for t in anim.fig.legends[0].get_texts()]
    assert labels == ["free", "in contact", "pushed past", "object"]
    plt.close(anim.fig)


def test_friction_figure_of_a_trial_without_usable_mu_says_so(tmp_path):
    """A peg out of reach (docs/formats.md, "Nulls and their reasons"): no frame passes F_N >= 0.1 mN, so Fig. 3e
    has nothing to draw; it says so instead of an empty legend box, and Fig. 3d keeps the threshold in view."""
    trial = vibrissa.synthesize_trial(duration=0.5, peg_distance_mm=34.5)
    result = vibrissa.analyze_trial(trial)
    result.write(tmp_path)
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["friction"]["median"] is None
    style.apply()
    fig = trial_figures.build(trial_figures.load(tmp_path / "frames.h5"), summary)["fig3cde_friction.png"]
    versus_force, hist = fig.axes[1], fig.axes[2]
    assert hist.get_legend() is None
    assert any("μ not estimated" in t.get_text() for t in hist.texts)
    assert versus_force.get_xlim()[1] > 0.1
    plt.close(fig)
