"""The viewer page (docs/viewer.md) opened from disk in real headless Chromium (Debian's chromium and
chromium-driver through python3-selenium): the canvas is drawn with the whiskers where the data put them, the
slider moves them, clicking a whisker selects it and redraws its plots, and the page logs no error and makes
no network request. WebGL runs on SwiftShader through ANGLE.

Set VIBRISSA_VIEWER_SCREENSHOTS=DIR to keep the screenshots (docs/figures/viewer_*.png are made so).
"""
import base64
import io
import json
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import vibrissa
from vibrissa import viewer

webdriver = pytest.importorskip("selenium.webdriver")
from selenium.webdriver.chrome.service import Service as ChromeService  # noqa: E402
from selenium.webdriver.common.action_chains import ActionChains  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.common.keys import Keys  # noqa: E402
from selenium.webdriver.support.ui import WebDriverWait  # noqa: E402

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
CHROMEDRIVER = shutil.which("chromedriver") or "/usr/bin/chromedriver"
pytestmark = pytest.mark.skipif(not (os.path.exists(CHROMIUM) and os.path.exists(CHROMEDRIVER)),
                                reason="chromium and chromium-driver are not installed")
FRAMES = 80
WIDTH, HEIGHT = 1200, 700


def _image(png):
    from matplotlib import image
    return (image.imread(io.BytesIO(png), format="png")[..., :3] * 255).astype(int)


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    """An array run (default scene, FRAMES frames, two head pitches), its page, and the deflected shapes of
    every frame of pitch 0 [mm] as the simulation gives them."""
    tmp = tmp_path_factory.mktemp("viewer")
    config = vibrissa.default_array_config()
    config["time"]["frames"] = FRAMES
    config["head"]["pitches_deg"] = [0, 10]
    config["output"] = {"render_count": FRAMES, "render_pitch_index": 0}
    result = vibrissa.simulate_array(config)
    result.write(tmp / "run")
    page = viewer.view(tmp / "run", tmp / "view.html")
    return dict(result=result, page=page, shapes_mm=result["render/deflected"] * 1e3, state=result.state[0])


@pytest.fixture(scope="module")
def browser(scene):
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader",
                 "--enable-unsafe-swiftshader", f"--window-size={WIDTH},{HEIGHT}", "--force-device-scale-factor=1"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    driver = webdriver.Chrome(service=ChromeService(executable_path=CHROMEDRIVER), options=options)
    driver.set_page_load_timeout(60)
    try:
        driver.get(pathlib.Path(scene["page"]).as_uri())
        WebDriverWait(driver, 60).until(lambda d: d.execute_script("return !!(window.vibrissaViewer && "
                                                                   "window.vibrissaViewer.ready)"))
        yield driver
    finally:
        driver.quit()


def shot(driver, name):
    png = driver.get_screenshot_as_png()
    keep = os.environ.get("VIBRISSA_VIEWER_SCREENSHOTS")
    if keep:
        pathlib.Path(keep).mkdir(parents=True, exist_ok=True)
        (pathlib.Path(keep) / f"viewer_{name}.png").write_bytes(png)
    return _image(png)


def js(driver, code, *args):
    return driver.execute_script(code, *args)


def set_colour_by_state(driver):
    js(driver, """const s = document.getElementById('colour');
                  s.value = String(window.vibrissaViewer.meta.colour_by.findIndex(c => c.kind === 'state'));
                  s.dispatchEvent(new Event('change'));""")


def test_page_is_self_contained_and_loads_without_errors_or_requests(browser, scene):
    text = pathlib.Path(scene["page"]).read_text()
    assert "http://" not in text.split("<script>")[0] and "<link" not in text and " src=" not in text
    entries = browser.get_log("browser")
    assert not [e for e in entries if e["level"] == "SEVERE"], entries
    requests = [json.loads(e["message"])["message"] for e in browser.get_log("performance")]
    urls = [m["params"]["request"]["url"] for m in requests if m["method"] == "Network.requestWillBeSent"]
    assert urls and all(u == pathlib.Path(scene["page"]).as_uri() for u in urls), urls
    assert js(browser, "return !!document.querySelector('#scene canvas').getContext('webgl')") is not None


