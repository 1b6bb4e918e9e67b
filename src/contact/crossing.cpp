#include "vibrissa/contact/crossing.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace vibrissa {
namespace {

struct EdgeFrame {
  Eigen::Vector3d p0, d, n1, n2;
  explicit EdgeFrame(const EdgeSegment& e) : p0(e.p0), d(e.direction), n1(e.normal), n2(e.direction.cross(e.normal)) {}
  [[nodiscard]] Eigen::Vector2d project(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d r = p - p0;
    return {r.dot(n1), r.dot(n2)};
  }
  [[nodiscard]] double along(const Eigen::Vector3d& p) const { return (p - p0).dot(d); }
};

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Signed distance of the edge's point (the origin of the projection) from the line of segment a→b,
// positive when the origin lies to the left of a→b.
double side(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d t = b - a;
  const double len = t.norm();
  if (len < 1e-15) return 0.0;
  return cross2(t, -a) / len;
}

}  // namespace

Eigen::Vector3d edge_vector_to_world(const EdgeSegment& edge, const Eigen::Vector2d& v_E) {
  return v_E.x() * edge.normal + v_E.y() * edge.direction.cross(edge.normal);
}

std::optional<Crossing> find_crossing(const std::vector<Eigen::Vector3d>& prev_W,
                                      const std::vector<Eigen::Vector3d>& now_W, const std::vector<double>& arc,
                                      const EdgeSegment& edge_prev, const EdgeSegment& edge_now,
                                      bool within_extent) {
  const EdgeFrame Ep(edge_prev), En(edge_now);
  std::optional<Crossing> best;
  const std::size_t n = now_W.size();
  Eigen::Vector2d ap = Ep.project(prev_W[0]), an = En.project(now_W[0]);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Eigen::Vector2d bp = Ep.project(prev_W[i + 1]), bn = En.project(now_W[i + 1]);
    const double f0 = side(ap, bp), f1 = side(an, bn);
    // A sign change: the edge's point passed from one side of this link's line to the other.
    if ((f0 > 0.0 && f1 <= 0.0) || (f0 < 0.0 && f1 >= 0.0)) {
      const double tau = f0 / (f0 - f1);
      if (!best || tau < best->tau) {
        const Eigen::Vector2d a = (1.0 - tau) * ap + tau * an, b = (1.0 - tau) * bp + tau * bn;
        const Eigen::Vector2d t = b - a;
        const double len2 = t.squaredNorm();
        constexpr double kJointSlack = 1e-9;  // a crossing exactly at a joint belongs to both links
        const double u_raw = len2 > 0.0 ? (-a).dot(t) / len2 : -1.0;
        if (u_raw >= -kJointSlack && u_raw <= 1.0 + kJointSlack) {
          const double u = std::clamp(u_raw, 0.0, 1.0);
          const double lambda = (1.0 - tau) * ((1.0 - u) * Ep.along(prev_W[i]) + u * Ep.along(prev_W[i + 1])) +
                                tau * ((1.0 - u) * En.along(now_W[i]) + u * En.along(now_W[i + 1]));
          if (!within_extent || edge_now.contains(lambda)) {
            Crossing c;
            c.tau = tau;
            c.arc_length = (1.0 - u) * arc[i] + u * arc[i + 1];
            c.edge_coordinate = lambda;
            // The link moved toward the side the edge's point was on: along its left normal if f0 > 0.
            const Eigen::Vector2d left = Eigen::Vector2d(-t.y(), t.x()).normalized();
            c.approach_E = f0 > 0.0 ? left : Eigen::Vector2d(-left);
            c.approach_W = edge_vector_to_world(edge_now, c.approach_E);
            best = c;
          }
        }
      }
    }
    ap = bp;
    an = bn;
  }
  return best;
}

}  // namespace vibrissa
