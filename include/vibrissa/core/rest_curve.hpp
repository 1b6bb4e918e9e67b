#pragma once
// Rest-shape construction: a smooth curve resampled into N+1 nodes equally spaced in arc length, and the
// whisker-centred frame of spec §2.1 (x along emergence, x-y = best-fit plane of the proximal 70 % of arc
// length, concave toward +y, z by the right-hand rule).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

namespace vibrissa {

namespace detail {
// 5-point Gauss-Legendre on [a, b] of |dc|.
template <class Derivative>
double speed_integral(const Derivative& dc, double a, double b) {
  static constexpr double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                  0.9061798459386640};
  static constexpr double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                  0.2369268850561891, 0.2369268850561891};
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  double sum = 0.0;
  for (int i = 0; i < 5; ++i) sum += w[i] * dc(mid + half * x[i]).norm();
  return half * sum;
}
}  // namespace detail

/// Nodes at arc lengths i L / N of a parametric curve c(t), t in [0, t_end], with derivative dc(t)
/// (callables double -> Eigen::Vector3d; a template, so the ~10^4 evaluations inline instead of going
/// through std::function).
template <class Curve, class Derivative>
std::vector<Eigen::Vector3d> resample_by_arc_length(const Curve& c, const Derivative& dc, double t_end, int links,
                                                    double* total_length = nullptr) {
  const int panels = std::max(400, 40 * links);
  std::vector<double> t(static_cast<std::size_t>(panels) + 1), cum(t.size(), 0.0);
  for (int i = 0; i <= panels; ++i) t[i] = t_end * i / panels;
  for (int i = 0; i < panels; ++i) cum[i + 1] = cum[i] + detail::speed_integral(dc, t[i], t[i + 1]);
  const double length = (total_length && *total_length > 0.0) ? *total_length : cum.back();
  if (length > cum.back() * (1.0 + 1e-12)) throw std::logic_error("resample_by_arc_length: curve too short");
  if (total_length) *total_length = length;

  std::vector<Eigen::Vector3d> nodes(static_cast<std::size_t>(links) + 1);
  nodes[0] = c(0.0);
  for (int i = 1; i <= links; ++i) {
    const double s = length * i / links;
    auto it = std::upper_bound(cum.begin(), cum.end(), s);
    std::size_t p = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - cum.begin()) - 1);
    p = std::min(p, static_cast<std::size_t>(panels - 1));
    const double frac = (s - cum[p]) / std::max(cum[p + 1] - cum[p], 1e-300);
    double tt = t[p] + frac * (t[p + 1] - t[p]);
    for (int iter = 0; iter < 8; ++iter) {  // Newton on arc length within the panel
      const double f = cum[p] + detail::speed_integral(dc, t[p], tt) - s;
      const double speed = dc(tt).norm();
      if (speed <= 0.0) break;
      const double step = f / speed;
      tt -= step;
      if (std::abs(step) < 1e-15 * std::max(1.0, std::abs(tt))) break;
    }
    nodes[static_cast<std::size_t>(i)] = c(tt);
  }
  return nodes;
}

/// Nodes (N+1) of the clamped cubic spline (end slopes from 4-point interpolation) through `points` (chord-length parametrised), equally spaced in
/// arc length; `tangent0` receives the unit tangent of the spline at the base.
std::vector<Eigen::Vector3d> resample_points(const std::vector<Eigen::Vector3d>& points, int links,
                                             Eigen::Vector3d* tangent0 = nullptr);

/// Planar curve y = A x^3 + B x^2 of arc length `length`, N+1 nodes in its own frame.
std::vector<Eigen::Vector3d> planar_polynomial_nodes(double length, double A, double B, int links);

/// R whose columns are the whisker-frame axes (x, y, z) expressed in the frame of `nodes`, for nodes that
/// start at the base; `tangent0` is the emergence direction.
Eigen::Matrix3d whisker_frame(const std::vector<Eigen::Vector3d>& nodes, const Eigen::Vector3d& tangent0);

}  // namespace vibrissa
