// Edge mode (spec §2.1, §3.1): frictionless slip along a straight edge. Unknowns (F_y, F_z, s); equations:
// the contact lies on the line, and the force is normal to the line (it is normal to the whisker by
// construction). The whisker is pushed, never pulled (docs/conventions.md, "Contact side").
#include <cmath>
#include <limits>
#include <optional>

#include "edge_problem.hpp"
#include "solution_check.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {

void validate(const Edge& edge) {
  require_finite(edge.point, "edge.point");
  require_normalizable(edge.direction, "edge.direction");
}

namespace detail {

/// Checks that a converged edge contact pushes the whisker; rewrites the status if it does not.
void check_contact_side(const Whisker& w, const Placement& X, const std::optional<Eigen::Vector3d>& approach_W,
                        Solution& out) {
  if (out.status != Status::converged || out.force_magnitude == 0.0) return;
  const Eigen::Vector3d displacement = out.contact_point_W - X.to_world(w.rest_point_B(out.arc_length));
  if (out.force_W.dot(displacement) < -1e-12 * out.force_magnitude * w.length()) {
    set_status(out, Status::no_contact, "the edge would have to pull the whisker toward it: not pressed against the edge");
    out.friction = FrictionState::none;
  } else if (approach_W && out.force_W.dot(*approach_W) > 0.0) {
    set_status(out, Status::no_contact, "the whisker is on the far side of the edge for the given approach direction");
    out.friction = FrictionState::none;
  }
}

}  // namespace detail

Solution solve_edge(const Whisker& w, const Placement& X, const Edge& edge, std::optional<double> hint,
                    const SolveOptions& options, const LoadState* warm,
                    const std::optional<Eigen::Vector3d>& approach_W) {
  return detail::solve_edge_from(w, X, edge, hint, options, warm, approach_W, nullptr);
}

namespace detail {

Solution solve_edge_from(const Whisker& w, const Placement& X, const Edge& edge, std::optional<double> hint,
                         const SolveOptions& options, const LoadState* warm,
                         const std::optional<Eigen::Vector3d>& approach_W, const ContactEvaluations* known) {
  validate(options);
  validate(edge);
  if (hint) require_finite(*hint, "load.arc_length_hint");
  if (approach_W) require_finite(*approach_W, "load.approach");
  const detail::Scales sc(w);
  const detail::EdgeGeometryB g = detail::edge_in_body(X, edge);
  if (!detail::within_reach(w, g))
    return detail::unloaded_solution(w, X, Status::no_contact, "the edge is out of the whisker's reach", options);

  // The rest point nearest the line: needed only where a solve starts from it (not on warm frames).
  std::optional<double> nearest;
  auto s_near = [&] {
    if (!nearest) nearest = detail::nearest_rest_arc_length(w, g);
    return *nearest;
  };
  Eigen::Vector3d u0;
  detail::ContactEvaluations carried;  // what the solve that produced `warm` left with it
  if (warm) {
    u0 = carried.start_at(w, sc, *warm);
    if (!known) known = &carried;
  } else if (hint) {
    u0 = Eigen::Vector3d(0.0, 0.0, std::clamp(*hint, 1e-6 * sc.length, w.length()) / sc.length);
  } else if (const auto guess = detail::cantilever_start(w, sc, g.point, g.direction)) {
    u0 = *guess;  // beam theory, as Elastica3D starts
  } else {
    u0 = Eigen::Vector3d(0.0, 0.0, s_near() / sc.length);  // zero force at the rest point nearest the line
  }
  detail::EdgeAttempt a = detail::attempt_edge(w, sc, g, 0.0, u0, options, known);
  if (a.status == Status::not_converged && (warm || hint)) {
    detail::EdgeAttempt cold =
        detail::attempt_edge(w, sc, g, 0.0, Eigen::Vector3d(0.0, 0.0, s_near() / sc.length), options);
    cold.lm.iterations += a.lm.iterations;
    a = cold;
  }
  if (a.status == Status::not_converged) a = detail::continue_from_touch(w, sc, g, s_near(), options, a);
  if (a.status == Status::slipped_off) {  // released: the whisker is free again (rest shape, no force)
    Solution off = detail::unloaded_solution(
        w, X, Status::slipped_off,
        a.folded ? "the contact equilibrium ends in a fold: the whisker snaps past the edge (push-past)"
                 : "equilibrium would need contact beyond the tip: the whisker slips off",
        options);
    off.fold = a.folded;
    off.iterations = a.lm.iterations;
    off.arc_length = std::min(a.lm.u[2] * sc.length, w.length());
    return detail::checked_solution(std::move(off), options.tolerance, w, X, options);
  }
  Solution out;
  detail::fill_solution(w, X, detail::state_from_unknowns(a.lm.u, sc), options, edge.direction.normalized(), out,
                        &a.evaluations);
  detail::set_status(out, a.status,
                     a.status == Status::converged ? "frictionless contact on the edge"
                                                   : "no equilibrium on the edge within the iteration limit");
  out.iterations = a.lm.iterations;
  out.residual = a.lm.residual * sc.length;
  detail::check_contact_side(w, X, approach_W, out);
  if (out.status == Status::converged && options.find_other_roots && !warm) {  // warm frames do not probe
    const double s_star = a.lm.u[2];
    for (double s_try : {0.25, 0.5, 0.75, 1.0}) {
      if (std::abs(s_try - s_star) < 0.05) continue;
      const auto other = detail::attempt_edge(w, sc, g, 0.0, Eigen::Vector3d(0.0, 0.0, s_try), options);
      if (other.status == Status::converged && std::abs(other.lm.u[2] - s_star) > 0.01) {
        out.other_root_arc_length = other.lm.u[2] * sc.length;
        break;
      }
    }
  }
  return detail::checked_solution(std::move(out), options.tolerance, w, X, options);
}

}  // namespace detail

}  // namespace vibrissa
