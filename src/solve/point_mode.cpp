// Contact-point mode (spec §2.1, "contact-point simulations"): find (F_y, F_z, s) such that the deflected
// whisker passes through the tracked point with the force normal to it there. Friction along the object is
// implicit: the tracked point fixes where the contact is.
#include <cmath>

#include "contact_problem.hpp"
#include "solution_check.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {

namespace {

struct PointAttempt {
  detail::LMResult lm;
  Status status = Status::not_converged;
};

PointAttempt attempt_point(const Whisker& w, const detail::Scales& sc, const Eigen::Vector3d& target_B,
                           const Eigen::Vector3d& u0, const SolveOptions& options) {
  const Eigen::Vector3d t = target_B / sc.length;
  auto residual = [&](const auto& u) {
    using S = std::decay_t<decltype(u[0])>;
    const auto c = detail::contact_at<S>(w, sc, u);
    return std::array<S, 3>{c.p_contact_B.x / sc.length - t.x(), c.p_contact_B.y / sc.length - t.y(),
                            c.p_contact_B.z / sc.length - t.z()};
  };
  PointAttempt a;
  a.lm = detail::levenberg_marquardt(residual, u0, detail::contact_bounds(), options.tolerance / sc.length,
                                     options.max_iterations);
  if (a.lm.converged)
    a.status = a.lm.u[2] > 1.0 + 1e-12 ? Status::slipped_off : Status::converged;
  else
    a.status = a.lm.at_upper_bound ? Status::slipped_off : Status::not_converged;
  return a;
}

}  // namespace

Solution solve_point(const Whisker& w, const Placement& X, const Eigen::Vector3d& point_W, std::optional<double> hint,
                     const SolveOptions& options, const LoadState* warm,
                     const std::optional<Eigen::Vector3d>& edge_direction_W) {
  validate(options);
  require_finite(point_W, "load.point");
  if (hint) require_finite(*hint, "load.arc_length_hint");
  if (edge_direction_W) {
    require_finite(*edge_direction_W, "load.edge_direction");
    require_normalizable(*edge_direction_W, "load.edge_direction");
  }
  const detail::Scales sc(w);
  const Eigen::Vector3d target_B = X.to_body(point_W);
  const double distance = target_B.norm();
  if (distance > w.length())
    return detail::unloaded_solution(w, X, Status::no_contact,
                                     "the target point lies beyond the whisker's length from the base", options);

  Eigen::Vector3d u0;
  if (warm) {
    u0 = detail::unknowns_from_state(*warm, sc);
  } else {
    const double s0 = hint ? std::clamp(*hint, 1e-6 * sc.length, w.length()) : detail::arc_length_at_distance(w, distance);
    u0 = Eigen::Vector3d(0.0, 0.0, s0 / sc.length);
  }
  PointAttempt a = attempt_point(w, sc, target_B, u0, options);
  if (hint && !warm) {  // the root nearest the hint: also start a little to either side, keep the nearest
    const double h = *hint / sc.length;
    for (double s_try : {h - 0.1, h + 0.1, 0.25, 0.5, 0.75, 1.0}) {  // basins are not intervals: probe widely
      const PointAttempt b = attempt_point(w, sc, target_B, Eigen::Vector3d(0.0, 0.0, std::clamp(s_try, 1e-6, 1.0)), options);
      if (b.status == Status::converged &&
          (a.status != Status::converged || std::abs(b.lm.u[2] - h) < std::abs(a.lm.u[2] - h) - 1e-9))
        a = b;
    }
  }
  if (a.status == Status::not_converged && warm) {  // a bad warm start: fall back to the cold rule
    const double s0 = detail::arc_length_at_distance(w, distance);
    PointAttempt cold = attempt_point(w, sc, target_B, Eigen::Vector3d(0.0, 0.0, s0 / sc.length), options);
    cold.lm.iterations += a.lm.iterations;
    a = cold;
  }

  Solution out;
  detail::fill_solution(w, X, detail::state_from_unknowns(a.lm.u, sc), options, edge_direction_W, out);
  out.iterations = a.lm.iterations;
  out.residual = a.lm.residual * sc.length;
  switch (a.status) {
    case Status::converged: detail::set_status(out, a.status, "contact point reached"); break;
    case Status::slipped_off:
      detail::set_status(out, a.status, "reaching the point would need contact beyond the tip");
      break;
    default: detail::set_status(out, a.status, "no equilibrium through the point within the iteration limit"); break;
  }
  if (a.status == Status::converged && options.find_other_roots) {
    const double s_star = a.lm.u[2];
    for (double s_try : {0.25, 0.5, 0.75, 1.0}) {  // probes along the whisker, away from the root found
      if (std::abs(s_try - s_star) < 0.05) continue;
      const PointAttempt other = attempt_point(w, sc, target_B, Eigen::Vector3d(0.0, 0.0, s_try), options);
      if (other.status == Status::converged && std::abs(other.lm.u[2] - s_star) > 0.01) {
        out.other_root_arc_length = other.lm.u[2] * sc.length;
        break;
      }
    }
  }
  return detail::checked_solution(std::move(out), options.tolerance, w, X, options);
}

}  // namespace vibrissa
