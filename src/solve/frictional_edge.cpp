// Frictional edge mode: Coulomb friction mu along the edge, quasi-static, with contact history.
// Beyond the paper (its §4.4 names it future work). Per frame:
//   1. the frictionless edge solution gives the point q_free the contact would slip to (and detects release);
//   2. stick: the contact stays at the previous point q_prev if the edge-parallel force needed there is
//      within the friction cone, |F_par| <= mu F_N (contact-point mode at q_prev);
//   3. slip: otherwise the contact moves from q_prev toward q_free, to where |F_par| = mu F_N with friction
//      opposing the slip; by §3.1 it lies between the two points.
#include <cmath>

#include "edge_problem.hpp"
#include "solution_check.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {

Solution solve_frictional_edge(const Whisker& w, const Placement& X, const Edge& edge, double mu,
                               const Eigen::Vector3d& previous_contact_W, const SolveOptions& options,
                               const LoadState* warm, const std::optional<Eigen::Vector3d>& approach_W) {
  validate(options);
  validate(edge);
  require_finite(mu, "friction_coefficient");
  if (mu < 0.0) invalid_input("friction_coefficient must be >= 0, got " + format_value(mu));
  require_finite(previous_contact_W, "previous_contact");
  const Eigen::Vector3d d = edge.direction.normalized();
  const Eigen::Vector3d q_prev = edge.point + (previous_contact_W - edge.point).dot(d) * d;

  SolveOptions inner = options;
  inner.compute_shape = false;
  inner.find_other_roots = false;
  // Both the frictionless and the stick solve start at the previous frame's state: one Jacobian there serves
  // both (their first evaluation): the estimate the previous solve left with its state, or one evaluated here.
  const detail::Scales sc(w);
  detail::ContactEvaluations at_warm;
  if (warm) {
    const Eigen::Vector3d u0 = at_warm.start_at(w, sc, *warm);
    if (!at_warm.at(*warm)) at_warm.evaluate_jacobian_at(w, sc, u0);
  }
  const detail::ContactEvaluations* known = warm ? &at_warm : nullptr;
  const Solution free = detail::solve_edge_from(w, X, edge, std::nullopt, inner, warm, approach_W, known);
  // The reported Solution: outputs from the final state (with the caller's options), typed outcome. A
  // converged inner solve already filled them for the same state and edge direction: without a shape they
  // are copied (evaluations: the slip attempt's, whose converged point they hold).
  auto finish = [&](const Solution& s, FrictionState friction, std::string_view message,
                    const detail::ContactEvaluations* evaluations = nullptr) {
    Solution out;
    if (s.status == Status::converged && !options.compute_shape && !evaluations)
      out = s;
    else
      detail::fill_solution(w, X, s.state, options, d, out, evaluations);
    detail::set_status(out, s.status, message);
    out.fold = s.fold;
    out.friction = s.status == Status::converged ? friction : FrictionState::none;
    out.iterations = s.iterations;
    out.residual = s.residual;
    return detail::checked_solution(std::move(out), options.tolerance, w, X, options);
  };
  if (free.status != Status::converged) return finish(free, FrictionState::none, free.message);
  if (mu == 0.0) return finish(free, FrictionState::slip, "frictionless: slipping on the edge");

  // 2. Stick at the previous contact.
  const LoadState* stick_start = warm ? warm : &free.state;
  Solution stick = detail::solve_point_from(w, X, q_prev, std::nullopt, inner, stick_start, d, known);
  if (stick.status == Status::converged) {
    detail::check_contact_side(w, X, approach_W, stick);
    if (stick.status == Status::converged && std::abs(*stick.edge_force) <= mu * *stick.normal_force * (1.0 + 1e-9)) {
      stick.iterations += free.iterations;
      return finish(stick, FrictionState::stick, "stick: the contact holds its previous point on the edge");
    }
  }

  // 3. Slip toward the frictionless point until the friction cone is met.
  const double travel = (free.contact_point_W - q_prev).dot(d);
  if (travel == 0.0)
    return finish(free, FrictionState::slip, "slip: previous contact coincides with the frictionless point");
  const double sigma = travel > 0.0 ? 1.0 : -1.0;
  const detail::EdgeGeometryB g = detail::edge_in_body(X, edge);
  detail::EdgeAttempt best;
  for (const LoadState* start : {stick.status == Status::converged ? &stick.state : &free.state, &free.state}) {
    detail::ContactEvaluations carried;  // what the stick or frictionless solve left with its state
    const Eigen::Vector3d u0 = carried.start_at(w, sc, *start);
    best = detail::attempt_edge(w, sc, g, sigma * mu, u0, inner, &carried);
    if (best.status == Status::converged) break;
  }
  Solution slip;
  slip.state = detail::state_from_unknowns(best.lm.u, sc);
  slip.status = best.status;
  slip.iterations = best.lm.iterations + free.iterations + stick.iterations;
  slip.residual = best.lm.residual * sc.length;
  Solution out = finish(slip, FrictionState::slip,
                        best.status == Status::converged
                            ? "slip: contact moved along the edge with |F_edge| = mu F_N"
                            : (best.status == Status::slipped_off
                                   ? "slip: equilibrium would need contact beyond the tip"
                                   : "slip: no frictional equilibrium within the iteration limit"),
                        &best.evaluations);
  detail::check_contact_side(w, X, approach_W, out);
  return detail::checked_solution(std::move(out), options.tolerance, w, X, options);
}

}  // namespace vibrissa
