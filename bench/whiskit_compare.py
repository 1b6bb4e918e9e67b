#!/usr/bin/env python3
"""The WHISKiT comparison of issue 27 point 7 (docs/performance.md, "The array and WHISKiT").

Two sub-commands, both driven by the same `vibrissa array` configuration (the default scene: the 31 right
whiskers of Towal 2011, the default whisk, +/-30 deg at 8 Hz about a 10 deg set point with Knutsen's slopes, the
default peg at (20, -8, -3) mm), 1 s at 1 kHz:

  inputs DIR   writes the inputs WHISKiT (SeNSE-lab/whiskitphysics, built separately; nothing of it is in this
               repository) needs to simulate the same whiskers and whisk, in the layout its binary reads relative
               to its working directory: DIR/data/whisker_param_average_rat/{param_name, param_side_row_col,
               param_s_a, param_angles, param_bp_pos, whisking_init_angle, whisking_trajectory}.csv, the rat-head
               mesh copied from a WHISKiT checkout (--whiskit-data), and DIR/run/ to run it from. The files are
               written from vibrissa's own array (names, base points, S, A and the angles of every 1 ms step), in
               the formats WHISKiT's readers expect (read in its src/Whisker.cpp, src/Rat.cpp, src/Simulation.cpp):
               angles in radians in the placement Rz(theta - 90 deg) Ry(-phi) Rx(zeta) of the data sheet, 20 link
               angles per whisker, and per whisker a row of 3 world-frame angular velocities [rad/s] of the
               follicle per 1 ms step (here the exact rotation between consecutive steps over the step).
               Prints the WHISKiT command line that places the peg where vibrissa's is.
  ours         runs `vibrissa array CONFIG --dynamics` on the same scene under /usr/bin/time -v and prints its
               CPU and wall time and the load average.
  peg-whisker NAME|all
               one whisker of the scene (e.g. C1R: the array's shape, placement and whisk, checked against the
               array's) or every one in turn through `vibrissa.simulate_dynamics` against the scene's peg with
               WHISKiT's radius (1 mm) and friction (0.25), 1 s at 1 kHz, N = 100, and prints the CPU time, steps
               and events: the contact side, while `vibrissa array --dynamics` does not touch objects.

  air NAME...  WHISKiT's in-air run (--OBJECT 0 --SAVE 1, outputs in --whiskit-output) against vibrissa for the
               named whiskers (e.g. C1R), 1 s: WHISKiT's reported base force and moment, the same fitted by the
               whisking frequency's first 10 harmonics over 0.25-1 s (the steady whisk; what is left over is the
               jitter of its sampled constraint force), and Newton's law on its own links (sum of m a and of the
               moments of m a, from finite differences of its saved link positions and its link masses); vibrissa
               with its defaults and "matched" (WHISKiT's 20 links, E, radii and mass; also with WHISKiT's damping
               ratio, with E / 20 as its E I / L joint stiffness would give, and with E scaled so that it lags as
               WHISKiT does); the tips' lag behind the rigidly turned rest shape; Newton's law on vibrissa's matched
               run; the harmonics at f and 2 f.
               Units: WHISKiT works in mm and kg, so its force is in mN and its moment in uN m (both world axes,
               on its follicle body, about the base point).
  air-steady NAME...
               the same for a WHISKiT run on `inputs DIR --steady-rate R` (every follicle turned at a constant R
               rad/s about its first step's axis): its saved force against Newton on its links over 0-10, 10-30,
               30-60 ms and the rest (the scatter of its saved force without the whisk's 1 ms steps).

Usage: /usr/bin/python3 bench/whiskit_compare.py inputs /tmp/whiskit_inputs --whiskit-data PATH/code/data
       /usr/bin/python3 bench/whiskit_compare.py ours [--vibrissa build/bin/vibrissa] [--threads 1] [--links N] [--mu M]
       /usr/bin/python3 bench/whiskit_compare.py peg-whisker C1R [--duration 1] [--mu 0.25] [--peg-radius-mm 1]
       /usr/bin/python3 bench/whiskit_compare.py air A0R B0R C0R C1R D0R [--whiskit-output DIR] [--inputs DIR]
       /usr/bin/python3 bench/whiskit_compare.py inputs /tmp/steady --steady-rate 5   # then WHISKiT --OBJECT 0
       /usr/bin/python3 bench/whiskit_compare.py air-steady C1R --whiskit-output DIR --inputs /tmp/steady
(PYTHONPATH=build/python for all but `ours`.)"""
import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

import numpy as np

