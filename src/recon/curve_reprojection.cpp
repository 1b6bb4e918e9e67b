#include "curve_reprojection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vibrissa::recon {

std::vector<Eigen::Vector2d> project_curve(const std::vector<Eigen::Vector3d>& dense_W, const Camera& camera) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(dense_W.size());
  for (const auto& p : dense_W) out.push_back(camera.project(p));
  return out;
}

double distance_to_curve(const std::vector<Eigen::Vector2d>& curve_px, const Eigen::Vector2d& pixel) {
  if (curve_px.empty()) return std::numeric_limits<double>::quiet_NaN();
  double best = (pixel - curve_px.front()).squaredNorm();
  for (std::size_t k = 0; k + 1 < curve_px.size(); ++k) {
    const Eigen::Vector2d a = curve_px[k], u = curve_px[k + 1] - a;
    const double uu = u.squaredNorm();
    const double t = uu > 0.0 ? std::clamp((pixel - a).dot(u) / uu, 0.0, 1.0) : 0.0;
    best = std::min(best, (pixel - (a + t * u)).squaredNorm());
  }
  return std::sqrt(best);
}

double distance_across_curve(const std::vector<Eigen::Vector2d>& curve_px, const Eigen::Vector2d& pixel) {
  double best = distance_to_curve(curve_px, pixel);
  if (curve_px.size() < 2) return best;
  // Beyond an end, the distance to the end segment's line (not to the end point).
  const auto beyond = [&](const Eigen::Vector2d& end, const Eigen::Vector2d& inner) {
    const Eigen::Vector2d u = end - inner, w = pixel - end;
    const double uu = u.squaredNorm();
    if (!(uu > 0.0) || w.dot(u) <= 0.0) return;
    best = std::min(best, std::abs(u.x() * w.y() - u.y() * w.x()) / std::sqrt(uu));
  };
  beyond(curve_px.front(), curve_px[1]);
  beyond(curve_px.back(), curve_px[curve_px.size() - 2]);
  return best;
}

}  // namespace vibrissa::recon
