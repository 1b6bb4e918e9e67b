#pragma once
// Shared pieces of the contact solves: scaling of the unknowns, residual functors (templated so they run
// on Dual<3>), and assembly of a Solution from solved unknowns.
#include <array>
#include <optional>

#include <Eigen/Core>

#include "levenberg_marquardt.hpp"
#include "vibrissa/core/chain_jacobian.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/solve/solution.hpp"

namespace vibrissa::detail {

/// Non-dimensionalisation: forces by E I_0 / L^2, lengths by L. Unknowns u = (F_y, F_z, s) scaled.
struct Scales {
  double length;  ///< L [m]
  double force;   ///< E I_0 / L^2 [N]
  explicit Scales(const Whisker& w)
      : length(w.length()), force(w.base_bending_stiffness() / (w.length() * w.length())) {}
};

/// Bounds on u: forces free; s/L in [1e-9, 1.5] (beyond 1 the last link is extended: slip-off detection).
LMBounds contact_bounds();

/// u from a warm-start state, and back.
Eigen::Vector3d unknowns_from_state(const LoadState& state, const Scales& sc);
LoadState state_from_unknowns(const Eigen::Vector3d& u, const Scales& sc);

/// Contact kinematics for scaled unknowns u = (F_y, F_z, s) of a normal follower force.
template <class S>
ContactKinematics<S> contact_at(const Whisker& w, const Scales& sc, const std::array<S, 3>& u) {
  const V3<S> force(S(0.0), sc.force * u[0], sc.force * u[1]);
  return deflect_for_solve<S>(w, force, V3<S>(S(0.0), S(0.0), S(0.0)), sc.length * u[2]);
}

/// The force-mode angle of a load (docs/conventions.md, "Loads and signs"): second-order scheme,
/// F = f (0, cos a, sin a) in the loaded link's frame; paper scheme, Elastica3D's ζ.
double force_angle(const Whisker& w, const Placement& X_WB, const LoadState& state);
/// Sets state.force_{x,y,z} for a normal force of magnitude `force` and force-mode angle `angle` at
/// state.arc_length (the inverse of force_angle).
void set_force_angle(const Whisker& w, const Placement& X_WB, double force, double angle, LoadState& state);

/// Orthonormal pair spanning the plane normal to unit vector d.
void normal_basis(const Eigen::Vector3d& d, Eigen::Vector3d& e1, Eigen::Vector3d& e2);

/// Fills every output of a Solution from the solved state (world and whisker-frame signals, shape).
/// `edge_direction_W` (unit) adds normal_force / edge_force. Scratch storage is per thread (allocated once).
void fill_solution(const Whisker& w, const Placement& X_WB, const LoadState& state, const SolveOptions& options,
                   const std::optional<Eigen::Vector3d>& edge_direction_W, Solution& out);

/// Sets the status and the contact state that goes with it (converged: contact; slipped_off: pushed_past;
/// no_contact and not_converged: free).
void set_status(Solution& out, Status status, std::string_view message);

/// A Solution for "no load": rest shape, zero force, with status and message.
Solution unloaded_solution(const Whisker& w, const Placement& X_WB, Status status, std::string_view message,
                           const SolveOptions& options);

/// Arc length at which the rest whisker is first as far from the base as `distance` (or L).
double arc_length_at_distance(const Whisker& w, double distance);

}  // namespace vibrissa::detail
