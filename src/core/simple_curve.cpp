#include "vibrissa/core/simple_curve.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "vibrissa/core/checks.hpp"

namespace vibrissa {

namespace {

// Squared distance between segments [p1, q1] and [p2, q2] (closest points by clamped parameters; Ericson,
// Real-Time Collision Detection, §5.1.9).
double segment_distance_sq(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                           const Eigen::Vector3d& q2) {
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2), denom = a * e - b * b;
  double s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return ((p1 + s * d1) - (p2 + t * d2)).squaredNorm();
}

[[noreturn]] void fail_pair(std::string_view field, std::size_t i, std::size_t j, const std::string& what) {
  invalid_input(std::string(field) + ": segments " + std::to_string(i) + " and " + std::to_string(j) +
                " (segment k joins points k and k+1) " + what + ": a whisker is a simple curve");
}

}  // namespace

void require_simple_curve(const std::vector<Eigen::Vector3d>& points, std::string_view field) {
  const std::size_t n = points.size();
  if (n < 3) return;
  const std::size_t segments = n - 1;
  double length = 0.0;
  for (std::size_t k = 0; k < segments; ++k) length += (points[k + 1] - points[k]).norm();
  // Hairpins: the turn between consecutive segments.
  for (std::size_t k = 0; k + 1 < segments; ++k) {
    const Eigen::Vector3d a = points[k + 1] - points[k], b = points[k + 2] - points[k + 1];
    const double na = a.norm(), nb = b.norm();
    if (!(na > 0.0 && nb > 0.0)) continue;  // coincident points are reported by the resampling
    const double turn = std::acos(std::clamp(a.dot(b) / (na * nb), -1.0, 1.0));
    if (turn > max_segment_turn_rad)
      fail_pair(field, k, k + 1, "turn back by " + format_value(std::round(turn * 180.0 / 3.14159265358979323846)) +
                                     " deg (more than 150 deg: a hairpin)");
  }
  // Crossings: non-adjacent segments closer than tol, swept in order of their lowest coordinate along the
  // axis of the largest extent.
  const double tol = 1e-6 * length;
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  Eigen::Index axis = 0;
  (hi - lo).maxCoeff(&axis);
  std::vector<std::size_t> order(segments);
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto low = [&](std::size_t k) { return std::min(points[k][axis], points[k + 1][axis]); };
  const auto high = [&](std::size_t k) { return std::max(points[k][axis], points[k + 1][axis]); };
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return low(x) < low(y); });
  for (std::size_t a = 0; a < segments; ++a) {
    const std::size_t i = order[a];
    for (std::size_t b = a + 1; b < segments && low(order[b]) <= high(i) + tol; ++b) {
      const std::size_t j = order[b];
      if ((i > j ? i - j : j - i) < 2 || points[i] == points[i + 1] || points[j] == points[j + 1]) continue;
      if (segment_distance_sq(points[i], points[i + 1], points[j], points[j + 1]) <= tol * tol)
        fail_pair(field, std::min(i, j), std::max(i, j), "touch or cross");
    }
  }
}

}  // namespace vibrissa
