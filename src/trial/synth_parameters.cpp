#include "vibrissa/trial/synth_parameters.hpp"

#include <numbers>
#include <stdexcept>

namespace vibrissa::trial {

const std::vector<SynthParameter>& synth_parameters() {
  constexpr double deg_per_rad = 180.0 / std::numbers::pi, rad_per_deg = std::numbers::pi / 180.0;
  static const std::vector<SynthParameter> table{
      {"duration", "trial length [s]", &SynthOptions::duration, 1.0, 1.0},
      {"frame_rate", "frames per second [Hz]", &SynthOptions::frame_rate, 1.0, 1.0},
      {"whisk_hz", "whisking frequency [Hz]", &SynthOptions::whisk_frequency, 1.0, 1.0},
      {"mu", "friction coefficient of the simulation", &SynthOptions::mu, 1.0, 1.0},
      {"theta_center_deg", "centre of the whisk [deg]", &SynthOptions::theta_center, deg_per_rad, rad_per_deg},
      {"theta_amplitude_deg", "half the whisk amplitude [deg]", &SynthOptions::theta_amplitude, deg_per_rad,
       rad_per_deg},
      {"theta_center_jitter_deg", "sd of the whisk-to-whisk set-point variation [deg]",
       &SynthOptions::theta_center_jitter, deg_per_rad, rad_per_deg},
      {"theta_amplitude_jitter", "relative sd of the whisk-to-whisk amplitude variation",
       &SynthOptions::theta_amplitude_jitter, 1.0, 1.0},
      {"protraction_fraction", "fraction of a whisk spent protracting", &SynthOptions::protraction_fraction, 1.0,
       1.0},
      {"phi_slope", "d phi / d theta (spec §2.2)", &SynthOptions::phi_slope, 1.0, 1.0},
      {"zeta_slope", "d zeta / d theta (spec §2.2)", &SynthOptions::zeta_slope, 1.0, 1.0},
      {"whisker_length_mm", "whisker arc length [mm]", &SynthOptions::whisker_length, 1e3, 1e-3},
      {"curvature", "rest shape y = a x^2, a [1/m]", &SynthOptions::curvature, 1.0, 1.0},
      {"peg_distance_mm", "horizontal distance base to peg [mm]", &SynthOptions::peg_distance, 1e3, 1e-3},
      {"peg_azimuth_deg", "azimuth of the peg about +z [deg]", &SynthOptions::peg_azimuth, deg_per_rad, rad_per_deg},
      {"noise_position_um", "sd of tracking noise on base and contact point [um]", &SynthOptions::noise_position,
       1e6, 1e-6},
      {"noise_angle_deg", "sd of tracking noise on the angles [deg]", &SynthOptions::noise_angle, deg_per_rad,
       rad_per_deg},
  };
  return table;
}

std::map<std::string, double> synth_parameter_defaults() {
  const SynthOptions defaults;
  std::map<std::string, double> values;
  for (const SynthParameter& p : synth_parameters()) values[p.name] = defaults.*p.field * p.unit_per_si;
  return values;
}

SynthOptions synth_options_from_parameters(const std::map<std::string, double>& values) {
  std::map<std::string, double> all = synth_parameter_defaults();
  for (const auto& [name, value] : values) {
    const auto it = all.find(name);
    if (it == all.end()) throw std::invalid_argument("synthetic trial: unknown parameter '" + name + "'");
    it->second = value;
  }
  SynthOptions options;
  for (const SynthParameter& p : synth_parameters()) options.*p.field = all.at(p.name) * p.si_per_unit;
  return options;
}

}  // namespace vibrissa::trial
