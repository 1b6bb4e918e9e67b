#include "vibrissa/contact/contact_geometry.hpp"

#include <cmath>

#include <algorithm>
#include <limits>

#include "vibrissa/contact/edge_segment.hpp"

namespace vibrissa {

double height_along_edge(const Edge& edge, const Eigen::Vector3d& p_W) {
  return (p_W - edge.point).dot(edge.direction.normalized());
}

NearestOnWhisker nearest_rest_point(const Whisker& w, const Placement& X, const Edge& edge) {
  const Eigen::Vector3d d = edge.direction.normalized();
  const auto& nodes = w.rest_nodes_B();
  const auto& arc = w.node_arc_lengths();
  // Distance to the line depends only on the components normal to d: minimise over each segment.
  auto perp = [&](const Eigen::Vector3d& p_W) {
    const Eigen::Vector3d r = p_W - edge.point;
    return Eigen::Vector3d(r - r.dot(d) * d);
  };
  NearestOnWhisker best;
  best.distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
    const Eigen::Vector3d a = X.to_world(nodes[i]), b = X.to_world(nodes[i + 1]);
    const Eigen::Vector3d pa = perp(a), pb = perp(b), ab = pb - pa;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp(-pa.dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double dist = (pa + t * ab).norm();
    if (dist < best.distance) {
      best.distance = dist;
      best.arc_length = arc[i] + t * (arc[i + 1] - arc[i]);
      best.on_whisker_W = a + t * (b - a);
      best.on_edge_W = edge.point + (best.on_whisker_W - edge.point).dot(d) * d;
    }
  }
  return best;
}

Eigen::Vector3d approach_direction(const Whisker& w, const Placement& before, const Placement& after, double s,
                                   const Edge& edge) {
  const Eigen::Vector3d d = edge.direction.normalized();
  const Eigen::Vector3d p_B = w.rest_point_B(s);
  Eigen::Vector3d v = after.to_world(p_B) - before.to_world(p_B);
  v -= v.dot(d) * d;
  const double n = v.norm();
  return n > 0.0 ? Eigen::Vector3d(v / n) : Eigen::Vector3d::Zero();
}

EdgeSegment infinite_segment(const Edge& edge) {
  validate(edge);
  EdgeSegment e;
  e.p0 = edge.point;
  e.direction = edge.direction.normalized();
  const Eigen::Vector3d helper = std::abs(e.direction.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  e.normal = (helper - helper.dot(e.direction) * e.direction).normalized();
  return e;
}

}  // namespace vibrissa
