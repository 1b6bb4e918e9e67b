#pragma once
// The ways to load a whisker (spec §2.1, §3.1), each returning a Solution. Every solve takes the whisker
// (the immutable model) and where it is (a Placement, or a Pose, which converts); the forms without a
// placement use the one the whisker was built with. Invalid input throws std::invalid_argument naming the
// field; a solve that cannot succeed returns a Status, never NaN.
#include <optional>

#include "vibrissa/core/whisker.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/solve/solution.hpp"

namespace vibrissa {

/// Force mode: a force of magnitude `force` [N] normal to the whisker at arc length `arc_length` [m], at
/// `angle` [rad] about the whisker axis: second-order scheme, 0 = +y of the loaded link, i.e. toward the
/// concave side of a planar whisker, pi/2 = +z; paper scheme, Elastica3D's ζ (docs/conventions.md, "Loads
/// and signs"). The force follows the link as it bends. Explicit, O(N).
Solution solve_force(const Whisker& whisker, const Placement& X_WB, double force, double arc_length, double angle,
                     const SolveOptions& options = {});

/// Dead load: a force with a fixed world direction `force_W` [N] applied at arc length `arc_length`.
Solution solve_dead_load(const Whisker& whisker, const Placement& X_WB, const Eigen::Vector3d& force_W,
                         double arc_length, const SolveOptions& options = {}, const LoadState* warm = nullptr);

/// Contact-point mode: the deflected whisker passes through `point_W` with the force normal to the whisker
/// there. Root choice (docs/conventions.md): warm start -> the root continuous with `warm`; else the root
/// nearest `arc_length_hint`; else nearest the arc length at which the rest whisker is as far from the base
/// as the target. `edge_direction_W`, if given, splits the force into normal_force / edge_force.
Solution solve_point(const Whisker& whisker, const Placement& X_WB, const Eigen::Vector3d& point_W,
                     std::optional<double> arc_length_hint = std::nullopt, const SolveOptions& options = {},
                     const LoadState* warm = nullptr,
                     const std::optional<Eigen::Vector3d>& edge_direction_W = std::nullopt);

/// Edge mode (frictionless slip): the contact lies on the edge line and the force is normal to both the
/// whisker and the line. `approach_W`, if given, is the direction in which the whisker moved into the edge;
/// the edge must then push against it (F · approach < 0), else no_contact.
Solution solve_edge(const Whisker& whisker, const Placement& X_WB, const Edge& edge,
                    std::optional<double> arc_length_hint = std::nullopt, const SolveOptions& options = {},
                    const LoadState* warm = nullptr, const std::optional<Eigen::Vector3d>& approach_W = std::nullopt);

/// Frictional edge mode (Coulomb, quasi-static, with contact history): the contact stays at
/// `previous_contact_W` (a point on the edge) while |edge-parallel force| <= mu · F_N (stick); otherwise it
/// slips along the edge toward the frictionless point until |edge force| = mu · F_N, opposing the slip.
/// mu = 0 reproduces solve_edge; mu -> infinity reproduces solve_point at the stuck point. The outcome is in
/// Solution::friction (stick / slip).
Solution solve_frictional_edge(const Whisker& whisker, const Placement& X_WB, const Edge& edge, double mu,
                               const Eigen::Vector3d& previous_contact_W, const SolveOptions& options = {},
                               const LoadState* warm = nullptr,
                               const std::optional<Eigen::Vector3d>& approach_W = std::nullopt);

/// The deflected nodes (base to tip, world [m]) of the whisker at X_WB under a solved state: the shape a solve
/// with compute_shape reports, recomputed on demand into `nodes_W` (reusing its storage).
void deflected_shape(const Whisker& whisker, const Placement& X_WB, const LoadState& state,
                     std::vector<Eigen::Vector3d>& nodes_W);

// --- the same at the placement the whisker was built with ---
inline Solution solve_force(const Whisker& w, double force, double arc_length, double angle,
                            const SolveOptions& options = {}) {
  return solve_force(w, w.placement(), force, arc_length, angle, options);
}
inline Solution solve_dead_load(const Whisker& w, const Eigen::Vector3d& force_W, double arc_length,
                                const SolveOptions& options = {}, const LoadState* warm = nullptr) {
  return solve_dead_load(w, w.placement(), force_W, arc_length, options, warm);
}
inline Solution solve_point(const Whisker& w, const Eigen::Vector3d& point_W,
                            std::optional<double> arc_length_hint = std::nullopt, const SolveOptions& options = {},
                            const LoadState* warm = nullptr,
                            const std::optional<Eigen::Vector3d>& edge_direction_W = std::nullopt) {
  return solve_point(w, w.placement(), point_W, arc_length_hint, options, warm, edge_direction_W);
}
inline Solution solve_edge(const Whisker& w, const Edge& edge, std::optional<double> arc_length_hint = std::nullopt,
                           const SolveOptions& options = {}, const LoadState* warm = nullptr,
                           const std::optional<Eigen::Vector3d>& approach_W = std::nullopt) {
  return solve_edge(w, w.placement(), edge, arc_length_hint, options, warm, approach_W);
}
inline Solution solve_frictional_edge(const Whisker& w, const Edge& edge, double mu,
                                      const Eigen::Vector3d& previous_contact_W, const SolveOptions& options = {},
                                      const LoadState* warm = nullptr,
                                      const std::optional<Eigen::Vector3d>& approach_W = std::nullopt) {
  return solve_frictional_edge(w, w.placement(), edge, mu, previous_contact_W, options, warm, approach_W);
}

}  // namespace vibrissa
