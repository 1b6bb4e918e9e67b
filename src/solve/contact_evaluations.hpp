#pragma once
// The record of a contact solve's chain evaluations: what it evaluated last (on doubles and with the
// Jacobian), reused where an evaluation repeats, and what a solve leaves with its state for the next frame
// (LoadSensitivity), from which a warm start takes its first step without walking the chain.
#include <array>
#include <limits>
#include <optional>
#include <type_traits>

#include <Eigen/Core>

#include "levenberg_marquardt.hpp"
#include "vibrissa/core/chain_jacobian.hpp"
#include "vibrissa/solve/solution.hpp"

namespace vibrissa::detail {

/// Non-dimensionalisation: forces by E I_0 / L^2, lengths by L. Unknowns u = (F_y, F_z, s) scaled.
struct Scales {
  double length;  ///< L [m]
  double force;   ///< E I_0 / L^2 [N]
  explicit Scales(const Whisker& w)
      : length(w.length()), force(w.base_bending_stiffness() / (w.length() * w.length())) {}
  /// The load (F_y, F_z, s) of scaled unknowns u: exactly the numbers given to the walk.
  [[nodiscard]] Eigen::Vector3d load(const Eigen::Vector3d& u) const { return {force * u[0], force * u[1], length * u[2]}; }
};

/// Contact kinematics for scaled unknowns u = (F_y, F_z, s) of a normal follower force.
template <class S>
ContactKinematics<S> contact_at(const Whisker& w, const Scales& sc, const std::array<S, 3>& u) {
  const V3<S> force(S(0.0), sc.force * u[0], sc.force * u[1]);
  return deflect_for_solve<S>(w, force, V3<S>(S(0.0), S(0.0), S(0.0)), sc.length * u[2]);
}

/// The contact kinematics an attempt evaluated last, on doubles and with the Jacobian, each keyed by the load it
/// was evaluated at (F_y, F_z, s: exactly the numbers given to the walk). An evaluation at the same load is
/// taken from here instead of walking the chain again: the converged point's kinematics give the Solution's
/// outputs (fill_solution; for an attempt that stopped unconverged, its last Jacobian evaluation's values).
/// Values of a Jacobian evaluation agree with the double walk's to rounding (core/chain_jacobian.hpp).
/// A record made for one whisker may seed attempts on the same whisker (frictional edge: the previous frame's
/// Jacobian serves both the frictionless and the stick solve, which start there).
///
/// Warm starts (LoadSensitivity): a solve leaves with its state the kinematics at its solution and their
/// derivatives — its last Jacobian, moved there by one secant (Broyden) update
/// K + (k(u) - k(u_J) - K s) s^T / (s^T s), s = u - u_J, when it was evaluated one step earlier. A warm start
/// from that state on the same whisker (start_at) has its starting residual exactly (the kinematics in the
/// whisker frame do not depend on the pose) and takes its first step from that estimate: a Newton step of the
/// new frame's equations that costs no walk. Only that first Jacobian is an estimate: levenberg_marquardt()
/// evaluates every later one, and takes the first step again from an exact Jacobian if it does not shrink the
/// residual tenfold (JacobianEstimates, estimate_contraction).
class ContactEvaluations final : public JacobianEstimates {
 public:
  /// contact_at() through the record: scaled unknowns u; a Dual<3> u must be seeded as the LM seeds it
  /// (derivative i of u[i] one, the others zero) for its Jacobian to be recorded or reused.
  template <class S>
  ContactKinematics<S> contact_at(const Whisker& w, const Scales& sc, const std::array<S, 3>& u);
  /// The kinematics at `state` if an evaluation was at exactly that load (normal loads: force_x = 0).
  [[nodiscard]] std::optional<ContactKinematics<double>> at(const LoadState& state) const;
  /// Records the kinematics with the exact Jacobian at scaled unknowns u (as an attempt starting at u evaluates).
  void evaluate_jacobian_at(const Whisker& w, const Scales& sc, const Eigen::Vector3d& u) {
    using D = Dual<3>;
    (void)contact_at<D>(w, sc, std::array<D, 3>{D::variable(u[0], 0), D::variable(u[1], 1), D::variable(u[2], 2)});
  }
  /// Scaled unknowns a warm start from `state` begins at. If `state` carries a sensitivity made on this whisker
  /// at exactly its load, the record adopts it (the kinematics there and the Jacobian estimate) and the start is
  /// the solved unknowns it was made from; otherwise the state's load, scaled, and the record is unchanged.
  Eigen::Vector3d start_at(const Whisker& w, const Scales& sc, const LoadState& state);
  /// The sensitivity to leave with `state` (the solution's): the kinematics at its load with the last Jacobian
  /// (exact or estimated) carried there by one secant update. Empty (whisker 0) if the record holds no
  /// evaluation at that load or no Jacobian.
  [[nodiscard]] LoadSensitivity sensitivity_at(const Whisker& w, const LoadState& state) const;

  [[nodiscard]] bool estimated() const override { return estimated_; }
  void forget_estimate() override;

 private:
  [[nodiscard]] std::optional<ContactKinematics<double>> at_load(const Eigen::Vector3d& load) const;
  /// The last Jacobian moved to the value's point by a secant update (requires both; s != 0).
  [[nodiscard]] std::optional<ContactKinematics<Dual<3>>> secant_update() const;
  static constexpr double none = std::numeric_limits<double>::quiet_NaN();  // never equal: nothing recorded
  Eigen::Vector3d value_load_{none, none, none}, jacobian_load_{none, none, none};
  Eigen::Vector3d value_u_{none, none, none}, jacobian_u_{none, none, none};  // the same, scaled unknowns
  ContactKinematics<double> value_;
  ContactKinematics<Dual<3>> jacobian_;
  bool estimated_ = false;  ///< jacobian_'s derivatives are an estimate (adopted from a state's sensitivity)
};

template <class S>
ContactKinematics<S> ContactEvaluations::contact_at(const Whisker& w, const Scales& sc, const std::array<S, 3>& u) {
  const Eigen::Vector3d uv(value_of(u[0]), value_of(u[1]), value_of(u[2]));
  const Eigen::Vector3d load = sc.load(uv);
  if constexpr (std::is_same_v<S, double>) {
    if (auto known = at_load(load)) return *known;
    value_ = detail::contact_at<double>(w, sc, u);
    value_load_ = load;
    value_u_ = uv;
    return value_;
  } else {
    bool seeded = true;
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j) seeded = seeded && u[i].d[j] == (i == j ? 1.0 : 0.0);
    if (!seeded) return detail::contact_at<S>(w, sc, u);
    if (load == jacobian_load_) return jacobian_;
    jacobian_ = detail::contact_at<S>(w, sc, u);
    jacobian_load_ = load;
    jacobian_u_ = uv;
    estimated_ = false;
    return jacobian_;
  }
}

}  // namespace vibrissa::detail
