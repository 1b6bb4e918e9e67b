#!/usr/bin/env python3
"""A whisker held by a peg is let go: the quasi-static contact (edge mode) gives the load, the linearised
dynamics (docs/dynamics.md) the ring-down after the peg vanishes. Writes the run and its figure.

    PYTHONPATH=build/python /usr/bin/python3 examples/dynamics/peg_release.py --out peg_release

The whisker, turned back by 1.5 degrees, would pass 0.2 mm beyond the peg at 20 mm: the peg pushes it
forward, lightly (inside the linear range).
"""

import argparse
import pathlib
import subprocess
import sys

import vibrissa


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="peg_release", help="output folder (dynamics.csv, .h5, .png)")
    args = parser.parse_args()

    props = vibrissa.WhiskerProperties(links=100)
    upright = vibrissa.Whisker.from_parabola(0.03, 15.0, properties=props)
    rest = upright.rest_point_B(0.02)  # where the unturned whisker is at 20 mm: the peg 0.3 mm below (-y)
    peg = vibrissa.Edge(point=[rest[0], rest[1] - 3e-4, 0.0], direction=[0.0, 0.0, 1.0])
    whisker = vibrissa.Whisker.from_parabola(0.03, 15.0, properties=props, pose=vibrissa.Pose(theta=-0.026))
    held = vibrissa.solve_edge(whisker, peg)
    assert held.status == vibrissa.Status.converged, held.message
    assert held.contact_state == vibrissa.ContactState.contact, held.contact_state
    force_B = held.whisker_frame.force
    print(f"held at s = {held.arc_length * 1e3:.2f} mm by F_B = {force_B * 1e6} uN")

    run = vibrissa.simulate_dynamics(whisker, 0.06, 5000, force=force_B, arc_length=held.arc_length)
    print(f"released: {run.summary['steps']} steps, peak M_B {run.summary['peak_MB_uNm']:.4f} uN m, "
          f"first mode {run.modes.frequency[0]:.1f} Hz, damping ratio {run.modes.damping_ratio[0]}")
    out = pathlib.Path(args.out)
    run.write(out)
    figure = pathlib.Path(__file__).resolve().parents[2] / "figures" / "dynamics_figure.py"
    subprocess.run([sys.executable, str(figure), str(out)], check=True)


if __name__ == "__main__":
    main()
