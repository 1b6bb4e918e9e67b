#pragma once
// Whisking kinematics (spec §2.2, data sheet §3, Knutsen et al. 2008): every whisker protracts by
// Δθ(t) and its elevation and roll follow linearly, φ = φ_rest + kφ·Δθ, ζ = ζ_rest + kζ·Δθ, with slopes
// that depend on the row. Angles are the morphology's source angles (right-side equivalent), in rad.
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "vibrissa/array/morphology.hpp"

namespace vibrissa::array {

/// Named sets of row slopes (data sheet §3).
enum class SlopeSet {
  knutsen2008,                 ///< Knutsen, Biess & Ahissar 2008 as published (default; the spec predates the rest)
  knutsen2008_pitch_adjusted,  ///< re-fitted for the 13.8° head-pitch difference to Towal's head frame
  rigid,                       ///< no coupling: φ and ζ stay at rest (pure protraction)
};
std::string_view to_string(SlopeSet set);
SlopeSet slope_set_from_string(std::string_view name, const char* field = "whisking.slopes");

struct RowSlopes {
  double k_phi = 0.0;   ///< dφ/dθ [rad/rad]
  double k_zeta = 0.0;  ///< dζ/dθ [rad/rad]
};
/// Slopes for row 1..5 (A..E); throws std::invalid_argument for another row.
RowSlopes row_slopes(SlopeSet set, int row);

/// Protraction Δθ(t) [rad] relative to the resting angle. Either a sinusoid
///   Δθ(t) = set_point − amplitude·cos(2π·frequency·t + phase)
/// (fully retracted at t = 0 with phase 0; one protraction lasts 1/(2·frequency)), or, when `series_time` is
/// not empty, the user's time series (linear interpolation, held constant outside).
struct Protraction {
  double amplitude = 0.0;  ///< [rad]
  double frequency = 8.0;  ///< [Hz]
  double set_point = 0.0;  ///< mean Δθ [rad]
  double phase = 0.0;      ///< [rad]
  std::vector<double> series_time;    ///< [s], strictly increasing
  std::vector<double> series_dtheta;  ///< [rad]

  [[nodiscard]] double operator()(double t) const;
  [[nodiscard]] double rate(double t) const;  ///< dΔθ/dt [rad/s]
};
void validate(const Protraction& p, const std::string& field = "whisking");

struct WhiskingKinematics {
  Protraction protraction;                        ///< every whisker, unless overridden
  std::map<std::string, Protraction> per_whisker;  ///< by name ("C2", both sides) or label ("C2R")
  SlopeSet slopes = SlopeSet::knutsen2008;

  [[nodiscard]] const Protraction& protraction_of(const WhiskerSpec& spec) const;
};

/// Source angles of a whisker at time t [rad].
struct WhiskerAngles {
  double theta = 0.0, phi = 0.0, zeta = 0.0;
};
WhiskerAngles angles_at(const WhiskerSpec& spec, const WhiskingKinematics& kinematics, double t);

}  // namespace vibrissa::array
