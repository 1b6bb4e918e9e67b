#pragma once
// A whisker's point list must describe a simple curve: no hairpin (a segment turning back on the one before)
// and no segment touching a non-adjacent one. docs/conventions.md, "Whisker geometry".
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace vibrissa {

/// Largest turn between consecutive segments of a whisker's point list [rad]: 150 deg (a rat whisker bends by
/// far less between two tracked points; more is a folded-back track).
inline constexpr double max_segment_turn_rad = 150.0 * 3.14159265358979323846 / 180.0;

/// Throws std::invalid_argument naming `field` and the pair of segments (segment k joins points k and k+1)
/// if consecutive segments turn by more than max_segment_turn_rad, or if two non-adjacent segments come
/// closer than 1e-6 of the curve's length. Sweep over the longest axis: near-linear for whisker-like curves.
void require_simple_curve(const std::vector<Eigen::Vector3d>& points, std::string_view field);

}  // namespace vibrissa
