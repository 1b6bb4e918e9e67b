// Force mode (spec §2.1): the load is given, the shape follows explicitly. Dead loads (fixed world
// direction) are found by solving for the follower load whose deflected direction equals the given one.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_problem.hpp"
#include "solution_check.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {

namespace {
void check_arc_length(const Whisker& w, double s) {
  require_finite(s, "load.arc_length");
  if (!(s > 0.0 && s <= w.length() * (1.0 + 1e-12)))
    invalid_input("load.arc_length must lie in (0, L = " + format_value(w.length()) + "] m, got " + format_value(s));
}
}  // namespace

Solution solve_force(const Whisker& w, const Placement& X, double force, double arc_length, double angle,
                     const SolveOptions& options) {
  validate(options);
  require_finite(force, "load.force");
  if (force < 0.0) invalid_input("load.force must be >= 0 (use angle to set direction), got " + format_value(force));
  require_finite(angle, "load.angle");
  check_arc_length(w, arc_length);
  LoadState state;
  state.arc_length = arc_length;
  detail::set_force_angle(w, X, force, angle, state);
  Solution out;
  detail::fill_solution(w, X, state, options, std::nullopt, out);
  detail::set_status(out, Status::converged, "explicit force-mode evaluation");
  return detail::checked_solution(std::move(out), options.tolerance, w, X, options);
}

Solution solve_dead_load(const Whisker& w, const Placement& X, const Eigen::Vector3d& force_W, double arc_length,
                         const SolveOptions& options, const LoadState* warm) {
  validate(options);
  require_finite(force_W, "load.force");
  check_arc_length(w, arc_length);
  const detail::Scales sc(w);
  const Eigen::Vector3d target_B = X.R_WB.transpose() * force_W / sc.force;
  int k;
  double h;
  w.locate(arc_length, k, h);
  // Start from the rest-frame components of the load (or the warm state).
  Eigen::Vector3d u0 = w.rest_link_frames_B()[static_cast<std::size_t>(k)].transpose() * target_B;
  if (warm) u0 = Eigen::Vector3d(warm->force_x, warm->force_y, warm->force_z) / sc.force;
  // Scaled tolerance on the force residual: the length tolerance over L, or 1e-14 of the load if larger.
  auto dead_load_tolerance = [&](const Eigen::Vector3d& goal) {
    return std::max(options.tolerance / sc.length, 1e-14 * std::max(1.0, goal.stableNorm()));  // no overflow
  };
  auto solve_for = [&](const Eigen::Vector3d& goal, const Eigen::Vector3d& start) {
    auto residual = [&](const auto& u) {
      using S = std::decay_t<decltype(u[0])>;
      const V3<S> F(u[0] * sc.force, u[1] * sc.force, u[2] * sc.force);
      const auto c = deflect_for_solve<S>(w, F, V3<S>(S(0.0), S(0.0), S(0.0)), S(arc_length));
      return std::array<S, 3>{c.force_B.x / sc.force - goal.x(), c.force_B.y / sc.force - goal.y(),
                              c.force_B.z / sc.force - goal.z()};
    };
    const double tol = dead_load_tolerance(goal);
    return detail::levenberg_marquardt(residual, start, detail::LMBounds{}, tol, options.max_iterations);
  };
  // Max-norm of the scaled residual of state u against the full load (not a continuation step's part of it).
  auto full_residual = [&](const Eigen::Vector3d& u) {
    const V3<double> F(u[0] * sc.force, u[1] * sc.force, u[2] * sc.force);
    const auto c = deflect_for_solve<double>(w, F, V3<double>(0.0, 0.0, 0.0), arc_length);
    return (Eigen::Vector3d(c.force_B.x, c.force_B.y, c.force_B.z) / sc.force - target_B).lpNorm<Eigen::Infinity>();
  };
  auto lm = solve_for(target_B, u0);
  if (!lm.converged) {  // continuation in the load magnitude from the unloaded rod (u = 0: exact at zero load)
    const auto c = detail::load_continuation(
        [&](double lambda, const Eigen::Vector3d& u, bool) { return solve_for(lambda * target_B, u); },
        Eigen::Vector3d::Zero(), 1.0 / 2048.0);
    const int iterations = lm.iterations + c.iterations;
    if (c.converged) {
      lm = c;
    } else {
      // Every reported residual belongs to the returned state: the last continuation step converged only for
      // a part of the load, so both candidates are judged against the whole load and the closer one is kept.
      const double inf = std::numeric_limits<double>::infinity();
      const double direct = std::isfinite(lm.residual) ? full_residual(lm.u) : inf;
      const double continued = std::isfinite(c.cost) ? full_residual(c.u) : inf;
      if (continued < direct) {
        lm = c;
        lm.residual = continued;
      } else if (std::isfinite(direct)) {
        lm.residual = direct;
      }
    }
    lm.converged = c.converged;
    lm.iterations = iterations;
  }
  LoadState state;
  state.force_x = lm.u[0] * sc.force;
  state.force_y = lm.u[1] * sc.force;
  state.force_z = lm.u[2] * sc.force;
  state.arc_length = arc_length;
  Solution out;
  detail::fill_solution(w, X, state, options, std::nullopt, out);
  out.iterations = lm.iterations;
  out.residual = lm.residual * sc.force;
  detail::set_status(out, lm.converged ? Status::converged : Status::not_converged,
                     lm.converged ? "dead load: follower equivalent found (residual in N)"
                                  : "dead load: no equilibrium found within the iteration limit (residual in N)");
  return detail::checked_solution(std::move(out), dead_load_tolerance(target_B) * sc.force, w, X, options);
}

}  // namespace vibrissa
