#!/usr/bin/python3
"""Validation of `vibrissa reconstruct` against ground truth (docs/reconstruction.md, "Validation").

A `vibrissa synth --shapes` trial (known 3D shapes, contact points and mu) is projected through two known
pinhole cameras (with radial distortion), and for the three-camera comparison through a third (side). Per noise level: Gaussian pixel noise on every tracked point, 2 %
of frames dropped in the front view, 5 % of points replaced by low-likelihood garbage, and 1 % of frames with
a tracker identity swap in the front view (the neighbouring whisker, 2 mm higher). The top view is written as
a plain CSV, the front view as a DeepLabCut CSV. `vibrissa reconstruct` rebuilds the trial, the errors are
measured against the truth, and `vibrissa trial` recovers mu end to end.

Usage: scripts/validate_reconstruction.py --vibrissa build/bin/vibrissa --out /tmp/recon_validation
         [--noise 0 0.25 0.5 1 2] [--duration 1.5] [--figure docs/figures/reconstruction_validation.png]
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np
import h5py

CAMERAS = {  # K [px], R_CW, camera centre [m], k1, k2
    "top": (np.array([[2400.0, 0, 320], [0, 2400, 240], [0, 0, 1]]), np.diag([1.0, -1.0, -1.0]),
            np.array([0.015, 0.01, 0.3]), -0.05, 0.0),
    "front": (np.array([[2400.0, 0, 320], [0, 2400, 240], [0, 0, 1]]),
              np.array([[1.0, 0, 0], [0, 0, -1], [0, 1, 0]]), np.array([0.015, -0.3, 0.0]), 0.03, 0.0),
}


def look_at(C, target):
    """R_CW of a camera at C looking at target (image x horizontal, y down)."""
    z = (target - C) / np.linalg.norm(target - C)
    x = np.cross([0.0, 0.0, 1.0], z)
    x /= np.linalg.norm(x)
    return np.stack([x, np.cross(z, x), z])


# A third camera for the three-camera comparison: oblique, 0.3 m from the whisker, from below, behind and aside.
_TARGET = np.array([0.015, 0.005, 0.0])
_C_SIDE = _TARGET + 0.3 * np.array([-0.55, -0.55, -0.63]) / np.linalg.norm([-0.55, -0.55, -0.63])
SIDE = (np.array([[2400.0, 0, 320], [0, 2400, 240], [0, 0, 1]]), look_at(_C_SIDE, _TARGET), _C_SIDE, 0.02, 0.0)
CAMERAS3 = dict(CAMERAS, side=SIDE)
POINTS_PER_VIEW = 25
MU_TRUE = 0.48


def project(name, P_W):
    K, R, C, k1, k2 = CAMERAS3[name]
    pc = (P_W - C) @ R.T
    n = pc[:, :2] / pc[:, 2:3]
    r2 = (n ** 2).sum(1, keepdims=True)
    n = n * (1 + k1 * r2 + k2 * r2 ** 2)
    return n @ K[:2, :2].T + K[:2, 2]


def resample(shape, count):
    seg = np.linalg.norm(np.diff(shape, axis=0), axis=1)
    s = np.concatenate([[0], np.cumsum(seg)])
    t = np.linspace(0, s[-1], count)
    return np.stack([np.interp(t, s, shape[:, k]) for k in range(3)], axis=1)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("command failed: " + " ".join(cmd) + "\n" + r.stdout + r.stderr)
    return r.stdout


def write_views(truth, sigma, rng, out_dir, front_shift=0):
    """Top view as a plain CSV, front view as a DeepLabCut CSV. front_shift > 0: the front video starts that
    many frames later (its frame f shows frame f + front_shift), as when two recordings were not cut alike."""
    shapes = truth["shape"]
    n = shapes.shape[0]
    dropped = set(rng.choice(n, size=int(0.02 * n), replace=False).tolist())
    swapped = set(rng.choice(sorted(set(range(n)) - dropped), size=int(0.01 * n), replace=False).tolist())
    top_rows = ["frame,point,x_px,y_px,likelihood"]
    K = POINTS_PER_VIEW
    header = ["scorer" + ",synthetic" * (3 * K), "bodyparts" + "".join(f",p{k},p{k},p{k}" for k in range(K)),
              "coords" + ",x,y,likelihood" * K]
    front_rows = list(header)
    ends_lost = set()  # frames with an end point (base or tip) lost in one view
    for i in range(n):
        shape = shapes[i][np.isfinite(shapes[i][:, 0])]
        pts = resample(shape, K)
        for view in ("top", "front"):
            P = pts
            if view == "front" and i in swapped:
                P = pts + np.array([0.0, 0.0, 0.002])
            px = project(view, P) + rng.normal(0.0, sigma, (K, 2))
            like = rng.uniform(0.9, 1.0, K)
            bad = rng.random(K) < 0.05
            px[bad] += rng.normal(0.0, 30.0, (bad.sum(), 2))
            like[bad] = rng.uniform(0.0, 0.3, bad.sum())
            if bad[0] or bad[-1]:
                ends_lost.add(i)
            if view == "top":
                top_rows += [f"{i},{k},{px[k,0]:.4f},{px[k,1]:.4f},{like[k]:.3f}" for k in range(K)]
            elif i not in dropped and i >= front_shift:
                front_rows.append(f"{i - front_shift}," +
                                  ",".join(f"{px[k,0]:.4f},{px[k,1]:.4f},{like[k]:.3f}" for k in range(K)))
    with open(os.path.join(out_dir, "top.csv"), "w") as f:
        f.write("\n".join(top_rows) + "\n")
    with open(os.path.join(out_dir, "front_dlc.csv"), "w") as f:
        f.write("\n".join(front_rows) + "\n")
    return dropped, swapped, ends_lost


def write_side(truth, sigma, rng, out_dir):
    """The third view (plain CSV side.csv): the same noise and 5 % low-likelihood garbage points as the others,
    no dropped frames or swaps; its own random stream, so the two-view data stay those of the tables above."""
    rows = ["frame,point,x_px,y_px,likelihood"]
    K = POINTS_PER_VIEW
    for i, shape in enumerate(truth["shape"]):
        pts = resample(shape[np.isfinite(shape[:, 0])], K)
        px = project("side", pts) + rng.normal(0.0, sigma, (K, 2))
        like = rng.uniform(0.9, 1.0, K)
        bad = rng.random(K) < 0.05
        px[bad] += rng.normal(0.0, 30.0, (bad.sum(), 2))
        like[bad] = rng.uniform(0.0, 0.3, bad.sum())
        rows += [f"{i},{k},{px[k,0]:.4f},{px[k,1]:.4f},{like[k]:.3f}" for k in range(K)]
    with open(os.path.join(out_dir, "side.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")


def calibration_json(path, cameras=None):
    cams = {}
    for name, (K, R, C, k1, k2) in (cameras or CAMERAS).items():
        cams[name] = {"model": "pinhole", "K": K.tolist(), "R": R.tolist(), "t": (-R @ C).tolist(), "k1": k1, "k2": k2}
    with open(path, "w") as f:
        json.dump({"length_unit": "m", "cameras": cams}, f, indent=1)


def wrap_deg(a):
    return (np.degrees(a) + 180.0) % 360.0 - 180.0


def rot_x(deg):
    c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(deg):
    c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    return np.array([[c, 0, s], [0, 1.0, 0], [-s, 0, c]])


def wrong_calibrations(cameras=CAMERAS):
    """The calibration errors users make: focal length 0.5 % off, a camera turned by 0.1 degree after
    calibrating, the lens distortion left out."""
    out = {}
    K, R, C, k1, k2 = cameras["front"]
    Kf = K.copy()
    Kf[0, 0] *= 1.005
    Kf[1, 1] *= 1.005
    out["front focal length +0.5 %"] = dict(cameras, front=(Kf, R, C, k1, k2))
    K, R, C, k1, k2 = cameras["top"]
    out["top camera turned 0.1° about its x axis (along the epipolar lines)"] = dict(cameras, top=(K, rot_x(0.1) @ R, C, k1, k2))
    out["top camera turned 0.1° about its y axis (across the epipolar lines)"] = dict(cameras, top=(K, rot_y(0.1) @ R, C, k1, k2))
    out["distortion omitted"] = {name: (K, R, C, 0.0, 0.0) for name, (K, R, C, _, _) in cameras.items()}
    return out


def reconstruct(vibrissa, top, front, cal, peg_mm, out, extra=()):
    """Runs vibrissa reconstruct; returns (exit code, stdout + stderr)."""
    cmd = [vibrissa, "reconstruct", "--top", top, "--front", front, "--calibration", cal,
           "--peg-mm", *[f"{v:.9g}" for v in peg_mm], "-o", out, "--report", out.replace(".h5", "_report.json"), *extra]
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r.returncode, (r.stdout + r.stderr).strip()


def evaluate(truth, rec, dropped, swapped):
    ok = rec["reconstructed"].astype(bool)
    c_true = truth["contact"].astype(bool)
    c_rec = rec["contact"].astype(bool)
    base_um = np.linalg.norm(rec["base"][ok] - truth["base"][ok], axis=1) * 1e6
    dth = np.abs(wrap_deg(rec["theta"][ok] - truth["theta"][ok]))
    dph = np.abs(wrap_deg(rec["phi"][ok] - truth["phi"][ok]))
    free = ok & ~c_true
    dze = np.abs(wrap_deg(rec["zeta"][free] - truth["zeta"][free]))
    both = ok & c_true & c_rec
    cp_um = np.linalg.norm(rec["contact_point"][both] - truth["contact_point"][both], axis=1) * 1e6
    swapped_idx = np.array(sorted(swapped), dtype=int)
    return {
        "frames": int(len(ok)), "reconstructed": int(ok.sum()),
        "dropped_flagged": int(sum(not ok[i] for i in dropped)), "dropped": len(dropped),
        "swaps_flagged": int((~ok[swapped_idx]).sum()) if len(swapped_idx) else 0, "swaps": len(swapped),
        "base_um_median": float(np.median(base_um)), "base_um_p95": float(np.percentile(base_um, 95)),
        "theta_deg_median": float(np.median(dth)), "theta_deg_p95": float(np.percentile(dth, 95)),
        "phi_deg_median": float(np.median(dph)), "phi_deg_p95": float(np.percentile(dph, 95)),
        "zeta_free_deg_median": float(np.median(dze)), "zeta_free_deg_p95": float(np.percentile(dze, 95)),
        "contact_um_median": float(np.median(cp_um)) if len(cp_um) else float("nan"),
        "contact_um_p95": float(np.percentile(cp_um, 95)) if len(cp_um) else float("nan"),
        "contact_missed": int((ok & c_true & ~c_rec).sum()), "contact_extra": int((ok & ~c_true & c_rec).sum()),
        "contact_true": int((ok & c_true).sum()),
        "reprojection_px_median": float(np.nanmedian(rec["reprojection_px"][ok])) if ok.any() else float("nan"),
        "reprojection_px_p95": float(np.nanpercentile(rec["reprojection_px"][ok], 95)) if ok.any() else float("nan"),
    }


def load(path, names):
    with h5py.File(path, "r") as f:
        return {k: f[k][()] for k in names if k in f}


def mu_of(vibrissa, trial, out):
    run([vibrissa, "trial", trial, "--out", out, "--no-figures"])
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)["friction"]["median"]


def inconsistent_inputs(a, truth, peg_mm, cal, names):
    """At 0.5 px: wrong calibrations, views out of step, swapped views. Each is run as given (exit code and
    message) and, when refused, again with the checks relaxed to measure what the trial would have been."""
    d = os.path.join(a.out, "checks")
    os.makedirs(d, exist_ok=True)
    relaxed = ["--min-yield", "0", "--max-unpaired", "1", "--max-epipolar-px", "1e6", "--max-reprojection-px", "1e6"]
    rng = np.random.default_rng(a.seed)
    dropped, swapped, _ = write_views(truth, 0.5, rng, d)
    top, front = os.path.join(d, "top.csv"), os.path.join(d, "front_dlc.csv")
    cases = [("correct calibration", top, front, cal, [])]
    for label, cams in wrong_calibrations().items():
        path = os.path.join(d, "cal_" + str(len(cases)) + ".json")
        calibration_json(path, cams)
        cases.append((label, top, front, path, []))
    cases.append(("--top and --front swapped", front, top, cal, []))
    sd = os.path.join(d, "shifted")
    os.makedirs(sd, exist_ok=True)
    write_views(truth, 0.5, np.random.default_rng(a.seed), sd, front_shift=40)
    stop, sfront = os.path.join(sd, "top.csv"), os.path.join(sd, "front_dlc.csv")
    cases.append(("front video starts 40 frames later", stop, sfront, cal, []))
    cases.append(("... with --front-frame-offset 40", stop, sfront, cal, ["--front-frame-offset", "40"]))
    out = []
    for k, (label, t, f, c, extra) in enumerate(cases):
        rec_path = os.path.join(d, f"case{k}.h5")
        code, msg = reconstruct(a.vibrissa, t, f, c, peg_mm, rec_path, extra)
        row = {"case": label, "exit": code, "message": msg.splitlines()[-1] if code else ""}
        if code:
            row["message"] = " ".join(line.strip() for line in msg.splitlines() if line.strip().startswith("-"))
            reconstruct(a.vibrissa, t, f, c, peg_mm, rec_path, extra + relaxed)
        rec = load(rec_path, names)
        ok = rec["reconstructed"].astype(bool)
        n = min(len(ok), len(truth["base"]))
        ok = ok[:n]
        base = np.linalg.norm(rec["base"][:n] - truth["base"][:n], axis=1) * 1e6
        row["reconstructed"] = f"{int(ok.sum())}/{len(rec['reconstructed'])}"
        row["reprojection_px_median"] = float(np.nanmedian(rec["reprojection_px"][:n][ok])) if ok.any() else float("nan")
        row["base_um_median"] = float(np.median(base[ok])) if ok.any() else float("nan")
        out.append(row)
        print(json.dumps(row), file=sys.stderr)
    return out


def three_cameras(a, truth, peg_mm, names):
    """Three cameras against two at 0.5 px: the errors of each pair and of all three on the same tracks, then
    the calibration errors and swapped views of the two-view table with the third view added."""
    d = os.path.join(a.out, "three")
    os.makedirs(d, exist_ok=True)
    dropped, swapped, _ = write_views(truth, 0.5, np.random.default_rng(a.seed), d)
    write_side(truth, 0.5, np.random.default_rng(a.seed + 1000), d)
    cal3 = os.path.join(d, "calibration3.json")
    calibration_json(cal3, CAMERAS3)
    files = {"top": os.path.join(d, "top.csv"), "front": os.path.join(d, "front_dlc.csv"),
             "side": os.path.join(d, "side.csv")}
    relaxed = ["--min-yield", "0", "--max-unpaired", "1", "--max-epipolar-px", "1e6", "--max-reprojection-px", "1e6"]

    def run3(label, views, cal, k):
        out = os.path.join(d, f"case{k}.h5")
        cmd = [a.vibrissa, "reconstruct", *[x for n, f in views for x in ("--view", f"{n}={f}")], "--calibration", cal,
               "--peg-mm", *[f"{v:.9g}" for v in peg_mm], "-o", out, "--report", out.replace(".h5", "_report.json")]
        r = subprocess.run(cmd, capture_output=True, text=True)
        msg = " ".join(line.strip() for line in (r.stdout + r.stderr).splitlines() if line.strip().startswith("-"))
        if r.returncode:
            subprocess.run(cmd + relaxed, capture_output=True, text=True)
        rec = load(out, names)
        with open(out.replace(".h5", "_report.json")) as f:
            report = json.load(f)
        row = evaluate(truth, rec, dropped, swapped)
        row.update(case=label, exit=r.returncode, message=msg,
                   view_reprojection=report["checks"]["view_reprojection_px_median"])
        print(json.dumps(row), file=sys.stderr)
        return row

    rows = []
    for k, pair in enumerate((("top", "front"), ("top", "side"), ("front", "side"), ("top", "front", "side"))):
        rows.append(run3(" + ".join(pair), [(n, files[n]) for n in pair], cal3, k))
    for k, (label, cams) in enumerate(wrong_calibrations(CAMERAS3).items()):
        path = os.path.join(d, f"cal3_{k}.json")
        calibration_json(path, cams)
        rows.append(run3(label, list(files.items()), path, 10 + k))
    swapped_views = [("top", files["front"]), ("front", files["top"]), ("side", files["side"])]
    rows.append(run3("top and front views swapped", swapped_views, cal3, 20))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--vibrissa", default="build/bin/vibrissa")
    ap.add_argument("--out", default="/tmp/recon_validation")
    ap.add_argument("--noise", type=float, nargs="+", default=[0.0, 0.25, 0.5, 1.0, 2.0])
    ap.add_argument("--duration", type=float, default=1.5)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--figure", default="")
    ap.add_argument("--reconstruct-args", default="", help="extra options for vibrissa reconstruct, e.g. '--fit-segments 8'")
    ap.add_argument("--only-three", action="store_true", help="only the three-camera comparison (no noise sweep, no checks)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    syn = os.path.join(a.out, "synth.h5")
    run([a.vibrissa, "synth", syn, "--duration", str(a.duration), "--shapes", "--mu", str(MU_TRUE)])
    names = ["time", "base", "theta", "phi", "zeta", "contact", "contact_point", "shape", "edges",
             "reconstructed", "reprojection_px"]
    truth = load(syn, names)
    peg_mm = truth["edges"][0][:3] * 1e3
    cal = os.path.join(a.out, "calibration.json")
    calibration_json(cal)
    mu_truth_trial = mu_of(a.vibrissa, syn, os.path.join(a.out, "truth_results"))
    rows = []
    if a.only_three:
        a.noise = []
    for sigma in a.noise:
        d = os.path.join(a.out, f"noise_{sigma:g}px")
        os.makedirs(d, exist_ok=True)
        rng = np.random.default_rng(a.seed)
        dropped, swapped, ends_lost = write_views(truth, sigma, rng, d)
        rec_path = os.path.join(d, "reconstructed.h5")
        run([a.vibrissa, "reconstruct", "--top", os.path.join(d, "top.csv"), "--front",
             os.path.join(d, "front_dlc.csv"), "--calibration", cal, "--peg-mm", *[f"{v:.9g}" for v in peg_mm],
             "-o", rec_path, "--report", os.path.join(d, "report.json"), *a.reconstruct_args.split()])
        rec = load(rec_path, names)
        row = evaluate(truth, rec, dropped, swapped)
        row["noise_px"] = sigma
        ok = rec["reconstructed"].astype(bool)
        lost = np.zeros(len(ok), bool)
        lost[sorted(ends_lost)] = True
        err = np.linalg.norm(rec["base"] - truth["base"], axis=1) * 1e6
        row["base_um_median_end_lost"] = float(np.median(err[ok & lost])) if (ok & lost).any() else float("nan")
        row["base_um_median_intact"] = float(np.median(err[ok & ~lost]))
        row["frames_end_lost"] = int((ok & lost).sum())
        row["mu"] = mu_of(a.vibrissa, rec_path, os.path.join(d, "results"))
        rows.append(row)
        print(json.dumps(row), file=sys.stderr)
    checks = [] if a.only_three else inconsistent_inputs(a, truth, peg_mm, cal, names)
    three = three_cameras(a, truth, peg_mm, names)
    with open(os.path.join(a.out, "validation.json"), "w") as f:
        json.dump({"mu_true": MU_TRUE, "mu_from_true_trial": mu_truth_trial, "rows": rows, "checks": checks,
                   "three_cameras": three}, f, indent=1)
    print(f"truth: mu = {MU_TRUE}; `vibrissa trial` on the synthetic trial itself: median mu = {mu_truth_trial:.4f}")
    print("| noise [px] | reconstructed | dropped flagged | swaps flagged | base [µm] median / p95 | θ [°] median / p95 "
          "| φ [°] median / p95 | ζ free [°] median / p95 | contact point [µm] median / p95 | contact missed / extra "
          "| median μ |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['noise_px']:g} | {r['reconstructed']}/{r['frames']} | {r['dropped_flagged']}/{r['dropped']} "
              f"| {r['swaps_flagged']}/{r['swaps']} | {r['base_um_median']:.1f} / {r['base_um_p95']:.1f} "
              f"| {r['theta_deg_median']:.2f} / {r['theta_deg_p95']:.2f} | {r['phi_deg_median']:.2f} / {r['phi_deg_p95']:.2f} "
              f"| {r['zeta_free_deg_median']:.2f} / {r['zeta_free_deg_p95']:.2f} "
              f"| {r['contact_um_median']:.0f} / {r['contact_um_p95']:.0f} "
              f"| {r['contact_missed']} / {r['contact_extra']} of {r['contact_true']} | {r['mu']:.3f} |")
    print()
    print("| noise [px] | reprojection [px] median / p95 | base [µm] median, frames with an end lost in one view "
          "(n) / intact |")
    print("|---|---|---|")
    for r in rows:
        print(f"| {r['noise_px']:g} | {r['reprojection_px_median']:.3f} / {r['reprojection_px_p95']:.3f} "
              f"| {r['base_um_median_end_lost']:.1f} ({r['frames_end_lost']}) / {r['base_um_median_intact']:.1f} |")
    print()
    print("| input (0.5 px noise) | exit | reconstructed | reprojection [px] median | base [µm] median | message |")
    print("|---|---|---|---|---|---|")
    for c in checks:
        msg = c["message"].replace("|", "/").replace("\n", " ")
        print(f"| {c['case']} | {c['exit']} | {c['reconstructed']} | {c['reprojection_px_median']:.2f} "
              f"| {c['base_um_median']:.0f} | {msg} |")
    print()
    print("| views (0.5 px noise) | exit | reconstructed | base [µm] median / p95 | θ [°] median / p95 "
          "| φ [°] median / p95 | reprojection [px] median: all (per view) | message |")
    print("|---|---|---|---|---|---|---|---|")
    for r in three:
        per_view = ", ".join(f"{n} {v:.2f}" if v is not None else f"{n} -" for n, v in r["view_reprojection"].items())
        msg = r["message"].replace("|", "/")
        print(f"| {r['case']} | {r['exit']} | {r['reconstructed']}/{r['frames']} "
              f"| {r['base_um_median']:.1f} / {r['base_um_p95']:.1f} | {r['theta_deg_median']:.2f} / {r['theta_deg_p95']:.2f} "
              f"| {r['phi_deg_median']:.2f} / {r['phi_deg_p95']:.2f} | {r['reprojection_px_median']:.2f} ({per_view}) "
              f"| {msg} |")
    if a.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        noise = [r["noise_px"] for r in rows]
        fig, ax = plt.subplots(1, 3, figsize=(12, 3.6))
        ax[0].plot(noise, [r["base_um_median"] for r in rows], "o-", label="base, median")
        ax[0].plot(noise, [r["base_um_p95"] for r in rows], "o--", label="base, 95th pct")
        ax[0].plot(noise, [r["contact_um_median"] for r in rows], "s-", label="contact point, median")
        ax[0].plot(noise, [r["contact_um_p95"] for r in rows], "s--", label="contact point, 95th pct")
        ax[0].set(xlabel="pixel noise σ [px]", ylabel="error [µm]", title="positions")
        ax[0].legend(fontsize=7)
        for key, lab in (("theta", "θ"), ("phi", "φ"), ("zeta_free", "ζ (no contact)")):
            ax[1].plot(noise, [r[key + "_deg_median"] for r in rows], "o-", label=lab + ", median")
        ax[1].set(xlabel="pixel noise σ [px]", ylabel="error [°]", title="angles")
        ax[1].legend(fontsize=7)
        ax[2].plot(noise, [r["mu"] for r in rows], "o-", label="from reconstruction")
        ax[2].axhline(MU_TRUE, color="k", ls=":", label=f"truth μ = {MU_TRUE}")
        ax[2].axhline(mu_truth_trial, color="gray", ls="--", label="from the synthetic trial")
        ax[2].set(xlabel="pixel noise σ [px]", ylabel="median μ", title="vibrissa trial, end to end")
        ax[2].legend(fontsize=7)
        fig.tight_layout()
        os.makedirs(os.path.dirname(a.figure) or ".", exist_ok=True)
        fig.savefig(a.figure, dpi=110)


if __name__ == "__main__":
    main()
