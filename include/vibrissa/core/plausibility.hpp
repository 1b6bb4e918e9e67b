#pragma once
// Plausibility warnings (unit guardrails): legal inputs that are probably a unit slip (a length typed in mm
// read as metres, radians declared as degrees, a peg out of the whisker's reach). They never stop a run; each
// names the quantity, the value and the likely mistake. The CLI prints them to standard error, results carry
// them in "warnings", Python raises them with warnings.warn. The ranges are those of rodent (rat and mouse)
// whiskers, with sources in docs/conventions.md ("Plausible ranges").
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/pose.hpp"
#include "vibrissa/core/whisker.hpp"

namespace vibrissa {

/// Ranges outside which a rodent whisker is implausible (docs/conventions.md, "Plausible ranges").
namespace plausible {
/// Arc length: the rat array's macrovibrissae reach ~52 mm (docs/array.md's arc-length model), with margin.
inline constexpr double min_length_m = 1e-3, max_length_m = 0.2;
/// Base radius: ~100 um for a rat C2 (spec §2.1), with a factor 10 of margin.
inline constexpr double max_base_radius_m = 1e-3;
/// Young's modulus: 3.3 GPa in the spec (§2.1), with a factor 30 of margin.
inline constexpr double min_youngs_modulus_Pa = 0.1e9, max_youngs_modulus_Pa = 100e9;
/// Pose angles [rad]: beyond +-pi is an angle in degrees read as radians.
inline constexpr double max_pose_angle_rad = 3.141592653589793;
/// An angle series declared in degrees whose every value lies within +-pi degrees is radians read as degrees.
inline constexpr double min_degree_series_span_rad = 3.141592653589793 / 180.0 * 3.141592653589793;
/// Contact forces on a rodent whisker are uN to a few mN; above 0.1 N is a unit slip (mN or uN as N).
inline constexpr double max_force_N = 0.1;
/// An object point or line farther than this many whisker lengths from the base can never be touched.
inline constexpr double max_reach_lengths = 1.5;
}  // namespace plausible

/// `v` with `digits` significant digits ("1.25", "573"): a warning shows values as a user recognises them.
std::string format_significant(double v, int digits = 4);

/// One sentence per implausible property of `whisker` (empty if none), naming the value and the range.
std::vector<std::string> plausibility_warnings(const Whisker& whisker);

/// "`quantity` L m ...: did you mean ...?" if the length `value_m` lies outside the plausible whisker
/// lengths (suggesting the factor of 1000 or 10^6 that brings it inside).
std::optional<std::string> length_warning(std::string_view quantity, double value_m);
/// Pose angles beyond +-pi (a value in degrees given as radians), named `field`.theta etc.
std::vector<std::string> pose_warnings(const Pose& pose, std::string_view field);
/// A force magnitude above plausible::max_force_N, named `field`.
std::optional<std::string> force_warning(std::string_view field, double force_N);
/// An angle series (radians, after conversion): values beyond 2 pi (degrees declared as radians), or, when the
/// file declared degrees, all within +-pi degrees (radians declared as degrees).
std::optional<std::string> angle_series_warning(std::string_view field, const std::vector<double>& values_rad,
                                                bool declared_degrees);
/// An object `field` (a point, or a line through `point_W` along `direction_W` when that is non-zero) whose
/// distance from the whisker base exceeds plausible::max_reach_lengths whisker lengths.
std::optional<std::string> reach_warning(std::string_view field, const Eigen::Vector3d& point_W,
                                         const Eigen::Vector3d& direction_W, const Eigen::Vector3d& base_W,
                                         double whisker_length);

}  // namespace vibrissa
