#include "curve_fit.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "vibrissa/core/rest_curve.hpp"

namespace vibrissa::recon {

namespace {
double median_of(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}
}  // namespace

std::optional<FittedCurve> fit_curve(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& weights,
                                     int degree, int nodes) {
  const std::size_t n = points.size();
  std::size_t weighted = 0;
  for (double w : weights) weighted += w > 0.0;
  if (weighted < std::size_t(degree) + 2) return std::nullopt;
  // Chord-length parameter mapped to [-1, 1] (conditioning of the power basis).
  std::vector<double> u(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) u[i] = u[i - 1] + (points[i] - points[i - 1]).norm();
  const double chord = u.back();
  if (!(chord > 0.0)) return std::nullopt;
  for (double& v : u) v = 2.0 * v / chord - 1.0;
  const int m = degree + 1;
  Eigen::MatrixXd V(Eigen::Index(n), m);
  Eigen::MatrixXd Y(Eigen::Index(n), 3);
  for (std::size_t i = 0; i < n; ++i) {
    double p = 1.0;
    for (int k = 0; k < m; ++k, p *= u[i]) V(Eigen::Index(i), k) = p;
    Y.row(Eigen::Index(i)) = points[i].transpose();
  }
  Eigen::VectorXd robust = Eigen::VectorXd::Ones(Eigen::Index(n));
  Eigen::MatrixXd C(m, 3);
  for (int it = 0; it < 8; ++it) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(Eigen::Index(n));
    for (std::size_t i = 0; i < n; ++i) w(Eigen::Index(i)) = std::sqrt(std::max(0.0, weights[i]) * robust(Eigen::Index(i)));
    C = (w.asDiagonal() * V).colPivHouseholderQr().solve(w.asDiagonal() * Y);
    std::vector<double> r(n);
    for (std::size_t i = 0; i < n; ++i) r[i] = (V.row(Eigen::Index(i)) * C - Y.row(Eigen::Index(i))).norm();
    const double scale = 1.4826 * median_of(r);
    if (!(scale > 1e-9 * chord)) break;  // (near) exact data: nothing to reweight
    const double c = 4.685 * scale;
    for (std::size_t i = 0; i < n; ++i) {
      const double q = r[i] / c;
      robust(Eigen::Index(i)) = q < 1.0 ? (1.0 - q * q) * (1.0 - q * q) : 0.0;
    }
  }
  auto curve = [&](double t) {  // t in [0, 2]
    const double x = t - 1.0;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    double pw = 1.0;
    for (int k = 0; k < m; ++k, pw *= x) p += pw * C.row(k).transpose();
    return p;
  };
  auto derivative = [&](double t) {
    const double x = t - 1.0;
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    double pw = 1.0;
    for (int k = 1; k < m; ++k, pw *= x) d += double(k) * pw * C.row(k).transpose();
    return d;
  };
  FittedCurve out;
  out.nodes = resample_by_arc_length(curve, derivative, 2.0, nodes);
  out.tangent0 = derivative(0.0).normalized();
  for (const auto& p : out.nodes)
    if (!p.allFinite()) return std::nullopt;
  if (!out.tangent0.allFinite()) return std::nullopt;
  return out;
}

}  // namespace vibrissa::recon
