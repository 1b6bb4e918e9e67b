#pragma once
// The numeric options of a synthetic trial as the front ends name them (`vibrissa synth --theta-center-deg`,
// `vibrissa.synthesize_trial(theta_center_deg=...)`): one table, so the CLI and Python convert the same
// values to the same SI SynthOptions bit for bit. Names carry the unit of the value (deg, mm, um); SynthOptions
// holds SI. `seed` (an integer) and `shapes` (a flag) are not numeric parameters and are set directly.
#include <map>
#include <string>
#include <vector>

#include "vibrissa/trial/synth.hpp"

namespace vibrissa::trial {

struct SynthParameter {
  std::string name;  ///< e.g. "theta_center_deg" (the CLI flag is --theta-center-deg)
  std::string help;
  double SynthOptions::*field;
  double unit_per_si;  ///< value in the parameter's unit = SI value * unit_per_si (e.g. 180/pi for deg)
  double si_per_unit;  ///< SI value = value in the parameter's unit * si_per_unit (e.g. pi/180 for deg)
};

/// Every numeric parameter, in the order of `vibrissa synth --help`.
const std::vector<SynthParameter>& synth_parameters();

/// The defaults of SynthOptions{} in the parameters' units, by name.
std::map<std::string, double> synth_parameter_defaults();

/// SynthOptions{} with every parameter set from `values` (units as named; missing names keep the default,
/// converted through the parameter's unit and back, as the CLI always did). Throws std::invalid_argument
/// naming an unknown parameter. Seed and shapes are left at their defaults.
SynthOptions synth_options_from_parameters(const std::map<std::string, double>& values);

}  // namespace vibrissa::trial
