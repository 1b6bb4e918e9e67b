#pragma once
// Synthetic whisking trials (docs/trials.md, "Synthetic trials"): a whisker with the paper's dimensions
// (spec §2.1) whisks at ~8 Hz with coupled kinematics (spec §2.2; rat-array-data §3: phi and zeta linear in
// theta) against a vertical peg; every contact frame is simulated with the frictional edge mode at a chosen
// mu, and the result is written as a tracked trial: the "tracked" contact point is the frictional solution's
// contact point, plus optional tracking noise. Running the pipeline on it must recover mu.
#include <cstdint>
#include <functional>
#include <optional>

#include "vibrissa/core/run_control.hpp"
#include "vibrissa/trial/format.hpp"

namespace vibrissa::trial {

struct SynthOptions {
  double duration = 2.0;       ///< [s]
  double frame_rate = 1000.0;  ///< [Hz]
  /// [Hz]. Not a divisor of the default frame rate (1000 / 8.3 = 120.5 frames per whisk), so whisks do not
  /// repeat frame for frame.
  double whisk_frequency = 8.3;
  double theta_center = 10.0 * 0.017453292519943295;     ///< [rad]
  double theta_amplitude = 30.0 * 0.017453292519943295;  ///< [rad]
  /// Whisk-to-whisk variation (seeded by `seed`): each whisk's set-point is theta_center plus a Gaussian of this
  /// sd [rad], its amplitude theta_amplitude times (1 + a Gaussian of this relative sd). Consecutive whisks
  /// join at their troughs, so theta stays continuous. Zero for identical whisks.
  double theta_center_jitter = 2.0 * 0.017453292519943295;
  double theta_amplitude_jitter = 0.1;
  /// Fraction of each whisk spent protracting (theta rising, half-cosine) before a faster retraction.
  double protraction_fraction = 0.7;
  double phi_center = 0.0;     ///< [rad] elevation at theta_center
  /// d phi / d theta: row B of the head-pitch-adjusted Knutsen set (rat-array-data §3); a vertical drive
  /// strong enough that the contact slips during protraction at mu = 0.48.
  double phi_slope = 0.591;
  double zeta_center = 0.0;    ///< [rad]
  double zeta_slope = -0.284;  ///< d zeta / d theta (same set, row B)
  double whisker_length = 0.035;  ///< arc length [m]
  double curvature = 8.0;         ///< y = a x^2 in the whisker frame, a [1/m]
  int rest_points = 41;           ///< points of the rest shape written to the trial
  TrialMaterial material;         ///< spec §2.1 defaults (100 um base radius, ratio 15, 3.3 GPa, 0.38)
  double peg_distance = 0.020;    ///< horizontal distance base -> peg [m]
  double peg_azimuth = 34.0 * 0.017453292519943295;  ///< azimuth of the peg about world +z [rad]
  double mu = 0.48;               ///< friction coefficient of the simulation
  double noise_position = 0.0;    ///< sd of Gaussian tracking noise on base and contact point [m]
  double noise_angle = 0.0;       ///< sd of Gaussian tracking noise on theta, phi, zeta [rad]
  std::uint64_t seed = 1;
  bool shapes = false;            ///< also write tracked 3D shapes
  int shape_nodes = 26;           ///< nodes per tracked shape
};

struct SynthStats {
  std::size_t frames = 0, contact_frames = 0, periods = 0;
  std::size_t stick_frames = 0, slip_frames = 0;  ///< of contact frames (by the solver's message)
  std::size_t slip_offs = 0, releases = 0, failures = 0;
};

/// Throws std::invalid_argument for non-physical options.
/// Progress counts frames simulated; cancel is polled per frame.
/// Throws std::invalid_argument naming the parameter (synth_parameters' names and units) unless every value is
/// finite and in range and duration x frame_rate <= limits::max_trial_frames (what `vibrissa trial` reads).
void validate_synth_options(const SynthOptions& options);
Trial synthesize_trial(const SynthOptions& options, SynthStats* stats = nullptr, const RunControl& control = {});

}  // namespace vibrissa::trial
