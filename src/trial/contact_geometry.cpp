#include "vibrissa/trial/contact_geometry.hpp"

#include <algorithm>
#include <limits>

namespace vibrissa::trial {

double height_along_edge(const Edge& edge, const Eigen::Vector3d& p_W) {
  return (p_W - edge.point).dot(edge.direction.normalized());
}

NearestOnWhisker nearest_rest_point(const Whisker& w, const Edge& edge) {
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
    const Eigen::Vector3d a = w.to_world(nodes[i]), b = w.to_world(nodes[i + 1]);
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

Eigen::Vector3d approach_direction(const Whisker& before, const Whisker& after, double s, const Edge& edge) {
  const Eigen::Vector3d d = edge.direction.normalized();
  Eigen::Vector3d v = after.rest_point_W(s) - before.rest_point_W(s);
  v -= v.dot(d) * d;
  const double n = v.norm();
  return n > 0.0 ? Eigen::Vector3d(v / n) : Eigen::Vector3d::Zero();
}

}  // namespace vibrissa::trial