STEP_S = 1e-3            # WHISKiT's TIME_STEP (its Parameters.cpp); the whisking file has one column triple per step
LINKS = 20               # WHISKiT's NUM_LINKS
DURATION_S = 1.0
EXTRA_STEPS = 10         # WHISKiT stops at min(TIME_STOP, (steps - 1) * TIME_STEP): give it a few more steps
# WHISKiT puts the array origin at (0, 26, 4) mm from its head (Rat.h originOffset) and its peg (OBJECT 1, a
# cylinder of radius 1 mm along z, Simulation.cpp) at (20, 25, 0) mm. Head position that puts vibrissa's head
# frame H at world = H + (0, 33, 0) mm, i.e. WHISKiT's peg axis through vibrissa's peg point (20, -8) mm.
WHISKIT_HEAD_POSITION_MM = (0.0, 7.0, -4.0)
# WHISKiT's follicle joint (Whisker.cpp, motorConstraint) limits each Euler angle of the follicle, relative to its
# pose at t = 0, to [-60, 30] deg on the right side. The default whisk starts fully retracted and sweeps 60 deg, so
# it would run into the limit at full protraction (measured: the follicle stops 1.5-1.8 deg short). Starting the
# same whisk at phase 60 deg (dtheta = -5 deg, protracting) keeps every whisker's follicle inside the limits.
PHASE_DEG = 60.0


def scene(frames: int, end_s: float, peg: bool = True, links: int = 0, mu: float = 0.0) -> dict:
    """The comparison's `vibrissa array` config: the default scene over `frames` frames to `end_s` (links > 0:
    that many links per whisker instead of the default 100; mu > 0: the peg with that friction, the array's
    frictional edge mode; else frictionless)."""
    import vibrissa
    config = vibrissa.default_array_config()
    config["time"] = {"start_s": 0.0, "end_s": end_s, "frames": frames}
    config["whisking"]["phase_deg"] = PHASE_DEG
    if not peg:  # far out of reach: only the kinematics are wanted
        config["objects"] = [{"type": "peg", "frame": "world", "point_mm": [1000.0, 1000.0, 0.0]}]
    config["output"] = {"render_count": 1}
    if links > 0:
        config["solver"]["links"] = links
    config["solver"]["mode"] = "frictional_edge" if mu > 0.0 else "edge"
    if mu > 0.0:
        config["solver"]["mu"] = mu
    return config


