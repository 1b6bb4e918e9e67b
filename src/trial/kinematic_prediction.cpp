#include "vibrissa/trial/kinematic_prediction.hpp"

#include <cmath>
#include <stdexcept>

namespace vibrissa::trial {

Eigen::Vector3d front_view_direction(const Edge& edge, const Eigen::Vector3d& base_W) {
  const Eigen::Vector3d d = edge.direction.normalized();
  Eigen::Vector3d r = edge.point - base_W;
  r -= r.dot(d) * d;
  if (!(r.norm() > 0.0)) throw std::invalid_argument("front_view_direction: the base lies on the edge line");
  return d.cross(r).normalized();
}

double kinematic_contact_height(const Whisker& w, const Placement& X, const Edge& edge, const Eigen::Vector3d& view_W) {
  const Eigen::Vector3d d = edge.direction.normalized();
  Eigen::Vector3d v = view_W - view_W.dot(d) * d;
  if (!(v.norm() > 0.0)) return std::nan("");
  v.normalize();
  const Eigen::Vector3d u = v.cross(d);  // in-plane horizontal axis; the peg projects to a = 0
  const auto& nodes = w.rest_nodes_B();
  double a_prev = 0.0, z_prev = 0.0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Vector3d r = X.to_world(nodes[i]) - edge.point;
    const double a = r.dot(u), z = r.dot(d);
    if (i > 0 && ((a_prev <= 0.0 && a >= 0.0) || (a_prev >= 0.0 && a <= 0.0)) && a != a_prev) {
      const double t = a_prev / (a_prev - a);
      return z_prev + t * (z - z_prev);
    }
    a_prev = a;
    z_prev = z;
  }
  return std::nan("");
}

}  // namespace vibrissa::trial
