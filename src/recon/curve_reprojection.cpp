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

}  // namespace vibrissa::recon
