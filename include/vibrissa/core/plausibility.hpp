#pragma once
// Plausibility warnings: legal inputs that are probably a unit slip (a length typed in mm, E in Pa vs GPa).
// They never stop a run; the CLI prints them to standard error and results carry them in "warnings".
#include <string>
#include <vector>

#include "vibrissa/core/whisker.hpp"

namespace vibrissa {

/// Ranges outside which a rodent whisker is implausible (docs/formats.md, "Plausibility warnings").
namespace plausible {
inline constexpr double min_length_m = 1e-3, max_length_m = 0.2;
inline constexpr double max_base_radius_m = 1e-3;
inline constexpr double min_youngs_modulus_Pa = 0.1e9, max_youngs_modulus_Pa = 100e9;
}  // namespace plausible

/// One sentence per implausible property of `whisker` (empty if none), naming the value and the range.
std::vector<std::string> plausibility_warnings(const Whisker& whisker);

}  // namespace vibrissa
