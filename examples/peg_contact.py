#!/usr/bin/env python3
"""Push a whisker against a vertical peg, plot its deflected shape and print the base forces and moments.

Run from the repository root after building (docs/python.md):

    PYTHONPATH=build/python /usr/bin/python3 examples/peg_contact.py --output peg.png

Then, as a batch: the whisker protracts past the peg over 60 frames, solved in one call (GIL released, all
cores), and the transverse force F_T and bending moment M_B at the base (spec §2.4) are plotted per frame.
"""

import argparse

import matplotlib

matplotlib.use("Agg")  # write files; no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vibrissa  # noqa: E402
from vibrissa.plot import plot_solution  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default="peg.png", help="figure to write (PNG)")
    args = parser.parse_args()

    # A C2-like whisker (spec §2.1): 30 mm long, y = 20 x^2 in its own frame, 100 µm base radius, taper 15.
    props = vibrissa.WhiskerProperties(links=100, base_radius=100e-6, taper_ratio=15.0,
                                       youngs_modulus=3.3e9, poisson_ratio=0.38)
    whisker = vibrissa.Whisker.from_parabola(0.030, 20.0, properties=props,
                                             pose=vibrissa.Pose(base=[0.0, 0.0, 0.0], theta=0.0))

    # A vertical peg (an edge along world +z) 18 mm out, 2 mm inside the whisker's concave side.
    peg = vibrissa.Edge(point=[0.018, 0.0045, 0.0], direction=[0.0, 0.0, 1.0])
    solution = vibrissa.solve_edge(whisker, peg)
    print(solution)
    if not solution.converged:
        raise SystemExit(f"no contact: {solution.message}")

    np.set_printoptions(precision=4)
    wf = solution.whisker_frame
    print(f"contact at s = {solution.arc_length * 1e3:.3f} mm, point {solution.contact_point_W * 1e3} mm")
    print(f"base force, world        F = {solution.force_W * 1e6} µN (|F| = {solution.force_magnitude * 1e6:.3f} µN)")
    print(f"base moment, world       M = {solution.moment_W * 1e9} nN·m")
    print(f"base force, whisker      (Fx, Fy, Fz) = {wf.force * 1e6} µN")
    print(f"base moment, whisker     (Mx, My, Mz) = {wf.moment * 1e9} nN·m")
    print(f"F_T = {wf.FT * 1e6:.4f} µN, M_B = {wf.MB * 1e9:.4f} nN·m, "
          f"F_D = {np.degrees(wf.FD):.2f}°, M_D = {np.degrees(wf.MD):.2f}°")

    # Batch: protract from -0.3 to 0.3 rad into the peg; each frame warm-starts from the previous one.
    # Protraction moves the whisker toward world +y (`approach`): frames where the peg would have to pull
    # the whisker report Status.no_contact instead of a contact on the far side.
    frames = 60
    theta = np.linspace(-0.3, 0.3, frames)
    angles = np.column_stack([theta, np.zeros(frames), np.zeros(frames)])  # (theta, phi, zeta) per frame
    sweep = vibrissa.solve_edge_batch(whisker, peg.point, peg.direction, pose_angles=angles, approach_W=[0, 1, 0])
    print(sweep, "statuses:", dict(zip(*np.unique(sweep.status_names, return_counts=True))))

    # One quantity per axis, each with its unit: the shape, then F_T and M_B over the protraction angle.
    fig, (ax_shape, ax_ft, ax_mb) = plt.subplots(1, 3, figsize=(13, 4.2))
    plot_solution(solution, whisker, ax=ax_shape)
    ax_shape.set_title("whisker against a peg (top view)")
    ok = sweep.converged
    deg = np.degrees(theta)
    ax_ft.plot(deg, np.where(ok, sweep.whisker_frame.FT * 1e6, np.nan), color="#0072B2")
    ax_ft.set_ylabel("transverse force $F_T$ [µN]")
    ax_ft.set_title("base force while protracting")
    ax_mb.plot(deg, np.where(ok, sweep.whisker_frame.MB * 1e9, np.nan), color="#D55E00")
    ax_mb.set_ylabel("bending moment $M_B$ [nN·m]")
    ax_mb.set_title("base moment while protracting")
    for ax in (ax_ft, ax_mb):
        ax.set_xlabel("protraction θ [deg]")
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
