#pragma once
// Shared pieces of the contact solves: scaling of the unknowns, residual functors (templated so they run
// on Dual<3>), and assembly of a Solution from solved unknowns.
#include <array>
#include <limits>
#include <optional>
#include <type_traits>

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

/// The contact kinematics an attempt evaluated last, on doubles and with the Jacobian, each with the load it
/// was evaluated at (F_y, F_z, s: exactly the numbers given to the walk). An evaluation at the same load is
/// taken from here instead of walking the chain again: the converged point's kinematics give the Solution's
/// outputs (fill_solution; for an attempt that stopped unconverged, its last Jacobian evaluation's values).
/// Values of a Jacobian evaluation are the same numbers as the double walk's (core/chain_jacobian.hpp).
/// A record made for one whisker may seed attempts on the same whisker (frictional edge: the previous frame's
/// Jacobian serves both the frictionless and the stick solve, which start there).
class ContactEvaluations {
 public:
  /// contact_at() through the record: scaled unknowns u; a Dual<3> u must be seeded as the LM seeds it
  /// (derivative i of u[i] one, the others zero) for its Jacobian to be recorded or reused.
  template <class S>
  ContactKinematics<S> contact_at(const Whisker& w, const Scales& sc, const std::array<S, 3>& u);
  /// The kinematics at `state` if an evaluation was at exactly that load (normal loads: force_x = 0).
  [[nodiscard]] std::optional<ContactKinematics<double>> at(const LoadState& state) const;
  /// Records the kinematics with the Jacobian at scaled unknowns u (as an attempt starting at u evaluates).
  void evaluate_jacobian_at(const Whisker& w, const Scales& sc, const Eigen::Vector3d& u) {
    using D = Dual<3>;
    (void)contact_at<D>(w, sc, std::array<D, 3>{D::variable(u[0], 0), D::variable(u[1], 1), D::variable(u[2], 2)});
  }

 private:
  [[nodiscard]] std::optional<ContactKinematics<double>> at_load(const Eigen::Vector3d& load) const;
  static constexpr double none = std::numeric_limits<double>::quiet_NaN();  // never equal: nothing recorded
  Eigen::Vector3d value_load_{none, none, none}, jacobian_load_{none, none, none};
  ContactKinematics<double> value_;
  ContactKinematics<Dual<3>> jacobian_;
};

template <class S>
ContactKinematics<S> ContactEvaluations::contact_at(const Whisker& w, const Scales& sc, const std::array<S, 3>& u) {
  const Eigen::Vector3d load(sc.force * value_of(u[0]), sc.force * value_of(u[1]), sc.length * value_of(u[2]));
  if constexpr (std::is_same_v<S, double>) {
    if (auto known = at_load(load)) return *known;
    value_ = detail::contact_at<double>(w, sc, u);
    value_load_ = load;
    return value_;
  } else {
    bool seeded = true;
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j) seeded = seeded && u[i].d[j] == (i == j ? 1.0 : 0.0);
    if (!seeded) return detail::contact_at<S>(w, sc, u);
    if (load == jacobian_load_) return jacobian_;
    jacobian_ = detail::contact_at<S>(w, sc, u);
    jacobian_load_ = load;
    return jacobian_;
  }
}

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
/// joint rotations). Scratch storage is per thread (allocated once).
void fill_solution(const Whisker& w, const Placement& X_WB, const LoadState& state, const SolveOptions& options,
                   const std::optional<Eigen::Vector3d>& edge_direction_W, Solution& out,
                   const ContactEvaluations* evaluated = nullptr);

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
