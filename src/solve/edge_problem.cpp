#include "edge_problem.hpp"

#include <algorithm>
#include <cmath>

namespace vibrissa::detail {

EdgeGeometryB edge_in_body(const Placement& X, const Edge& edge) {
  EdgeGeometryB g;
  g.point = X.to_body(edge.point);
  g.direction = (X.R_WB.transpose() * edge.direction).normalized();
  normal_basis(g.direction, g.e1, g.e2);
  return g;
}

EdgeAttempt attempt_edge(const Whisker& w, const Scales& sc, const EdgeGeometryB& g, double c,
                         const Eigen::Vector3d& u0, const SolveOptions& options, const ContactEvaluations* known) {
  const Eigen::Vector3d q = g.point / sc.length;
  EdgeAttempt a;
  if (known) a.evaluations = *known;
  auto residual = [&](const auto& u) {
    using S = std::decay_t<decltype(u[0])>;
    const auto k = a.evaluations.contact_at<S>(w, sc, u);
    const V3<S> rel(k.p_contact_B.x / sc.length - q.x(), k.p_contact_B.y / sc.length - q.y(),
                    k.p_contact_B.z / sc.length - q.z());
    const V3<S> F(k.force_B.x / sc.force, k.force_B.y / sc.force, k.force_B.z / sc.force);
    const V3<S> d(g.direction), e1(g.e1), e2(g.e2);
    S along = dot(F, d);
    if (c != 0.0) {
      using std::sqrt;
      const S normal2 = dot(F, F) - along * along;
      along = along + c * sqrt(normal2 + S(1e-300));
    }
    return std::array<S, 3>{dot(rel, e1), dot(rel, e2), along};
  };
  a.lm = levenberg_marquardt(residual, u0, contact_bounds(), options.tolerance / sc.length, options.max_iterations,
                             &a.evaluations);
  if (a.lm.converged)
    a.status = a.lm.u[2] > 1.0 + 1e-12 ? Status::slipped_off : Status::converged;
  else
    a.status = a.lm.at_upper_bound ? Status::slipped_off : Status::not_converged;
  return a;
}

EdgeAttempt continue_from_touch(const Whisker& w, const Scales& sc, const EdgeGeometryB& g, double s_touch,
                                const SolveOptions& options, const EdgeAttempt& failed) {
  // Translate the line (keeping its direction) so that it passes through the rest point at s_touch.
  const Eigen::Vector3d touch = w.rest_point_B(s_touch);
  Eigen::Vector3d offset = g.point - touch;
  offset -= offset.dot(g.direction) * g.direction;
  Eigen::Vector3d u(0.0, 0.0, s_touch / sc.length);
  double lambda = 0.0, step = 0.25;
  int iterations = failed.lm.iterations;
  EdgeAttempt last = failed;
  while (lambda < 1.0 && step > 1.0 / 1024.0) {
    const double next = std::min(1.0, lambda + step);
    EdgeGeometryB gi = g;
    gi.point = touch + next * offset;
    EdgeAttempt a = attempt_edge(w, sc, gi, 0.0, u, options);
    iterations += a.lm.iterations;
    if (a.status == Status::converged) {
      u = a.lm.u;
      lambda = next;
      last = a;
      step = std::min(2.0 * step, 0.5);
    } else {
      if (a.status == Status::slipped_off) last = a;
      step *= 0.5;
    }
  }
  if (lambda < 1.0) {  // a fold: no equilibrium continues the contact from first touch (snap-through)
    last.status = Status::slipped_off;
    last.folded = true;
  }
  last.lm.iterations = iterations;
  return last;
}

namespace {

/// Where `p` is seen along the line: its offset from the line in the plane normal to it.
Eigen::Vector2d seen_along(const EdgeGeometryB& g, const Eigen::Vector3d& p) {
  const Eigen::Vector3d r = p - g.point;
  return {r.dot(g.e1), r.dot(g.e2)};
}

}  // namespace

bool within_reach(const Whisker& w, const EdgeGeometryB& g) {
  // In the projection along the line, the line is a point: it is reachable if the projected rest whisker
  // gets at least as far from the projected base as that point is. Any node that does decides (from the
  // tip, which usually does): the same answer as comparing with the farthest node.
  const Eigen::Vector2d base = seen_along(g, Eigen::Vector3d::Zero());
  const double distance = base.norm();
  const auto& nodes = w.rest_nodes_B();
  return std::any_of(nodes.rbegin(), nodes.rend(), [&](const Eigen::Vector3d& p) {
    return distance <= (seen_along(g, p) - base).norm() * (1.0 + 1e-12);
  });
}

double nearest_rest_arc_length(const Whisker& w, const EdgeGeometryB& g) {
  const auto& nodes = w.rest_nodes_B();
  const auto& arc = w.node_arc_lengths();
  double best = 1e300, best_s = w.length();
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
    const Eigen::Vector2d a = seen_along(g, nodes[i]), b = seen_along(g, nodes[i + 1]);
    const Eigen::Vector2d ab = b - a;
    const double f = std::clamp(-a.dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    const double dist = (a + f * ab).norm();
    if (dist < best) {
      best = dist;
      best_s = arc[i] + f * (arc[i + 1] - arc[i]);
    }
  }
  return best_s;
}

}  // namespace vibrissa::detail
