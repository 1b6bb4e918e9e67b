#pragma once
// Shared pieces of the contact solves: bounds and states of the unknowns, cold starts, and assembly of a
// Solution from solved unknowns (scaling and the record of evaluations: contact_evaluations.hpp).
#include <optional>

#include <Eigen/Core>

#include "contact_evaluations.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/solve/solution.hpp"

namespace vibrissa::detail {

/// Bounds on u: forces free; s/L in [1e-9, 1.5] (beyond 1 the last link is extended: slip-off detection).
LMBounds contact_bounds();

/// u from a warm-start state, and back.
Eigen::Vector3d unknowns_from_state(const LoadState& state, const Scales& sc);
LoadState state_from_unknowns(const Eigen::Vector3d& u, const Scales& sc);

/// The force-mode angle of a load (docs/conventions.md, "Loads and signs"): second-order scheme,
/// F = f (0, cos a, sin a) in the loaded link's frame; paper scheme, Elastica3D's ζ.
double force_angle(const Whisker& w, const Placement& X_WB, const LoadState& state);
/// Sets state.force_{x,y,z} for a normal force of magnitude `force` and force-mode angle `angle` at
/// state.arc_length (the inverse of force_angle).
void set_force_angle(const Whisker& w, const Placement& X_WB, double force, double angle, LoadState& state);

/// Orthonormal pair spanning the plane normal to unit vector d.
void normal_basis(const Eigen::Vector3d& d, Eigen::Vector3d& e1, Eigen::Vector3d& e2);

/// solve_point() whose first attempt reuses `known` evaluations (nullptr: none).
Solution solve_point_from(const Whisker& w, const Placement& X_WB, const Eigen::Vector3d& point_W,
                          std::optional<double> hint, const SolveOptions& options, const LoadState* warm,
                          const std::optional<Eigen::Vector3d>& edge_direction_W, const ContactEvaluations* known);

/// Fills every output of a Solution from the solved state (world and whisker-frame signals, shape).
/// `edge_direction_W` (unit) adds normal_force / edge_force. `evaluated`, if it holds the kinematics at
/// `state`, saves the forward evaluation (the shape of the second-order scheme still walks the chain for the
/// joint rotations). `kinematics`: the kinematics at `state`, known (the same saving; the object modes).
/// Scratch storage is per thread (allocated once).
void fill_solution(const Whisker& w, const Placement& X_WB, const LoadState& state, const SolveOptions& options,
                   const std::optional<Eigen::Vector3d>& edge_direction_W, Solution& out,
                   const ContactEvaluations* evaluated = nullptr,
                   const ContactKinematics<double>* kinematics = nullptr);

/// Sets the status and the contact state that goes with it (converged: contact; slipped_off: pushed_past;
/// no_contact and not_converged: free).
void set_status(Solution& out, Status status, std::string_view message);

/// A Solution for "no load": rest shape, zero force, with status and message.
Solution unloaded_solution(const Whisker& w, const Placement& X_WB, Status status, std::string_view message,
                           const SolveOptions& options);

/// Arc length at which the rest whisker is first as far from the base as `distance` (or L), distances
/// measured normal to the unit vector `along` if given (seen along it).
double arc_length_at_distance(const Whisker& w, double distance, const Eigen::Vector3d& along = Eigen::Vector3d::Zero());

/// Transverse compliance of the rest whisker at arc length s as a straight cantilever [m/N]: a force there
/// turns joint j (at s_j < s) by w_j (s - s_j) F / E I_j, which moves the load point by (s - s_j) times that
/// (chain.hpp, eqs. (1), (3)), plus the follicle spring's s^2 / k.
double cantilever_compliance(const Whisker& w, double s);

/// Largest turn about the base, from the rest point to where the contact must go, for which a cold solve
/// starts from the cantilever guess [rad]. Beyond it linear beam theory is no guide, and which of several
/// equilibria a solve reaches depends on its path: those start from zero force, as before issue 13.
inline constexpr double max_cantilever_turn = 0.5;

/// The beam-theory first guess of a cold solve (as Elastica3D starts its search), toward `target_B` seen along
/// the unit vector `along` (a line through it; zero: the point itself): scaled unknowns (F_y, F_z, s) with s
/// where the rest whisker, seen so, is as far from the base as the target (a rotation about the base keeps
/// that distance) and the normal force that moves that point there as a linear cantilever. nullopt if the
/// point must turn about the base by more than max_cantilever_turn.
std::optional<Eigen::Vector3d> cantilever_start(const Whisker& w, const Scales& sc, const Eigen::Vector3d& target_B,
                                                const Eigen::Vector3d& along);

}  // namespace vibrissa::detail
