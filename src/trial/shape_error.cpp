#include "vibrissa/trial/shape_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vibrissa::trial {

double distance_to_polyline(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& c) {
  if (c.empty()) return std::nan("");
  if (c.size() == 1) return (p - c[0]).norm();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < c.size(); ++i) {
    const Eigen::Vector3d ab = c[i + 1] - c[i];
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - c[i]).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (p - (c[i] + t * ab)).norm());
  }
  return best;
}

double mean_shape_error(const std::vector<Eigen::Vector3d>& sim, const std::vector<double>& arc, double s_applied,
                        const std::vector<Eigen::Vector3d>& tracked) {
  if (tracked.empty()) return std::nan("");
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < sim.size() && i < arc.size(); ++i) {
    if (arc[i] > s_applied) break;
    sum += distance_to_polyline(sim[i], tracked);
    ++count;
  }
  return count ? sum / static_cast<double>(count) : std::nan("");
}

}  // namespace vibrissa::trial
