"""Identifiability and noise study of the base-wrench inverse (docs/inverse.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/inverse_noise_study.py [--out docs/figures/inverse_noise.png]

Prints the identifiability table (condition number and linearised standard deviations of s, f, zeta and of
the contact point, per signal set and contact position) as Markdown, and draws the Monte Carlo localisation
error against sensor noise and against arc length, with the linearised prediction, to a PNG.
Deterministic: fixed seed.
"""

import argparse
import os

import numpy as np

import vibrissa

L, CURVATURE = 0.040, 12.0  # the rat whisker of the tests (spec §2.1 material)
FORCE, ZETA = 1e-4, np.deg2rad(40.0)  # 0.1 mN, 40 degrees about the loaded link
SIGMA_F, SIGMA_M = 1e-6, 1e-8  # sensor noise: 1 uN per force component, 0.01 uN·m per moment component
SETS = ["bending", "bending_axial", "moments", "moments_axial", "all"]
NAMES = ["Fx", "Fy", "Fz", "Mx", "My", "Mz"]
PRESET = {"bending": "My,Mz", "bending_axial": "Fx,My,Mz", "moments": "Mx,My,Mz", "moments_axial": "Fx,Mx,My,Mz",
          "all": "Fx..Mz"}


def noise_sd(signals, scale=1.0):
    """Standard deviations of the chosen signals, in signal order."""
    names = {"bending": ["My", "Mz"], "bending_axial": ["Fx", "My", "Mz"], "moments": ["Mx", "My", "Mz"],
             "moments_axial": ["Fx", "Mx", "My", "Mz"], "all": NAMES}[signals]
    return np.array([scale * (SIGMA_F if n[0] == "F" else SIGMA_M) for n in names])


def identifiability_table(w):
    rows = ["| signals | s/L | condition | σ_s [mm] | σ_f [µN] | σ_ζ [deg] | σ_p [mm] |",
            "|---|---|---|---|---|---|---|"]
    for signals in SETS:
        for frac in (0.25, 0.5, 0.75):
            fwd = vibrissa.solve_force(w, FORCE, frac * L, ZETA)
            # Warm-started at the true contact, so that the linearisation is taken there even when the set
            # cannot tell the contacts apart.
            r = vibrissa.solve_base_wrench(w, fwd.force_W, fwd.moment_W, signals=signals, noise=noise_sd(signals),
                                           warm=fwd)
            idf = r.identifiability
            if not idf.identifiable:
                nd = idf.null_direction
                rows.append(f"| {PRESET[signals]} | {frac:.2f} | ∞ | null direction (Δs/L, Δf/F₀, Δζ) = "
                            f"({nd[0]:+.2f}, {nd[1]:+.2f}, {nd[2]:+.2f}) | | | |")
                continue
            sd = np.sqrt(np.diag(idf.covariance))
            sp = np.sqrt(np.trace(idf.contact_point_covariance))
            rows.append(f"| {PRESET[signals]} | {frac:.2f} | {idf.condition_number:.3g} | {1e3 * sd[0]:.3g} | "
                        f"{1e6 * sd[1]:.3g} | {np.rad2deg(sd[2]):.3g} | {1e3 * sp:.3g} |")
    return "\n".join(rows)