def rotation(theta, phi, zeta):
    """Rz(theta - 90 deg) Ry(-phi) Rx(zeta) (data sheet section 2), angles in rad, shape (..., 3, 3)."""
    def rz(a):
        c, s = np.cos(a), np.sin(a)
        z, o = np.zeros_like(a), np.ones_like(a)
        return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)

    def ry(a):
        c, s = np.cos(a), np.sin(a)
        z, o = np.zeros_like(a), np.ones_like(a)
        return np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2)

    def rx(a):
        c, s = np.cos(a), np.sin(a)
        z, o = np.zeros_like(a), np.ones_like(a)
        return np.stack([np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2)
    return rz(theta - np.pi / 2) @ ry(-phi) @ rx(zeta)


def rotation_vector(R):
    """log of rotation matrices (..., 3, 3) -> rotation vectors (..., 3)."""
    cos = np.clip((np.trace(R, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0)
    angle = np.arccos(cos)
    axis = np.stack([R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0], R[..., 1, 0] - R[..., 0, 1]], -1)
    scale = np.where(angle > 1e-12, angle / (2.0 * np.sin(np.maximum(angle, 1e-12))), 0.5)
    return axis * scale[..., None]


def rotation_matrix(v):
    """exp of a rotation vector v (3,) [rad] (Rodrigues)."""
    angle = float(np.linalg.norm(v))
    if angle < 1e-15:
        return np.eye(3)
    k = np.asarray(v) / angle
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def parabola_nodes(S_mm: float, A_per_mm: float, count: int):
    """`count` points at equal arc length along (x, A x^2) from x = 0 to arc length S (mm)."""
    x = np.linspace(0.0, S_mm, 20001)
    y = A_per_mm * x ** 2
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    targets = np.linspace(0.0, S_mm, count)
    xs = np.interp(targets, s, x)
    return np.stack([xs, A_per_mm * xs ** 2], -1)


def link_angles(S_mm: float, A_per_mm: float):
    """WHISKiT's param_angles row: 20 relative link angles [rad] of the parabola's chords, the first link along
    the follicle's x axis (angle 0), the k-th (k >= 1) at its chord's direction; negative = toward -y of the link
    frame, which WHISKiT's placement takes to -z of the whisker frame (the data sheet's (x, 0, -A x^2))."""
    nodes = parabola_nodes(S_mm, A_per_mm, LINKS + 1)
    d = np.diff(nodes, axis=0)
    absolute = np.arctan2(d[:, 1], d[:, 0])
    absolute[0] = 0.0
    relative = np.diff(np.concatenate([[0.0], absolute]))
    return -relative


def write_csv(path: pathlib.Path, rows, fmt="%.9g"):
    with open(path, "w") as f:
        for row in rows:
            f.write(",".join(fmt % v if not isinstance(v, str) else v for v in row) + "\n")


def cmd_inputs(args) -> int:
    import vibrissa
    steps = int(round(DURATION_S / STEP_S)) + EXTRA_STEPS
    frames = steps + 1
    result = vibrissa.simulate_array(scene(frames, steps * STEP_S, peg=False))
    names = [str(n) for n in result["whisker"]]
    row, column = result["row"].astype(int), result["column"].astype(int)
    theta, phi, zeta = result["theta"], result["phi"], result["zeta"]      # (whiskers, frames), rad
    base_mm = result["base_W"][0, :, 0, :] * 1e3
    R = rotation(theta, phi, zeta)                                          # (whiskers, frames, 3, 3)
    shown = int(result["render/frame"][0])                                  # the rendered frame
    rest_mm = result["render/rest"][0].astype(float) * 1e3                  # (whiskers, nodes, 3) there
    rest_base_mm = result["base_W"][0, :, shown, :] * 1e3

    # S and A of every whisker from vibrissa's rest shape: arc length and the parabola through the tip.
    S, A, fit = [], [], []
    for w in range(len(names)):
        local = (rest_mm[w] - rest_base_mm[w]) @ R[w, shown]  # rows: R^T (p - base), the whisker frame
        S.append(float(np.sum(np.linalg.norm(np.diff(rest_mm[w], axis=0), axis=1))))
        x, z = local[:, 0], local[:, 2]
        A.append(float(-np.sum(z * x ** 2) / np.sum(x ** 4)))
        fit.append(float(np.max(np.abs(np.hypot(local[:, 1], z + A[-1] * x ** 2)))))
    print(f"{len(names)} whiskers; rest shapes vs (x, 0, -A x^2) in the Rz Ry Rx placement: largest gap "
          f"{max(fit) * 1e3:.2g} um")

    out = pathlib.Path(args.dir)
    data = out / "data" / "whisker_param_average_rat"
    data.mkdir(parents=True, exist_ok=True)
    (out / "run").mkdir(exist_ok=True)
    (out / "data" / "object").mkdir(exist_ok=True)
    head = pathlib.Path(args.whiskit_data) / "object" / "NewRatHead.obj"
    if head.exists():
        shutil.copy(head, out / "data" / "object" / "NewRatHead.obj")
    else:
        print(f"warning: {head} not found: WHISKiT needs its rat-head mesh at {out}/data/object/", file=sys.stderr)
    whiskit_names = ["R" + n[:-1] for n in names]             # A0R -> RA0
    with open(data / "param_name.csv", "w") as f:
        f.write("".join(n + "\n" for n in whiskit_names))
    write_csv(data / "param_side_row_col.csv", [(1, r, c) for r, c in zip(row, column)], "%d")
    write_csv(data / "param_s_a.csv", zip(S, A))
    write_csv(data / "param_angles.csv", [link_angles(s, a) for s, a in zip(S, A)])
    write_csv(data / "param_bp_pos.csv", base_mm)
    write_csv(data / "param_bp_angles.csv", np.stack([theta[:, 0], phi[:, 0], zeta[:, 0]], -1))
    write_csv(data / "whisking_init_angle.csv", np.stack([theta[:, 0], phi[:, 0], zeta[:, 0]], -1))
    # angular velocity over step k (k = 1..steps): the rotation from frame k-1 to frame k, world frame, / step
    omega = rotation_vector(R[:, 1:] @ np.swapaxes(R[:, :-1], -1, -2)) / STEP_S   # (whiskers, steps, 3)
    if args.steady_rate is not None:   # a steady rotation instead: the first step's axis at a constant rate
        axis = omega[:, :1] / np.linalg.norm(omega[:, :1], axis=-1, keepdims=True)
        omega = np.broadcast_to(axis * args.steady_rate, omega.shape)
    write_csv(data / "whisking_trajectory.csv", omega.reshape(len(names), -1))
    print(f"wrote {data} ({steps} steps of {STEP_S * 1e3:g} ms); peak |omega| {np.abs(omega).max():.3g} rad/s")
    position = " ".join(f"{v:g}" for v in WHISKIT_HEAD_POSITION_MM)
    print("run from", out / "run", ":")
    print(f"  /usr/bin/time -v WHISKIT/code/build/whiskit --MODEL_TYPE 0 --ACTIVE 1 --OBJECT 1 --SPEED 0 "
          f"--POSITION {position} --ORIENTATION 0 0 0 --TIME_STOP {DURATION_S + STEP_S / 2:g} --PRINT 0 "
          f"--SAVE 1 --dir_out ../output/peg --WHISKER_NAMES {' '.join(whiskit_names)}")
    return 0


def cmd_ours(args) -> int:
    frames = int(round(DURATION_S / STEP_S)) + 1
    with tempfile.TemporaryDirectory() as tmp:
        config = pathlib.Path(tmp) / "scene.json"
        config.write_text(json.dumps(scene(frames, DURATION_S, peg=True, links=args.links, mu=args.mu)))
        command = [args.vibrissa, "array", str(config), "--dynamics", "--no-figures", "--threads",
                   str(args.threads), "--out", str(pathlib.Path(tmp) / "out")]
        load = os.getloadavg()[0]
        run = subprocess.run(["/usr/bin/time", "-v"] + command, capture_output=True, text=True)
        if run.returncode != 0:
            print(run.stdout, run.stderr, file=sys.stderr)
            return 1
        times = {}
        for line in run.stderr.splitlines():
            key, _, value = line.strip().partition(": ")
            times[key] = value
        summary = json.loads((pathlib.Path(tmp) / "out" / "summary.json").read_text())
    user, system = float(times["User time (seconds)"]), float(times["System time (seconds)"])
    print(" ".join(command[:2]) + " SCENE.json " + " ".join(command[3:-2]))
    print(f"31 whiskers x {DURATION_S:g} s, N = {args.links or 100}, mu {args.mu:g}, {frames} frames: "
          f"CPU {user + system:.2f} s (user {user:.2f}, "
          f"sys {system:.2f}), wall {times['Elapsed (wall clock) time (h:mm:ss or m:ss)']}, "
          f"load average {load:.1f} -> {os.getloadavg()[0]:.1f}")
    print("dynamics:", json.dumps(summary.get("dynamics", {}))[:400])
    return 0


def array_kinematics(frames: int = 101):
    """The scene's array over its first 0.1 s (placements and angles only): the input of array_whisker_case."""
    import vibrissa
    return vibrissa.simulate_array(scene(frames, 0.1, peg=False))


def array_whisker_case(name: str, peg_radius_m: float, mu: float, result=None, **whisker_fields):
    """One whisker of the scene as `vibrissa.simulate_dynamics` arguments: the whisker (S, A, Belli's base radius,
    taper 15, placed as the array places it, vibrissa's angles; `whisker_fields` replace or add `make_whisker`
    fields, e.g. links, radii, youngs_modulus), the whisk with its row's slopes (fitted to the array's own angle
    series, so they are the array's), and the scene's peg with a radius."""
    import vibrissa
    result = array_kinematics() if result is None else result
    frames = len(result["time"])
    names = [str(n) for n in result["whisker"]]
    w = names.index(name)
    row, column = int(result["row"][w]), int(result["column"][w])
    theta, phi, zeta = result["theta"][w], result["phi"][w], result["zeta"][w]
    base_m = result["base_W"][0, w, 0, :]
    shown = int(result["render/frame"][0])
    rest = result["render/rest"][0, w].astype(float)
    S = float(np.sum(np.linalg.norm(np.diff(rest, axis=0), axis=1)))
    local = (rest - result["base_W"][0, w, shown, :]) @ rotation(theta, phi, zeta)[shown]
    A = float(-np.sum(local[:, 2] * local[:, 0] ** 2) / np.sum(local[:, 0] ** 4))      # 1/m
    whisking = scene(frames, 0.1)["whisking"]
    t = np.linspace(0.0, 0.1, frames)
    dtheta = np.radians(whisking["set_point_deg"] - whisking["amplitude_deg"] *
                        np.cos(2 * np.pi * whisking["frequency_Hz"] * t + np.radians(whisking["phase_deg"])))
    theta_rest = float(np.mean(theta - dtheta))
    k_phi = float(np.polyfit(dtheta, phi, 1)[0])
    k_zeta = float(np.polyfit(dtheta, zeta, 1)[0])
    phi_rest = float(np.mean(phi - k_phi * dtheta))
    zeta_rest = float(np.mean(zeta - k_zeta * dtheta))
    d_base_mm = 0.041 + 0.002 * S * 1e3 + 0.011 * row - 0.0039 * column       # Belli 2018 (docs/array.md)
    fields = {"links": 100, "base_radius": d_base_mm / 2 * 1e-3, "taper_ratio": 15}
    if "radii" in whisker_fields:
        fields = {"links": fields["links"]}
    fields.update(whisker_fields)
    whisker = vibrissa.make_whisker(length=S, curvature=A, **fields,
                                    pose={"base": base_m.tolist(), "theta": theta_rest - np.pi / 2,
                                          "phi": phi_rest, "zeta": zeta_rest - np.pi / 2})
    peg = scene(frames, 0.1)["objects"][0]
    objects = [{"type": "peg", "point": [v * 1e-3 for v in peg["point_mm"]], "direction": [0, 0, 1],
                "radius": peg_radius_m, "friction_coefficient": mu}]
    whisking = dict(whisking, k_phi=k_phi, k_zeta=k_zeta)
    whisking.pop("slopes", None)
    at_shown = vibrissa.make_whisker(length=S, curvature=A, links=100,
                                     pose={"base": result["base_W"][0, w, shown, :].tolist(),
                                           "theta": float(theta[shown]) - np.pi / 2, "phi": float(phi[shown]),
                                           "zeta": float(zeta[shown]) - np.pi / 2})
    gap = float(np.abs(np.asarray(at_shown.rest_nodes_W) - rest).max())
    return whisker, whisking, objects, gap


def cmd_peg_whisker(args) -> int:
    import resource
    import vibrissa
    kinematics = array_kinematics()
    names = [str(n) for n in kinematics["whisker"]] if args.name == "all" else [args.name]
    total, load = 0.0, os.getloadavg()[0]
    for name in names:
        whisker, whisking, objects, gap = array_whisker_case(name, args.peg_radius_mm * 1e-3, args.mu, kinematics)
        print(f"{name}: shape and placement as the array's to {gap * 1e6:.2g} um; whisking {json.dumps(whisking)}")
        start = resource.getrusage(resource.RUSAGE_SELF)
        result = vibrissa.simulate_dynamics(whisker, args.duration, 1000.0, whisking=whisking, objects=objects)
        end = resource.getrusage(resource.RUSAGE_SELF)
        cpu = (end.ru_utime - start.ru_utime) + (end.ru_stime - start.ru_stime)
        total += cpu
        kinds = [e["type"] for e in result.events]
        print(f"{name} against the peg (radius {args.peg_radius_mm:g} mm, mu {args.mu:g}), {args.duration:g} s, "
              f"1 kHz, N = 100: CPU {cpu:.2f} s, steps {result.summary['steps']} "
              f"(rejected {result.summary['rejected_steps']}), status {result.summary['status']}, events "
              f"{ {k: kinds.count(k) for k in sorted(set(kinds))} }", flush=True)
    print(f"{len(names)} whisker(s): CPU {total:.2f} s in all, load average {load:.1f} -> {os.getloadavg()[0]:.1f}")
    return 0


# WHISKiT's whisker model (read in its src/Whisker.cpp and src/Parameters.cpp; numbers only): E 5 GPa; density
# linear in arc length from 1260 kg/m3 at the base to 1690 at the tip, each link's taken at its distal end; base
# radius from Belli 2018's base diameter (as vibrissa's array); tip radius (r_base - k S) / 2, at least 1.5 um, with
# its fitted slope k = 0.0012 + 0.00017 row - 0.000066 col + 0.00011 col^2 (S, radii in mm); radius linear in
# between; each link a frustum whose mass acts at its mid-length.
WHISKIT_E_PA = 5e9
WHISKIT_DENSITY_KG_M3 = (1260.0, 1690.0)
WHISKIT_OUTPUT = "/work/whiskit_inputs/peg/output/air"
WHISKIT_INPUTS = "/work/whiskit_inputs/peg"
STEADY_FROM_S = 0.25     # whole whisk cycles from here to 1 s (6 of 8 Hz): after both tools' start
HARMONICS = 10           # of the whisking frequency, in the fit of the steady whisk (up to 80 Hz)


def whiskit_links(row: int, column: int, S_mm: float, links: int = LINKS):
    """WHISKiT's radii at the link ends [m] (links + 1) and link masses [kg] of a whisker."""
    r_base = (0.041 + 0.002 * S_mm + 0.011 * row - 0.0039 * column) / 2
    slope = 0.0012 + 0.00017 * row - 0.000066 * column + 0.00011 * column ** 2
    r_tip = max((r_base - slope * S_mm) / 2, 0.0015)
    radii = np.linspace(r_base, r_tip, links + 1)
    length = S_mm / links
    rho = (WHISKIT_DENSITY_KG_M3[0] + np.diff(WHISKIT_DENSITY_KG_M3)[0] * np.arange(1, links + 1) / links) * 1e-9
    mass = rho * np.pi * length / 3 * (radii[:-1] ** 2 + radii[:-1] * radii[1:] + radii[1:] ** 2)   # kg/mm3 mm3
    return radii * 1e-3, mass


def read_whiskit_air(output: pathlib.Path, name: str):
    """WHISKiT's --SAVE 1 outputs of one whisker (e.g. RC1): times [s], base force [N], moment [N m] (world axes,
    about the base point) and positions of its base and link centres [m], (frames, links + 1, 3). Row k is the state
    after k steps of 1 ms; its force and moment are those of the last 10 us internal step (row 0: none yet)."""
    names = [line.strip().rstrip(",") for line in open(output / "whisker_ID.csv")]
    w = names.index(name)

    def table(path):
        return np.genfromtxt(path, delimiter=",")[:, :-1]   # rows end with a comma
    force = np.stack([table(output / "dynamics" / f"F{c}.csv")[:, w] for c in "xyz"], -1) * 1e-3   # kg mm/s2
    moment = np.stack([table(output / "dynamics" / f"M{c}.csv")[:, w] for c in "xyz"], -1) * 1e-6  # kg mm2/s2
    points = np.stack([table(output / "kinematics" / c / f"{name}.csv") for c in "xyz"], -1) * 1e-3
    time = np.arange(len(force)) * STEP_S
    return time[1:], force[1:], moment[1:], points


def steady_fit(time, y):
    """Least-squares fit of y (frames, 3) over the steady whisk by the whisking frequency's harmonics 0..HARMONICS:
    (fit, leftover, amplitudes (HARMONICS + 1, 3)) on the frames from STEADY_FROM_S."""
    keep = time >= STEADY_FROM_S - 1e-9
    t = time[keep]
    f = scene(2, 1.0)["whisking"]["frequency_Hz"]
    basis = [np.ones_like(t)]
    for k in range(1, HARMONICS + 1):
        basis += [np.cos(2 * np.pi * k * f * t), np.sin(2 * np.pi * k * f * t)]
    basis = np.stack(basis, -1)
    c, *_ = np.linalg.lstsq(basis, y[keep], rcond=None)
    amplitudes = np.vstack([np.abs(c[:1]), np.hypot(c[1::2], c[2::2])])
    return basis @ c, y[keep] - basis @ c, amplitudes


def second_difference(x, h):
    """5-point central second derivative along axis 0 (the frames 2 .. n-3)."""
    return (-x[:-4] + 16 * x[1:-3] - 30 * x[2:-2] + 16 * x[3:-1] - x[4:]) / (12 * h * h)


def newton_wrench(points, mass, base, h):
    """Newton's law on the whole whisker from its link centres `points` (frames, links, 3) [m] and masses: the force
    and moment about `base` (frames, 3) the follicle carries in air, -sum m a and -sum (x - base) x m a, on frames
    2 .. n-3 (the links' spin about their centroids, (link / whisker length)^2 smaller, left out)."""
    a = second_difference(points, h)
    force = -np.einsum("i,tic->tc", mass, a)
    moment = -np.einsum("i,tic->tc", mass, np.cross(points[2:-2] - base[2:-2, None, :], a))
    return force, moment


def compare_fits(x, y, k):
    """rms ratio and correlation of two steady fits (frames, fit force, fit moment) in their k-th entry (1: force,
    2: moment), on their common frames."""
    _, i, j = np.intersect1d(x[0], y[0], return_indices=True)
    a, b = x[k][i], y[k][j]
    aa, bb = (a ** 2).sum(), (b ** 2).sum()
    return float(np.sqrt(aa / bb)), float(np.sum(a * b) / np.sqrt(aa * bb))


def whiskit_parameters(inputs):
    """The whisker parameters `inputs` wrote for WHISKiT: their folder, the names, side/row/column and (S, A)."""
    params = pathlib.Path(inputs) / "data" / "whisker_param_average_rat"
    names = [line.strip() for line in open(params / "param_name.csv")]
    row_col = np.genfromtxt(params / "param_side_row_col.csv", delimiter=",").astype(int)
    s_a = np.genfromtxt(params / "param_s_a.csv", delimiter=",")
    return params, names, row_col, s_a


def cmd_air(args) -> int:
    import vibrissa
    output = pathlib.Path(args.whiskit_output)
    params, whiskit_names, row_col, s_a = whiskit_parameters(args.inputs)
    omega = np.genfromtxt(params / "whisking_trajectory.csv", delimiter=",")
    kinematics = array_kinematics()
    load = os.getloadavg()[0]

    def peaks(label, time, force, moment, tip):
        steady = time >= STEADY_FROM_S - 1e-9
        fit_F, left_F, _ = steady_fit(time, force)
        fit_M, left_M, _ = steady_fit(time, moment)
        norm = lambda v: np.linalg.norm(v, axis=-1)   # noqa: E731
        print(f"  {label:52s} {norm(force).max() * 1e6:6.1f} {norm(force[steady]).max() * 1e6:6.1f} "
              f"{norm(fit_F).max() * 1e6:6.2f} {np.sqrt((norm(left_F) ** 2).mean()) * 1e6:6.2f}   "
              f"{norm(moment).max() * 1e6:6.3f} {norm(moment[steady]).max() * 1e6:6.3f} {norm(fit_M).max() * 1e6:6.3f} "
              f"{np.sqrt((norm(left_M) ** 2).mean()) * 1e6:6.3f}   {norm(tip).max() * 1e3:5.2f} "
              f"{norm(tip[steady]).max() * 1e3:5.2f}")
        return np.round(time[steady] / STEP_S).astype(int), fit_F, fit_M

    for name in args.names:
        wname = "R" + name[:-1]                       # C1R -> RC1
        i = whiskit_names.index(wname)
        row, column, S_mm = int(row_col[i, 1]), int(row_col[i, 2]), float(s_a[i, 0])
        radii, mass = whiskit_links(row, column, S_mm)
        time, force, moment, points = read_whiskit_air(output, wname)
        # Its follicle turns by the whisking file's angular velocity, constant over each 1 ms step: the rest shape
        # turned with it, against which its links lag.
        turn = [np.eye(3)]
        for w_k in omega[i].reshape(-1, 3)[: len(points) - 1]:
            turn.append(rotation_matrix(w_k * STEP_S) @ turn[-1])
        turn = np.array(turn)
        rest = points[0, 1:] - points[0, :1]
        lag = points[:, 1:] - points[:, :1] - np.einsum("tij,nj->tni", turn, rest)
        tip_lag = lag[:, -1] + 0.5 * (lag[:, -1] - lag[:, -2])       # the tip, half a link beyond the last centre
        newton_F, newton_M = newton_wrench(points[:, 1:], mass, points[:, 0], STEP_S)
        volume = np.pi * S_mm * 1e-3 / LINKS / 3 * (radii[:-1] ** 2 + radii[:-1] * radii[1:] + radii[1:] ** 2)
        density = float(mass.sum() / volume.sum())
        print(f"{name} (WHISKiT {wname}): S {S_mm:.2f} mm, WHISKiT's radii {radii[0] * 1e6:.1f} -> "
              f"{radii[-1] * 1e6:.2f} um, mass {mass.sum() * 1e9:.1f} ug (uniform {density:.0f} kg/m3)")
        print("  peaks; F [uN]: all, steady, fit, leftover rms; M [uN m]: the same; tip lag [mm]: all, steady")
        w_fit = peaks("WHISKiT, reported", time, force, moment, tip_lag[1:])
        own = peaks("WHISKiT, Newton on its links", np.arange(len(points))[2:-2] * STEP_S, newton_F, newton_M,
                    tip_lag[2:-2])
        runs = {"vibrissa, defaults (N 100, 3.3 GPa, 1300, taper 15)": ({}, {}),
                "vibrissa, matched (N 20, 5 GPa, its radii, mass)": (
                    {"links": LINKS, "radii": radii.tolist(), "youngs_modulus": WHISKIT_E_PA}, {"density": density}),
                "vibrissa, matched, zeta 0.32 (WHISKiT's)": (
                    {"links": LINKS, "radii": radii.tolist(), "youngs_modulus": WHISKIT_E_PA},
                    {"density": density, "damping_ratio": 0.32}),
                "vibrissa, matched, E 5/20 GPa (springs E I / L)": (
                    {"links": LINKS, "radii": radii.tolist(), "youngs_modulus": WHISKIT_E_PA / LINKS},
                    {"density": density})}
        fits, matched = {}, "vibrissa, matched (N 20, 5 GPa, its radii, mass)"
        steady = time >= STEADY_FROM_S - 1e-9
        whiskit_lag = float(np.linalg.norm(tip_lag[1:][steady], axis=-1).max())
        for label, (fields, settings) in list(runs.items()) + [("fitted E", (None, None))]:
            if settings is None:   # the modulus at which vibrissa matched lags as WHISKiT (lag ~ 1/E below f_1)
                r = matched_result
                lag = float(np.linalg.norm(np.stack([r.tip_x_B, r.tip_y_B, r.tip_z_B], -1)[r.time >= STEADY_FROM_S
                                                                                          - 1e-9], axis=-1).max())
                modulus = WHISKIT_E_PA * lag / whiskit_lag
                label = f"vibrissa, matched, E {modulus / 1e9:.2f} GPa (its lag as WHISKiT's)"
                fields = {"links": LINKS, "radii": radii.tolist(), "youngs_modulus": modulus}
                settings = {"density": density}
            whisker, whisking, _, _ = array_whisker_case(name, 1e-3, 0.0, kinematics, **fields)
            r = vibrissa.simulate_dynamics(whisker, DURATION_S, 1.0 / STEP_S, whisking=whisking, **settings)
            F = np.stack([r.Fx_W, r.Fy_W, r.Fz_W], -1)
            M = np.stack([r.Mx_W, r.My_W, r.Mz_W], -1)
            fits[label] = peaks(label, r.time, F, M, np.stack([r.tip_x_B, r.tip_y_B, r.tip_z_B], -1))
            if label == matched:
                matched_result = r
        for what, k in (("force", 1), ("moment", 2)):
            ratio, correlation = compare_fits(w_fit, fits[matched], k)
            own_ratio, own_correlation = compare_fits(own, fits[matched], k)
            print(f"  steady {what}: WHISKiT's fit / matched rms {ratio:.2f} (correlation {correlation:.3f}); "
                  f"Newton on its links / matched {own_ratio:.2f} ({own_correlation:.3f})")
        # Newton's law on vibrissa's own matched run: link centroids on the chords between the recorded nodes.
        nodes = np.asarray(matched_result.nodes_W)
        r0, r1 = radii[:-1], radii[1:]
        along = (r0 ** 2 + 2 * r0 * r1 + 3 * r1 ** 2) / (4 * (r0 ** 2 + r0 * r1 + r1 ** 2))
        centroids = nodes[:, :-1] + along[None, :, None] * np.diff(nodes, axis=1)
        ours_mass = density * volume
        F_n, M_n = newton_wrench(centroids, ours_mass, nodes[:, 0], STEP_S)
        F_o = np.stack([matched_result.Fx_W, matched_result.Fy_W, matched_result.Fz_W], -1)[2:-2]
        M_o = np.stack([matched_result.Mx_W, matched_result.My_W, matched_result.Mz_W], -1)[2:-2]
        gap = lambda a, b: np.linalg.norm(a - b, axis=-1).max() / np.linalg.norm(b, axis=-1).max()   # noqa: E731
        print(f"  vibrissa matched against Newton on its recorded shapes (1 kHz): force {gap(F_o, F_n):.2%}, "
              f"moment {gap(M_o, M_n):.2%} of the peaks (the deflection x base-motion products it leaves out)")
        _, _, amp = steady_fit(matched_result.time, np.stack([matched_result.Fx_B, matched_result.Fy_B,
                                                              matched_result.Mz_B], -1))
        print(f"  vibrissa matched, harmonics 0, f, 2f, 3f of Fx_B (axial) [uN] {np.round(amp[:4, 0] * 1e6, 2)}, "
              f"Fy_B {np.round(amp[:4, 1] * 1e6, 2)}, Mz_B [uN m] {np.round(amp[:4, 2] * 1e6, 3)}")
    print(f"load average {load:.1f} -> {os.getloadavg()[0]:.1f}")
    return 0


def cmd_air_steady(args) -> int:
    """WHISKiT's saved force against Newton on its links, window by window, for a run on `inputs --steady-rate`."""
    output = pathlib.Path(args.whiskit_output)
    params, whiskit_names, row_col, s_a = whiskit_parameters(args.inputs)
    for name in args.names:
        wname = "R" + name[:-1]
        i = whiskit_names.index(wname)
        _, mass = whiskit_links(int(row_col[i, 1]), int(row_col[i, 2]), float(s_a[i, 0]))
        time, force, _, points = read_whiskit_air(output, wname)
        newton, _ = newton_wrench(points[:, 1:], mass, points[:, 0], STEP_S)
        newton_time = np.arange(len(points))[2:-2] * STEP_S
        edges = [0.0, 0.01, 0.03, 0.06, time[-1] + STEP_S]
        for lo, hi in zip(edges[:-1], edges[1:]):
            saved = np.linalg.norm(force[(time >= lo) & (time < hi)], axis=-1)
            own = np.linalg.norm(newton[(newton_time >= lo) & (newton_time < hi)], axis=-1)
            print(f"{name} {lo * 1e3:4.0f}-{hi * 1e3:4.0f} ms: saved |F| mean {saved.mean() * 1e6:6.2f} max "
                  f"{saved.max() * 1e6:6.2f} uN; Newton on its links mean {own.mean() * 1e6:6.2f} max "
                  f"{own.max() * 1e6:6.2f} uN")
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("inputs")
    p.add_argument("dir")
    p.add_argument("--whiskit-data", default="/work/whiskit/code/data")
    p.add_argument("--steady-rate", type=float, help="turn every follicle at this constant rate [rad/s] about its "
                   "first step's axis instead of whisking (the scatter of WHISKiT's saved force without the whisk's "
                   "1 ms angular-velocity steps: `air-steady`)")
    p = sub.add_parser("ours")
    p.add_argument("--vibrissa", default="build/bin/vibrissa")
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--links", type=int, default=0, help="links per whisker (default: the config's, 100)")
    p.add_argument("--mu", type=float, default=0.0, help="the peg's friction (WHISKiT's: 0.25); 0: frictionless")
    p = sub.add_parser("peg-whisker")
    p.add_argument("name", help="a whisker of the array, e.g. C1R, or 'all': every whisker, one after the other")
    p.add_argument("--duration", type=float, default=DURATION_S)
    p.add_argument("--peg-radius-mm", type=float, default=1.0, help="WHISKiT's peg: 1 mm")
    p.add_argument("--mu", type=float, default=0.25, help="WHISKiT's: 0.5 x 0.5 (Bullet multiplies frictions)")
    p = sub.add_parser("air")
    p.add_argument("names", nargs="+", help="whiskers of the array, e.g. C1R")
    p.add_argument("--whiskit-output", default=WHISKIT_OUTPUT, help="WHISKiT's --dir_out of its in-air run")
    p.add_argument("--inputs", default=WHISKIT_INPUTS, help="the folder `inputs` wrote (its data/ is read)")
    p = sub.add_parser("air-steady")
    p.add_argument("names", nargs="+", help="whiskers of the array, e.g. C1R")
    p.add_argument("--whiskit-output", required=True, help="WHISKiT's --dir_out of a run on `inputs --steady-rate`")
    p.add_argument("--inputs", required=True, help="the folder `inputs --steady-rate` wrote")
    args = parser.parse_args()
    return {"inputs": cmd_inputs, "ours": cmd_ours, "peg-whisker": cmd_peg_whisker,
            "air": cmd_air, "air-steady": cmd_air_steady}[args.command](args)


if __name__ == "__main__":
    sys.exit(main())
