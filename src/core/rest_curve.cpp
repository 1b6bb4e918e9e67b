#include "vibrissa/core/rest_curve.hpp"

#include "vibrissa/core/cubic_spline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace vibrissa {
namespace {

// Clamped cubic spline through (t_i, y_i) with end slopes d0, dn: second derivatives m_i.
std::vector<double> clamped_spline_moments(const std::vector<double>& t, const std::vector<double>& y, double d0,
                                           double dn) {
  const std::size_t n = t.size();
  std::vector<double> a(n, 0.0), b(n, 0.0), c(n, 0.0), d(n, 0.0);
  const double h0 = t[1] - t[0], hn = t[n - 1] - t[n - 2];
  b[0] = 2.0 * h0;
  c[0] = h0;
  d[0] = 6.0 * ((y[1] - y[0]) / h0 - d0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double hl = t[i] - t[i - 1], hr = t[i + 1] - t[i];
    a[i] = hl;
    b[i] = 2.0 * (hl + hr);
    c[i] = hr;
    d[i] = 6.0 * ((y[i + 1] - y[i]) / hr - (y[i] - y[i - 1]) / hl);
  }
  a[n - 1] = hn;
  b[n - 1] = 2.0 * hn;
  d[n - 1] = 6.0 * (dn - (y[n - 1] - y[n - 2]) / hn);
  return solve_tridiagonal(a, std::move(b), c, std::move(d));
}

// Derivative at t[0] of the polynomial through the first (up to 4) samples: O(h^3) end slopes, so the
// spline's tangent at the base (the emergence direction, spec §2.1) is accurate.
double end_slope(const std::vector<double>& t, const std::vector<double>& y, bool at_start) {
  const std::size_t n = std::min<std::size_t>(4, t.size());
  std::vector<double> ts(n), ys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = at_start ? i : t.size() - 1 - i;
    ts[i] = t[k];
    ys[i] = y[k];
  }
  double slope = 0.0;  // derivative of the Lagrange interpolant at ts[0]
  for (std::size_t i = 0; i < n; ++i) {
    double li = 0.0;  // l_i'(ts[0])
    if (i == 0) {
      for (std::size_t j = 1; j < n; ++j) li += 1.0 / (ts[0] - ts[j]);
    } else {
      li = 1.0 / (ts[i] - ts[0]);
      for (std::size_t j = 1; j < n; ++j)
        if (j != i) li *= (ts[0] - ts[j]) / (ts[i] - ts[j]);
    }
    slope += ys[i] * li;
  }
  return slope;
}

}  // namespace

std::vector<Eigen::Vector3d> resample_points(const std::vector<Eigen::Vector3d>& points, int links,
                                             Eigen::Vector3d* tangent0) {
  const std::size_t n = points.size();
  std::vector<double> t(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const double chord = (points[i] - points[i - 1]).norm();
    if (!(chord > 0.0))
      throw std::invalid_argument("whisker.points: consecutive points " + std::to_string(i - 1) + " and " +
                                  std::to_string(i) + " coincide");
    t[i] = t[i - 1] + chord;
  }
  std::array<std::vector<double>, 3> y, m;
  for (int d = 0; d < 3; ++d) {
    y[d].resize(n);
    for (std::size_t i = 0; i < n; ++i) y[d][i] = points[i][d];
    m[d] = clamped_spline_moments(t, y[d], end_slope(t, y[d], true), end_slope(t, y[d], false));
  }
  auto interval = [&](double tt) {
    auto it = std::upper_bound(t.begin(), t.end(), tt);
    std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - t.begin()) - 1);
    return std::min(i, n - 2);
  };
  auto eval = [&](double tt) {
    const std::size_t i = interval(tt);
    const double h = t[i + 1] - t[i], A = (t[i + 1] - tt) / h, B = (tt - t[i]) / h;
    Eigen::Vector3d p;
    for (int d = 0; d < 3; ++d)
      p[d] = A * y[d][i] + B * y[d][i + 1] + ((A * A * A - A) * m[d][i] + (B * B * B - B) * m[d][i + 1]) * h * h / 6.0;
    return p;
  };
  auto deriv = [&](double tt) {
    const std::size_t i = interval(tt);
    const double h = t[i + 1] - t[i], A = (t[i + 1] - tt) / h, B = (tt - t[i]) / h;
    Eigen::Vector3d v;
    for (int d = 0; d < 3; ++d)
      v[d] = (y[d][i + 1] - y[d][i]) / h - (3 * A * A - 1) * h / 6.0 * m[d][i] + (3 * B * B - 1) * h / 6.0 * m[d][i + 1];
    return v;
  };
  if (tangent0) *tangent0 = deriv(0.0).normalized();
  try {
    return equal_chord_nodes(eval, deriv, t.back(), std::nullopt, links);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("whisker.points: ") + e.what());
  }
}

std::vector<Eigen::Vector3d> planar_polynomial_nodes(double length, double A, double B, int links) {
  auto c = [&](double x) { return Eigen::Vector3d(x, A * x * x * x + B * x * x, 0.0); };
  auto dc = [&](double x) { return Eigen::Vector3d(1.0, 3.0 * A * x * x + 2.0 * B * x, 0.0); };
  return equal_chord_nodes(c, dc, length, length, links);  // arc length >= x: x = length is past the tip
}

Eigen::Matrix3d whisker_frame(const std::vector<Eigen::Vector3d>& nodes, const Eigen::Vector3d& tangent0) {
  const Eigen::Vector3d x0 = tangent0.normalized();
  const std::size_t n = nodes.size();
  // §2.1: the x-y plane is the best-fit plane of the proximal 70 % of arc length (nodes are equally spaced).
  const std::size_t count = std::max<std::size_t>(3, static_cast<std::size_t>(std::floor(0.7 * double(n - 1))) + 1);
  Eigen::MatrixXd X(static_cast<Eigen::Index>(std::min(count, n)), 3);
  for (Eigen::Index i = 0; i < X.rows(); ++i) X.row(i) = nodes[static_cast<std::size_t>(i)].transpose();
  const Eigen::RowVector3d centroid = X.colwise().mean();
  X.rowwise() -= centroid;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(X, Eigen::ComputeThinV);
  const Eigen::Vector3d sv = svd.singularValues();
  Eigen::Vector3d normal = svd.matrixV().col(2);
  if (!(sv(1) > 1e-9 * std::max(sv(0), 1e-300))) {
    // Straight (collinear) proximal part: no plane is defined; take z as close to +z of the input frame as
    // possible (or +y if the whisker is vertical). Documented in docs/conventions.md.
    Eigen::Vector3d up = std::abs(x0.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
    normal = (up - up.dot(x0) * x0).normalized();
  }
  Eigen::Vector3d x = (x0 - x0.dot(normal) * normal).normalized();
  Eigen::Vector3d z = normal;
  Eigen::Vector3d y = z.cross(x);
  double mean_y = 0.0;
  for (const auto& p : nodes) mean_y += (p - nodes.front()).dot(y);
  if (mean_y < 0.0) {  // concave toward +y
    y = -y;
    z = -z;
  }
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = y;
  R.col(2) = z;
  return R;
}

}  // namespace vibrissa