def monte_carlo(w, fracs, scales, signals, trials, rng):
    """RMS contact-point error [m] (Monte Carlo) and the linearised prediction, shape (len(fracs), len(scales))."""
    R = np.eye(3)  # the whisker sits at the default pose: world = whisker frame B
    F, M, truth, predicted = [], [], [], []
    for frac in fracs:
        fwd = vibrissa.solve_force(w, FORCE, frac * L, ZETA)
        for scale in scales:
            sd = noise_sd("all", scale)
            noise = rng.standard_normal((trials, 6)) * sd
            F.append(fwd.force_W + noise[:, :3] @ R.T)  # noise in the sensor (whisker) frame B
            M.append(fwd.moment_W + noise[:, 3:] @ R.T)
            truth.append(fwd.contact_point_W)
            lin = vibrissa.solve_base_wrench(w, fwd.force_W, fwd.moment_W, signals=signals,
                                             noise=noise_sd(signals, scale), warm=fwd)
            predicted.append(np.sqrt(np.trace(lin.identifiability.contact_point_covariance)))
    # One weighting for every series: the noise scales forces and moments alike, so the fit does not change.
    b = vibrissa.solve_base_wrench_batch(w, np.array(F), np.array(M), signals=signals, noise=noise_sd(signals))
    err = np.linalg.norm(b.contact_point_W - np.array(truth)[:, None, :], axis=-1)
    ok = b.converged
    # A point where no trial converged has no error to average: NaN, left out of the figure.
    rms = np.sqrt(np.array([np.mean(e[k] ** 2) if k.any() else np.nan for e, k in zip(err, ok)]))
    shape = (len(fracs), len(scales))
    return rms.reshape(shape), np.array(predicted).reshape(shape), ok.mean()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="docs/figures/inverse_noise.png")
    parser.add_argument("--trials", type=int, default=40)
    args = parser.parse_args()
    w = vibrissa.Whisker.from_parabola(L, CURVATURE)
    print(identifiability_table(w))

    rng = np.random.default_rng(2016)
    scales = np.array([0.1, 0.3, 1.0, 3.0, 10.0])
    fracs_a = np.array([0.3, 0.6, 0.9])
    fracs_b = np.linspace(0.1, 0.9, 9)
    results = {}
    for signals in ("all", "bending_axial"):
        results[signals, "a"] = monte_carlo(w, fracs_a, scales, signals, args.trials, rng)
        results[signals, "b"] = monte_carlo(w, fracs_b, np.array([1.0]), signals, args.trials, rng)
        print(f"{signals}: converged fraction {results[signals, 'a'][2]:.3f} / {results[signals, 'b'][2]:.3f}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(10, 4.2), constrained_layout=True)
    colours = ["tab:blue", "tab:orange", "tab:green"]
    for signals, marker in (("all", "o"), ("bending_axial", "s")):
        rms, pred, _ = results[signals, "a"]
        for i, frac in enumerate(fracs_a):
            ax_a.loglog(scales * SIGMA_F * 1e6, rms[i] * 1e3, marker, color=colours[i], mfc="none" if marker == "s" else None,
                        label=f"{PRESET[signals]}, s/L={frac:.1f}")
            ax_a.loglog(scales * SIGMA_F * 1e6, pred[i] * 1e3, "-" if signals == "all" else "--", color=colours[i], lw=1)
        rms, pred, _ = results[signals, "b"]
        ax_b.semilogy(fracs_b, rms[:, 0] * 1e3, marker, color="k", mfc="none" if marker == "s" else None,
                      label=f"{PRESET[signals]} (Monte Carlo)")
        ax_b.semilogy(fracs_b, pred[:, 0] * 1e3, "-" if signals == "all" else "--", color="k", lw=1,
                      label=f"{PRESET[signals]} (linearised)")
    ax_a.set_xlabel("sensor noise σ_F [µN] (σ_M = σ_F × 10 mm)")
    ax_a.set_ylabel("RMS contact-point error [mm]")
    ax_a.set_title(f"(a) error vs noise, f = {FORCE * 1e6:.0f} µN; lines: linearised")
    ax_a.legend(fontsize=7, ncol=2)
    ax_a.grid(True, which="both", alpha=0.3)
    ax_b.set_xlabel("contact arc length s / L")
    ax_b.set_ylabel("RMS contact-point error [mm]")
    ax_b.set_title(f"(b) error vs s, σ_F = {SIGMA_F * 1e6:.0f} µN, σ_M = {SIGMA_M * 1e6:.2f} µN·m")
    ax_b.legend(fontsize=8)
    ax_b.grid(True, which="both", alpha=0.3)
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    fig.savefig(args.out, dpi=90)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
