#include "contact_evaluations.hpp"

#include <array>
#include <cmath>

#include "contact_problem.hpp"

namespace vibrissa::detail {
namespace {

/// The nine kinematic quantities of a record (const or not), in the order LoadSensitivity stores them.
template <class Kinematics>
auto components(Kinematics& k) {
  return std::array{&k.p_contact_B.x, &k.p_contact_B.y, &k.p_contact_B.z, &k.force_B.x, &k.force_B.y,
                    &k.force_B.z,     &k.couple_B.x,    &k.couple_B.y,    &k.couple_B.z};
}

}  // namespace

namespace {
/// A load the record's normal-force evaluations can hold: no axial force, no couple.
bool normal_load(const LoadState& s) {
  return s.force_x == 0.0 && s.couple_x == 0.0 && s.couple_y == 0.0 && s.couple_z == 0.0;
}
}  // namespace

std::optional<ContactKinematics<double>> ContactEvaluations::at(const LoadState& state) const {
  if (!normal_load(state)) return std::nullopt;
  return at_load(Eigen::Vector3d(state.force_y, state.force_z, state.arc_length));
}

std::optional<ContactKinematics<double>> ContactEvaluations::at_load(const Eigen::Vector3d& load) const {
  if (load == value_load_) return value_;
  if (load == jacobian_load_) {
    auto v = [](const V3<Dual<3>>& x) { return V3<double>(x.x.v, x.y.v, x.z.v); };
    return ContactKinematics<double>{v(jacobian_.p_contact_B), v(jacobian_.force_B), v(jacobian_.couple_B)};
  }
  return std::nullopt;
}

std::optional<ContactKinematics<Dual<3>>> ContactEvaluations::secant_update() const {
  // Broyden's update of K = dk/du from u_J to u: K + (k(u) - k(u_J) - K s) s^T / (s^T s), s = u - u_J.
  if (!(value_u_ == value_u_) || !(jacobian_u_ == jacobian_u_)) return std::nullopt;  // NaN: nothing recorded
  const Eigen::Vector3d s = value_u_ - jacobian_u_;
  const double ss = s.squaredNorm();
  if (!(ss > 0.0)) return std::nullopt;
  ContactKinematics<Dual<3>> out = jacobian_;
  const auto to = components(out);
  const auto from = components(jacobian_);
  const auto value = components(value_);
  for (std::size_t i = 0; i < 9; ++i) {
    const Dual<3>& k = *from[i];
    const double predicted = k.d[0] * s[0] + k.d[1] * s[1] + k.d[2] * s[2];
    const double c = (*value[i] - k.v - predicted) / ss;
    to[i]->v = *value[i];
    for (std::size_t j = 0; j < 3; ++j) {
      to[i]->d[j] = k.d[j] + c * s[static_cast<Eigen::Index>(j)];
      if (!std::isfinite(to[i]->d[j])) return std::nullopt;
    }
  }
  return out;
}

void ContactEvaluations::forget_estimate() {
  if (!estimated_) return;
  jacobian_load_ = jacobian_u_ = Eigen::Vector3d::Constant(none);
  estimated_ = false;
}

Eigen::Vector3d ContactEvaluations::start_at(const Whisker& w, const Scales& sc, const LoadState& state) {
  const LoadSensitivity& c = state.sensitivity;
  const Eigen::Vector3d u(c.unknowns[0], c.unknowns[1], c.unknowns[2]);
  const Eigen::Vector3d load = sc.load(u);
  if (c.whisker == 0 || c.whisker != w.mechanics_fingerprint() || !normal_load(state) ||
      load != Eigen::Vector3d(state.force_y, state.force_z, state.arc_length))
    return unknowns_from_state(state, sc);
  const auto to = components(jacobian_);
  for (std::size_t i = 0; i < 9; ++i) {
    to[i]->v = c.kinematics[4 * i];
    for (std::size_t j = 0; j < 3; ++j) to[i]->d[j] = c.kinematics[4 * i + 1 + j];
  }
  jacobian_load_ = load;
  jacobian_u_ = u;
  estimated_ = true;
  return u;
}

LoadSensitivity ContactEvaluations::sensitivity_at(const Whisker& w, const LoadState& state) const {
  LoadSensitivity out;
  if (!normal_load(state)) return out;
  const Eigen::Vector3d load(state.force_y, state.force_z, state.arc_length);
  std::optional<ContactKinematics<Dual<3>>> k;
  Eigen::Vector3d u;
  if (load == jacobian_load_) {
    k = jacobian_;
    u = jacobian_u_;
  } else if (load == value_load_) {
    k = secant_update();
    u = value_u_;
  }
  if (!k) return out;
  const auto from = components(*k);
  for (std::size_t i = 0; i < 9; ++i) {
    out.kinematics[4 * i] = from[i]->v;
    for (std::size_t j = 0; j < 3; ++j) out.kinematics[4 * i + 1 + j] = from[i]->d[j];
  }
  out.unknowns = {u[0], u[1], u[2]};
  out.whisker = w.mechanics_fingerprint();
  return out;
}

}  // namespace vibrissa::detail
