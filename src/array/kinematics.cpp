#include "vibrissa/array/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "array_util.hpp"

namespace vibrissa::array {

std::string_view to_string(SlopeSet set) {
  switch (set) {
    case SlopeSet::knutsen2008: return "knutsen2008";
    case SlopeSet::knutsen2008_pitch_adjusted: return "knutsen2008_pitch_adjusted";
    case SlopeSet::rigid: return "rigid";
  }
  return "knutsen2008";
}

SlopeSet slope_set_from_string(std::string_view name, const char* field) {
  for (SlopeSet s : {SlopeSet::knutsen2008, SlopeSet::knutsen2008_pitch_adjusted, SlopeSet::rigid})
    if (name == to_string(s)) return s;
  fail(std::string(field) + " must be 'knutsen2008', 'knutsen2008_pitch_adjusted' or 'rigid', got '" +
       std::string(name) + "'");
}

RowSlopes row_slopes(SlopeSet set, int row) {
  if (row < 1 || row > 5) fail("row must be 1..5 (A..E), got " + std::to_string(row));
  // Data sheet §3. Slopes are dimensionless (deg/deg = rad/rad).
  static constexpr RowSlopes kOriginal[5] = {{0.12, -0.76}, {0.30, -0.25}, {0.30, 0.22}, {0.14, 0.42}, {-0.02, 0.73}};
  static constexpr RowSlopes kAdjusted[5] = {
      {0.398, -0.900}, {0.591, -0.284}, {0.578, 0.243}, {0.393, 0.449}, {0.217, 0.744}};
  switch (set) {
    case SlopeSet::knutsen2008: return kOriginal[row - 1];
    case SlopeSet::knutsen2008_pitch_adjusted: return kAdjusted[row - 1];
    case SlopeSet::rigid: return {};
  }
  return {};
}

double Protraction::operator()(double t) const {
  if (series_time.empty()) return set_point - amplitude * std::cos(2.0 * std::numbers::pi * frequency * t + phase);
  if (t <= series_time.front()) return series_dtheta.front();
  if (t >= series_time.back()) return series_dtheta.back();
  const auto it = std::upper_bound(series_time.begin(), series_time.end(), t);
  const std::size_t i = static_cast<std::size_t>(it - series_time.begin()) - 1;
  const double f = (t - series_time[i]) / (series_time[i + 1] - series_time[i]);
  return (1.0 - f) * series_dtheta[i] + f * series_dtheta[i + 1];
}

double Protraction::rate(double t) const {
  if (series_time.empty()) {
    const double w = 2.0 * std::numbers::pi * frequency;
    return amplitude * w * std::sin(w * t + phase);
  }
  if (t < series_time.front() || t >= series_time.back()) return 0.0;
  const auto it = std::upper_bound(series_time.begin(), series_time.end(), t);
  const std::size_t i = static_cast<std::size_t>(it - series_time.begin()) - 1;
  return (series_dtheta[i + 1] - series_dtheta[i]) / (series_time[i + 1] - series_time[i]);
}

void validate(const Protraction& p, const std::string& field) {
  // A protraction angle beyond a half turn either way means nothing for a whisker on a face; rats whisk at 5-25 Hz,
  // and 10 kHz already lies above a whisker's first modes (docs/dynamics.md): larger values are typing errors
  // (and would make the dynamics take unbounded steps).
  constexpr double max_angle = std::numbers::pi, max_frequency_Hz = 1e4;
  if (!(std::abs(p.amplitude) <= max_angle))
    fail(field + ".amplitude_deg must lie in [-180, 180], got " + fmt(to_deg(p.amplitude)));
  if (!(p.frequency >= 0.0 && p.frequency <= max_frequency_Hz))
    fail(field + ".frequency_Hz must lie in [0, 10000], got " + fmt(p.frequency));
  if (!(std::abs(p.set_point) <= max_angle))
    fail(field + ".set_point_deg must lie in [-180, 180], got " + fmt(to_deg(p.set_point)));
  if (!std::isfinite(p.phase)) fail(field + ".phase_deg must be finite, got " + fmt(to_deg(p.phase)));
  if (p.series_time.size() != p.series_dtheta.size())
    fail(field + ".series: time_s has " + std::to_string(p.series_time.size()) + " values but dtheta_deg has " +
         std::to_string(p.series_dtheta.size()));
  if (p.series_time.size() == 1) fail(field + ".series needs at least 2 samples, got 1");
  for (std::size_t i = 0; i < p.series_time.size(); ++i) {
    if (!std::isfinite(p.series_time[i]))
      fail(field + ".series.time_s[" + std::to_string(i) + "] must be finite, got " + fmt(p.series_time[i]));
    if (!(std::abs(p.series_dtheta[i]) <= 2.0 * max_angle))
      fail(field + ".series.dtheta_deg[" + std::to_string(i) + "] must lie in [-360, 360], got " +
           fmt(to_deg(p.series_dtheta[i])));
    if (i > 0 && !(p.series_time[i] > p.series_time[i - 1]))
      fail(field + ".series.time_s must increase strictly, but time_s[" + std::to_string(i) + "] = " +
           fmt(p.series_time[i]));
  }
}

const Protraction& WhiskingKinematics::protraction_of(const WhiskerSpec& spec) const {
  if (!per_whisker.empty()) {
    if (const auto it = per_whisker.find(spec.label()); it != per_whisker.end()) return it->second;
    if (const auto it = per_whisker.find(spec.name); it != per_whisker.end()) return it->second;
  }
  return protraction;
}

WhiskerAngles angles_at(const WhiskerSpec& spec, const WhiskingKinematics& k, double t) {
  // Knutsen et al. 2008 (spec §2.2, data sheet §3): φ and ζ are linear in Δθ with row-specific slopes.
  const double dtheta = k.protraction_of(spec)(t);
  const RowSlopes s = row_slopes(k.slopes, spec.row);
  return {spec.theta_rest + dtheta, spec.phi_rest + s.k_phi * dtheta, spec.zeta_rest + s.k_zeta * dtheta};
}

}  // namespace vibrissa::array
