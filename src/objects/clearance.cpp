#include "vibrissa/objects/clearance.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

namespace vibrissa {

namespace {

struct NodeGap {
  double lower = -std::numeric_limits<double>::infinity();  // a lower bound of the gap
  bool exact = false;
  double gap = 0.0;
  SurfacePoint surface;
};

}  // namespace

LinkGap link_minimum(const PlacedShape& object, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r_a,
                     double r_b, const SurfacePoint& q_a, const SurfacePoint& q_b, double stop_below) {
  LinkGap best{0.0, q_a.signed_distance - r_a, q_a};
  if (const double gap_b = q_b.signed_distance - r_b; gap_b < best.gap) best = {1.0, gap_b, q_b};
  if (best.gap < stop_below) return best;
  const Eigen::Vector3d ab = b - a;
  const double dr = r_b - r_a;
  // d gap / d tau = n . (b - a) - (r_b - r_a): a minimum inside needs it to change sign.
  auto derivative = [&](const Eigen::Vector3d& normal) { return normal.dot(ab) - dr; };
  double lo = 0.0, hi = 1.0;
  double d_lo = derivative(q_a.normal), d_hi = derivative(q_b.normal);
  if (!(d_lo < 0.0 && d_hi > 0.0)) return best;  // the link's minimum is at an end
  for (int it = 0; it < 60 && hi - lo > 1e-13; ++it) {
    // Regula falsi on the derivative, bisecting when it stalls.
    double tau = lo - d_lo * (hi - lo) / (d_hi - d_lo);
    if (!(tau > lo + 0.01 * (hi - lo) && tau < hi - 0.01 * (hi - lo))) tau = 0.5 * (lo + hi);
    const SurfacePoint q = object.nearest_W(a + tau * ab);
    const double gap = q.signed_distance - (r_a + tau * dr);
    if (gap < best.gap) best = {tau, gap, q};
    if (gap < stop_below) return best;
    const double d = derivative(q.normal);
    if (d < 0.0) {
      lo = tau;
      d_lo = d;
    } else {
      hi = tau;
      d_hi = d;
    }
    if (std::abs(d) * (hi - lo) < 1e-15) break;
  }
  return best;
}

Clearance clearance(const PlacedShape& object, std::span<const Eigen::Vector3d> nodes, std::span<const double> arc,
                    std::span<const double> radii, double threshold, bool first_below) {
  const std::size_t n = nodes.size();
  Clearance best;
  if (n == 0) return best;
  auto radius = [&](std::size_t i) { return radii.empty() ? 0.0 : radii[i]; };
  // Lipschitz constant of the gap per unit arc length: 1 (signed distance) + the taper's slope.
  double slope = 0.0, longest = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double l = std::max(arc[i + 1] - arc[i], 1e-300);
    slope = std::max(slope, std::abs(radius(i + 1) - radius(i)) / l);
    longest = std::max(longest, (nodes[i + 1] - nodes[i]).norm());
  }
  const double K = 1.0 + slope;
  thread_local std::vector<NodeGap> g;
  g.assign(n, NodeGap{});
  auto evaluate = [&](std::size_t i) {
    if (g[i].exact) return;
    const SurfacePoint q = object.nearest_W(nodes[i]);
    g[i].exact = true;
    g[i].gap = g[i].lower = q.signed_distance - radius(i);
    g[i].surface = q;
    if (g[i].gap < best.gap) best = {g[i].gap, arc[i], nodes[i], q.normal};
  };
  // The shape's box (none for unbounded shapes: a distance of 0 to it, as Bounds::distance gives).
  const Bounds box = object.shape->bounds();
  const bool bounded = box.lower.array().isFinite().any() || box.upper.array().isFinite().any();
  // Sphere tracing along the nodes: a node is queried only if its bound (from the shape's box and the last
  // queried node) lets a neighbouring link come below the threshold.
  double last_gap = -std::numeric_limits<double>::infinity();  // no node queried yet: no bound from it
  double last_arc = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double from_box = (bounded ? box.distance(object.X_WO.to_object(nodes[i])) : 0.0) - radius(i);
    const double from_last = last_gap - K * (arc[i] - last_arc);
    g[i].lower = std::max(from_box, from_last);
    if (!(g[i].lower >= threshold + K * longest)) {  // (an infinite threshold: every node)
      evaluate(i);
      if (first_below && g[i].gap < threshold) return best;
      last_gap = g[i].gap;
      last_arc = arc[i];
    }
  }
  // Each link that may come below the threshold: the minimum of the gap along it. The lower bound: a link's
  // gap is at least the mean of its ends' (bounds) less K l / 2.
  double bound = n == 1 ? g[0].lower : std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double l = arc[i + 1] - arc[i];
    if (0.5 * (g[i].lower + g[i + 1].lower - K * l) >= threshold && std::isfinite(threshold)) {
      bound = std::min(bound, 0.5 * (g[i].lower + g[i + 1].lower - K * l));
      continue;
    }
    evaluate(i);
    evaluate(i + 1);
    if (first_below && best.gap < threshold) return best;
    bound = std::min(bound, 0.5 * (g[i].gap + g[i + 1].gap - K * l));
    const LinkGap m = link_minimum(object, nodes[i], nodes[i + 1], radius(i), radius(i + 1), g[i].surface,
                                   g[i + 1].surface, first_below ? threshold : -std::numeric_limits<double>::infinity());
    if (m.gap < best.gap)
      best = {m.gap, arc[i] + m.tau * l, nodes[i] + m.tau * (nodes[i + 1] - nodes[i]), m.surface.normal};
    if (first_below && best.gap < threshold) return best;
  }
  if (best.gap >= threshold) best.gap = std::max(best.gap, threshold);
  best.lower_bound = std::min(bound, best.gap);
  return best;
}

}  // namespace vibrissa