def test_canvas_shows_the_whiskers_where_the_data_put_them(browser, scene):
    set_colour_by_state(browser)
    state = scene["state"]  # [whisker][frame]
    frame = int(np.argmax((state == 1).sum(axis=0)))
    js(browser, "window.vibrissaViewer.setFrame(arguments[0])", frame)
    img = shot(browser, "contact_state")
    canvas = browser.find_element(By.CSS_SELECTOR, "#scene canvas").rect
    region = img[int(canvas["y"]):int(canvas["y"] + canvas["height"]), int(canvas["x"]):int(canvas["x"] + canvas["width"])]
    assert (region.sum(axis=2) < 3 * 235).mean() > 0.005  # not blank
    # The page's centre lines are the simulation's shapes (resampled), to half the quantisation step.
    shapes = scene["shapes_mm"][frame]  # [whisker][node][3]
    half_step = 0.5 * np.array(js(browser, "return window.vibrissaViewer.meta.quant.step"))
    assert half_step.max() < 5e-3  # mm
    for w in range(shapes.shape[0]):
        page_line = np.array(js(browser, "return window.vibrissaViewer.centreLine(arguments[0])", w)).reshape(-1, 3)
        assert (np.abs(page_line - viewer._resample(shapes[w])) <= half_step * 1.001 + 1e-5).all()
    # Each whisker in contact is drawn vermillion at the screen point of its mid-node (from the data, through
    # the page's camera); a free whisker grey.
    checked = 0
    for w in np.flatnonzero(state[:, frame] == 1):
        x, y = js(browser, "return window.vibrissaViewer.projectMm(arguments[0])", shapes[w][shapes.shape[1] // 3].tolist())
        patch = img[int(y) - 2:int(y) + 3, int(x) - 2:int(x) + 3].reshape(-1, 3)
        assert ((patch[:, 0] > 170) & (patch[:, 1] < 140) & (patch[:, 2] < 90)).any(), (w, x, y, patch)
        checked += 1
    assert checked >= 1


def test_slider_moves_the_whiskers(browser, scene):
    js(browser, "window.vibrissaViewer.setFrame(10)")
    before = np.array(js(browser, "return window.vibrissaViewer.centreLine(0)"))
    img0 = shot(browser, "frame_10")
    slider = browser.find_element(By.ID, "slider")
    slider.send_keys(Keys.ARROW_RIGHT)  # as a user: the slider has focus, one step
    assert js(browser, "return window.vibrissaViewer.frame") == 11
    js(browser, """const s = document.getElementById('slider'); s.value = '40';
                   s.dispatchEvent(new Event('input'));""")
    assert js(browser, "return window.vibrissaViewer.frame") == 40
    after = np.array(js(browser, "return window.vibrissaViewer.centreLine(0)")).reshape(-1, 3)
    assert np.abs(after.ravel() - before).max() > 0.1  # mm: whisking moved it
    half_step = 0.5 * np.array(js(browser, "return window.vibrissaViewer.meta.quant.step"))
    assert (np.abs(after - viewer._resample(scene["shapes_mm"][40][0])) <= half_step * 1.001 + 1e-5).all()
    img1 = shot(browser, "frame_40")
    assert np.abs(img1 - img0).sum(axis=2).astype(bool).mean() > 0.001
    assert "frame 41/" in browser.find_element(By.ID, "time").text


def test_clicking_a_whisker_selects_it_and_redraws_its_plots(browser, scene):
    frame = 40
    js(browser, "window.vibrissaViewer.setFrame(arguments[0])", frame)
    n = len(scene["result"].datasets["whisker"])
    all_nodes = np.array(js(browser, "return window.vibrissaViewer.screenNodes()"))  # [whisker][node][2]
    points = all_nodes[:, 2 * all_nodes.shape[1] // 3]
    current = js(browser, "return window.vibrissaViewer.selected")
    # the whisker whose point lies farthest from every other whisker (an unambiguous click), not selected yet
    clearance = [np.min(np.linalg.norm(np.delete(all_nodes, w, axis=0).reshape(-1, 2) - points[w], axis=1))
                 if w != current else -1 for w in range(n)]
    target = int(np.argmax(clearance))
    assert clearance[target] > 4
    plot_before = js(browser, "return document.getElementById('plot-MB').toDataURL()")
    canvas = browser.find_element(By.CSS_SELECTOR, "#scene canvas")
    r = canvas.rect
    x, y = points[target]
    ActionChains(browser).move_to_element_with_offset(canvas, int(round(x - r["x"] - r["width"] / 2)),
                                                      int(round(y - r["y"] - r["height"] / 2))).click().perform()
    assert js(browser, "return window.vibrissaViewer.selected") == target
    name = scene["result"].datasets["whisker"][target]
    name = name.decode() if isinstance(name, bytes) else str(name)
    assert name in browser.find_element(By.ID, "info").text
    assert browser.find_element(By.ID, "whisker").get_attribute("value") == str(target)
    assert js(browser, "return document.getElementById('plot-MB').toDataURL()") != plot_before
    shot(browser, "selected")
    assert not [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]


def test_second_head_pitch_is_shown_on_request(browser, scene):
    js(browser, """const s = document.getElementById('pitch'); s.value = '1'; s.dispatchEvent(new Event('change'));""")
    assert js(browser, "return window.vibrissaViewer.group") == 1
    labels = js(browser, "return Array.from(document.getElementById('pitch').options).map(o => o.text)")
    assert labels == ["+0.0°", "+10.0°"]
    js(browser, """const s = document.getElementById('colour'); s.value = '0'; s.dispatchEvent(new Event('change'));
                   window.vibrissaViewer.setFrame(60);""")
    assert "M_B" in browser.find_element(By.ID, "legend-title").text
    shot(browser, "pitch10_MB")


def test_cli_view_writes_the_page(scene, tmp_path):
    cli = os.environ.get("VIBRISSA_CLI")
    if not cli:
        pytest.skip("VIBRISSA_CLI is not set")
    out = tmp_path / "v.html"
    done = subprocess.run([cli, "view", str(pathlib.Path(scene["page"]).parent / "run"), "-o", str(out)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    text = out.read_text()
    assert 'id="vibrissa-meta"' in text and "THREE.OrbitControls" in text
    bad = subprocess.run([cli, "view", str(tmp_path / "nothing")], capture_output=True, text=True, timeout=60)
    assert bad.returncode == 1 and "nothing" in bad.stderr


def decode_blob(element):
    """What viewer.js does to a blob element, in NumPy."""
    import re
    import zlib
    dtype = {"float32": np.float32, "int16": np.int16, "uint8": np.uint8, "uint32": np.uint32}[
        re.search(r'data-dtype="(\w+)"', element).group(1)]
    raw = zlib.decompress(base64.b64decode(element.split(">", 1)[1].rsplit("<", 1)[0]))
    size = np.dtype(dtype).itemsize
    values = np.frombuffer(raw, np.uint8).reshape(size, -1).T.copy().view(dtype).ravel()
    stride = re.search(r'data-delta="(\d+)"', element)
    if stride:
        values = values.reshape(-1, int(stride.group(1))).cumsum(axis=0, dtype=dtype).ravel()
    return values


def test_blobs_round_trip_exactly():
    blobs = viewer._Blobs()
    a = (np.arange(7, dtype=np.float32) - 3) / 3
    codes = np.array([[32767, -32767, 5], [-32767, 32767, -5], [0, 1, 2]], dtype=np.int16)  # wrapping deltas
    assert blobs.add(a) == "b0" and blobs.add(codes, delta=True) == "b1"
    assert np.array_equal(decode_blob(blobs.elements[0]), a)
    assert np.array_equal(decode_blob(blobs.elements[1]), codes.ravel())


def test_trial_page_draws_the_whisker_through_its_contact_point(browser, tmp_path):
    trial = vibrissa.synthesize_trial(duration=0.3)
    trial.write(str(tmp_path / "trial.h5"))  # the name TrialResult.view gives it (in the title)
    result = vibrissa.analyze_trial(trial)
    results = result.write(tmp_path / "trial_results")
    page = viewer.view(tmp_path / "trial.h5", tmp_path / "trial.html")
    assert result.view(tmp_path / "same.html").read_text() == page.read_text()  # TrialResult.view: the same page
    browser.get_log("browser")  # clear
    browser.get(pathlib.Path(page).as_uri())
    WebDriverWait(browser, 60).until(lambda d: d.execute_script("return !!(window.vibrissaViewer && "
                                                                "window.vibrissaViewer.ready)"))
    import h5py
    with h5py.File(results / "frames.h5", "r") as f:
        status, point = f["cp_status"][()], np.column_stack([f[f"cp_contact_{c}"][()] for c in "xyz"]) * 1e3
    frame = int(np.flatnonzero(status == 0)[len(np.flatnonzero(status == 0)) // 2])
    js(browser, "window.vibrissaViewer.setFrame(arguments[0])", frame)
    line = np.array(js(browser, "return window.vibrissaViewer.centreLine(0)")).reshape(-1, 3)
    a, b = line[:-1], line[1:]  # distance from the contact point to the drawn polyline [mm]
    t = np.clip(np.einsum("ij,ij->i", point[frame] - a, b - a) / np.einsum("ij,ij->i", b - a, b - a), 0, 1)
    assert np.min(np.linalg.norm(a + t[:, None] * (b - a) - point[frame], axis=1)) < 0.05
    assert js(browser, "return window.vibrissaViewer.meta.kind") == "trial"
    # F_D and M_D as the figures draw them: the stored angle (mod 360) where defined, unwrapped within a contact
    with h5py.File(results / "frames.h5", "r") as f:
        stored = {"MD": np.degrees(f["cp_MD"][()]), "FD": np.degrees(f["cp_FD"][()]), "period": f["period"][()]}
    for s, name in ((2, "MD"), (3, "FD")):
        shown = np.array(js(browser, "const v = window.vibrissaViewer; return v.meta.times.map((_, t) => v.signal("
                                     "arguments[0], 0, t))", s), dtype=float)
        drawn = np.isfinite(shown)
        assert drawn.sum() > 10 and np.isfinite(stored[name][drawn]).all()
        turns = (shown[drawn] - stored[name][drawn]) / 360
        assert np.allclose(turns, np.round(turns), atol=1e-5)  # the same direction
        same_period = np.diff(stored["period"]) == 0
        steps = np.abs(np.diff(shown))[same_period & drawn[1:] & drawn[:-1]]
        assert steps.max() < 90, (name, steps.max())  # no wrap within a contact
    shot(browser, "trial")
    assert not [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]


def open_page(browser, page):
    browser.get_log("browser")  # clear
    browser.get(pathlib.Path(page).as_uri())
    WebDriverWait(browser, 60).until(lambda d: d.execute_script("return !!(window.vibrissaViewer && "
                                                                "window.vibrissaViewer.ready)"))


def page_line(browser, w=0):
    return np.array(js(browser, "return window.vibrissaViewer.centreLine(arguments[0])", w)).reshape(-1, 3)


def within_grid(browser, line_mm, expected_mm):
    half_step = 0.5 * np.array(js(browser, "return window.vibrissaViewer.meta.quant.step"))
    return (np.abs(line_mm - viewer._resample(expected_mm)) <= half_step * 1.001 + 1e-5).all()


SOLVE_CASE = {"whisker": {"length": 0.03, "curvature": 20.0, "links": 60},
              "load": {"mode": "object", "object": {"type": "cylinder", "point": [0.02, 0.003, 0.0],
                                                    "axis": [0, 0, 1], "radius": 0.001}, "approach": [0, 1, 0]}}


def test_solve_page_shows_the_whisker_contact_and_force(browser, tmp_path):
    case_path = tmp_path / "case.json"
    case_path.write_text(json.dumps(SOLVE_CASE))
    solution = vibrissa.solve_case_file(case_path, tmp_path / "out.json")
    assert solution.converged
    page = viewer.view(tmp_path / "out.json", tmp_path / "solve.html")  # finds case.json beside the result
    assert solution.view(tmp_path / "same.html", case=case_path).read_text() == page.read_text()
    open_page(browser, page)
    assert js(browser, "return window.vibrissaViewer.meta.kind") == "solve"
    shape_mm = np.asarray(solution.shape_W) * 1e3
    assert within_grid(browser, page_line(browser), shape_mm)  # the deflected whisker where the solve put it
    rest = np.array(js(browser, "return window.vibrissaViewer.meta.rest"))
    assert rest  # the rest shape is drawn (the case is known)
    arrow = js(browser, "return window.vibrissaViewer.arrow(0)")  # the contact force, at the contact point
    assert np.allclose(arrow["origin"], np.asarray(solution.contact_point_W) * 1e3, atol=1e-3)
    force = np.asarray(solution.force_W)
    assert np.allclose(arrow["direction"], force / np.linalg.norm(force), atol=1e-5)
    base_moment = js(browser, "return window.vibrissaViewer.arrow(2)")
    assert np.allclose(base_moment["origin"], shape_mm[0], atol=1e-3)
    moment = np.asarray(solution.moment_W)
    assert np.allclose(base_moment["direction"], moment / np.linalg.norm(moment), atol=1e-5)
    table = browser.find_element(By.ID, "values").text
    assert "converged" in table and f"{solution.force_magnitude:.4g} N" in table
    assert not browser.find_element(By.ID, "slider").is_displayed()  # one frame: no slider
    img = shot(browser, "solve")
    # the contact point is drawn: the contact dot (black) or the whisker at the point where it projects
    x, y = js(browser, "return window.vibrissaViewer.projectMm(arguments[0])", (np.asarray(solution.contact_point_W) * 1e3).tolist())
    assert (img[int(y) - 3:int(y) + 4, int(x) - 3:int(x) + 4].sum(axis=2) < 3 * 120).any()
    assert not [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    cli = os.environ.get("VIBRISSA_CLI")
    if cli:  # the command gives the same page (case.json beside the result)
        done = subprocess.run([cli, "view", str(tmp_path / "out.json"), "-o", str(tmp_path / "cli.html")],
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stderr
        assert (tmp_path / "cli.html").read_text() == page.read_text()
    bad = tmp_path / "bad.json"
    bad.write_text('{"a": 1}')
    with pytest.raises(ValueError, match="not a `vibrissa solve` result"):
        viewer.view(bad, tmp_path / "bad.html")


def select_value(browser, element_id, index):
    js(browser, """const s = document.getElementById(arguments[0]); s.value = String(arguments[1]);
                   s.dispatchEvent(new Event('change'));""", element_id, index)


def test_sweep_page_picks_a_run_by_its_grid_coordinates(browser, tmp_path):
    from vibrissa.sweep_runs import configured
    base = vibrissa.default_array_config()
    base["morphology"]["whiskers"] = ["C1", "C2", "D1"]
    base["time"]["frames"] = 24
    grid = {"objects.0.point_mm.0": [16.0, 24.0], "whisking.amplitude_deg": [20, 30]}
    result = vibrissa.sweep("array", base, out=tmp_path / "sweep", scheduler="serial", grid=grid,
                            variables=["state", "MB", "FT"])
    page = result.vibrissa.view(tmp_path / "sweep.html")  # the accessor; `vibrissa view DIR` the same page
    assert viewer.view(tmp_path / "sweep", tmp_path / "same.html").read_text() == page.read_text()
    open_page(browser, page)
    labels = js(browser, "return window.vibrissaViewer.meta.group_dims.map(d => d.label)")
    assert labels == list(grid)
    frame = 20
    js(browser, "window.vibrissaViewer.setFrame(arguments[0])", frame)
    select_value(browser, "pitch", 1)  # objects.0.point_mm.0 = 24
    select_value(browser, "dim-1", 1)  # whisking.amplitude_deg = 30
    assert js(browser, "return window.vibrissaViewer.group") == 3
    run = dict(base, output={"render_count": 24, "render_pitch_index": 0})
    expected = vibrissa.simulate_array(configured(run, {"objects.0.point_mm.0": 24.0, "whisking.amplitude_deg": 30}))
    shapes = expected["render/deflected"][frame] * 1e3
    for w in range(3):
        assert within_grid(browser, page_line(browser, w), shapes[w])
    # the plotted signal of the selected whisker is the sweep's value at that run
    w = js(browser, "return window.vibrissaViewer.selected")
    mb = float(result.MB.isel({"objects.0.point_mm.0": 1, "whisking.amplitude_deg": 1, "pitch": 0, "whisker": w,
                                "time": frame})) * 1e6
    shown = js(browser, "return window.vibrissaViewer.signal(0, arguments[0], arguments[1])", w, frame)
    assert shown == pytest.approx(mb, rel=1e-6, abs=1e-9)
    img_a = shot(browser, "sweep")
    select_value(browser, "pitch", 0)  # another peg position: the scene changes
    assert js(browser, "return window.vibrissaViewer.group") == 1
    assert np.abs(shot(browser, "sweep_other") - img_a).sum(axis=2).astype(bool).mean() > 0.0005
    assert not [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]


def test_solve_sweep_page_steps_through_the_last_parameter(browser, tmp_path):
    case = {"whisker": {"length": 0.03, "curvature": 20.0, "links": 60},
            "load": {"mode": "edge", "point": [0.02, 0.0065, 0.0], "direction": [0, 0, 1]}}
    ys = [0.0075, 0.0065, 0.0055]
    result = vibrissa.sweep("solve", case, out=tmp_path / "s", scheduler="serial",
                            grid={"load.point.2": [0.0, 0.002], "load.point.1": ys})
    page = viewer.view(tmp_path / "s", tmp_path / "s.html")
    open_page(browser, page)
    assert js(browser, "return window.vibrissaViewer.meta.times") == ys
    select_value(browser, "pitch", 1)  # load.point.2 = 0.002
    js(browser, "window.vibrissaViewer.setFrame(2)")
    solved = vibrissa.load_case(dict(case, load=dict(case["load"], point=[0.02, ys[2], 0.002]))).solve()
    assert within_grid(browser, page_line(browser), np.asarray(solved.shape_W) * 1e3)
    assert float(result.FT.isel({"load.point.2": 1, "load.point.1": 2})) * 1e3 == pytest.approx(
        js(browser, "return window.vibrissaViewer.signal(1, 0, 2)"), rel=1e-6)
    assert "load.point.1" in browser.find_element(By.ID, "time").text
    shot(browser, "solve_sweep")
    assert not [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]


def test_trial_sweep_page_shows_each_runs_trial(browser, tmp_path):
    result = vibrissa.sweep("trial", {"synth": {"duration": 0.12}}, out=tmp_path / "t", scheduler="serial",
                            grid={"analysis.mu": [0.2, 0.6], "synth.seed": [1, 2]}, variables=["cp_MB", "cp_FT"])
    page = viewer.view(tmp_path / "t", tmp_path / "t.html", runs=[0, 3])  # (mu 0.2, seed 1) and (mu 0.6, seed 2)
    open_page(browser, page)
    assert js(browser, "return window.vibrissaViewer.meta.group_dims[0].label") == "run"
    select_value(browser, "pitch", 1)  # run 3: mu 0.6, seed 2
    assert js(browser, "return window.vibrissaViewer.group") == 1
    mb = result.cp_MB.isel({"analysis.mu": 1, "synth.seed": 1}).values * 1e6
    shown = np.array(js(browser, "const v = window.vibrissaViewer; return v.meta.times.map((_, t) => v.signal(0, 0, t))"),
                     dtype=float)
    assert np.allclose(shown, mb, rtol=1e-6, atol=1e-9, equal_nan=True)  # the sweep's M_B of that run
    other = result.cp_MB.isel({"analysis.mu": 0, "synth.seed": 0}).values * 1e6
    assert not np.allclose(other, mb, rtol=1e-3, equal_nan=True)  # the other run differs: the list picked this one
    assert not [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]


def test_sweep_page_draws_each_runs_own_object(tmp_path):
    import re
    base = vibrissa.default_array_config()
    base["morphology"]["whiskers"] = ["C1", "C2"]
    base["time"]["frames"] = 6
    base["objects"] = [{"type": "sphere", "frame": "head", "centre_mm": [20, -8, -3], "radius_mm": 3}]
    result = vibrissa.sweep("array", base, scheduler="serial", grid={"objects.0.radius_mm": [2.0, 4.0]},
                            variables=["state"])
    text = result.vibrissa.view(tmp_path / "p.html").read_text()
    meta = json.loads(re.search(r'id="vibrissa-meta">(.*?)</script>', text, re.S).group(1))
    blobs = {m.group(1): m.group(0) for m in re.finditer(r'<script type="application/octet-stream" id="(b\d+)".*?</script>', text, re.S)}
    assert len(meta["objects"]) == 2  # one sphere per radius
    radii = []
    for o in meta["objects"]:
        v = decode_blob(blobs[o["vertices"]]).reshape(-1, 3)
        radii.append(np.linalg.norm(v - v.mean(axis=0), axis=1).max())
    assert radii == pytest.approx([2.0, 4.0], rel=0.02)  # mm
    for g, group in enumerate(meta["groups"]):  # each run places its own sphere, the other is collapsed
        poses = decode_blob(blobs[group["object_poses"]]).reshape(6, 2, 12)
        assert np.abs(poses[:, g]).max() > 0 and np.abs(poses[:, 1 - g]).max() == 0
