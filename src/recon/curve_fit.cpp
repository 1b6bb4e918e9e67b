#include "curve_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "vibrissa/core/rest_curve.hpp"

namespace vibrissa::recon {

namespace {

constexpr int spline_degree = 3;
/// Modified GCV: the hat-matrix trace counted twice. Plain GCV under-smooths on a few dozen points (measured
/// with scripts/validate_reconstruction.py: at 1 px, the base angles scatter twice as much).
constexpr double gcv_trace_factor = 2.0;

double median_of(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// Clamped uniform cubic B-spline on [0, 1] with `segments` intervals: the segments + 3 basis values (or
/// first derivatives) at u, by the Cox-de Boor recursion.
class CubicBasis {
 public:
  explicit CubicBasis(int segments) : segments_(segments) {
    for (int k = 0; k < spline_degree; ++k) knots_.push_back(0.0);
    for (int k = 0; k <= segments; ++k) knots_.push_back(double(k) / segments);
    for (int k = 0; k < spline_degree; ++k) knots_.push_back(1.0);
  }
  [[nodiscard]] int size() const { return segments_ + spline_degree; }
  /// Basis values (derivative = false) or their first derivatives at u in [0, 1].
  [[nodiscard]] Eigen::RowVectorXd at(double u, bool derivative) const {
    u = std::clamp(u, 0.0, 1.0);
    const int span = std::min(int(u * segments_), segments_ - 1) + spline_degree;  // knots_[span] <= u < knots_[span+1]
    // Degree-0 .. degree-(p-1) functions on this span, then the last step (values or derivatives).
    const int p = spline_degree;
    std::array<double, p + 1> N{};
    N[0] = 1.0;
    auto raise = [&](int q) {  // from degree q - 1 to q
      std::array<double, p + 1> M{};
      for (int j = 0; j < q; ++j) {
        const int i = span - q + 1 + j;  // global index of the degree-(q-1) function N[j]
        const double denom = knots_[std::size_t(i + q)] - knots_[std::size_t(i)];
        const double a = denom > 0.0 ? N[std::size_t(j)] / denom : 0.0;
        M[std::size_t(j)] += a * (knots_[std::size_t(i + q)] - u);
        M[std::size_t(j + 1)] += a * (u - knots_[std::size_t(i)]);
      }
      N = M;
    };
    for (int q = 1; q < p; ++q) raise(q);
    Eigen::RowVectorXd out = Eigen::RowVectorXd::Zero(size());
    if (!derivative) {
      raise(p);
      for (int j = 0; j <= p; ++j) out(span - p + j) = N[std::size_t(j)];
      return out;
    }
    // d/du N_{i,p} = p (N_{i,p-1} / (t_{i+p} - t_i) - N_{i+1,p-1} / (t_{i+p+1} - t_{i+1})).
    for (int j = 0; j < p; ++j) {
      const int i = span - p + 1 + j;  // global index of the degree-(p-1) function N[j]
      const double denom = knots_[std::size_t(i + p)] - knots_[std::size_t(i)];
      const double a = denom > 0.0 ? p * N[std::size_t(j)] / denom : 0.0;
      out(i - 1) -= a;
      out(i) += a;
    }
    return out;
  }

 private:
  int segments_;
  std::vector<double> knots_;
};

}  // namespace

std::optional<FittedCurve> fit_curve(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& weights,
                                     int segments, int nodes) {
  const std::size_t n = points.size();
  std::size_t weighted = 0;
  for (double w : weights) weighted += w > 0.0;
  if (segments < 1 || weighted < std::size_t(segments + spline_degree + 1)) return std::nullopt;
  // Chord-length parameter mapped to [0, 1] (then corrected to the foot points on the fitted curve).
  std::vector<double> u(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) u[i] = u[i - 1] + (points[i] - points[i - 1]).norm();
  const double chord = u.back();
  if (!(chord > 0.0)) return std::nullopt;
  for (double& v : u) v /= chord;
  const CubicBasis basis(segments);
  const int m = basis.size();
  Eigen::MatrixXd Y(Eigen::Index(n), 3);
  for (std::size_t i = 0; i < n; ++i) Y.row(Eigen::Index(i)) = points[i].transpose();
  // Penalty: the integrated squared third derivative, the integral of |c'''(u)|^2 over [0, 1] (constant on each
  // segment of a cubic spline, where the second difference of the first derivative gives it exactly), weighted
  // by lambda chosen by generalised cross-validation. Its null space is exactly the quadratics in u, toward
  // which it shrinks (an undeflected whisker is close to a parabola). Third differences of the coefficients,
  // used before, are not: at the clamped ends the coefficients of a quadratic are not equally spaced
  // (Greville abscissae 0, h/3, h, 2h, ...), so heavy smoothing bent and shifted both ends (on a 30 mm whisker
  // with 60 um noise the base lay 39 um behind the first point, its tangent tilted by -1.6 degrees).
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(m, m);
  {
    const double h = 1.0 / segments, delta = 0.25 * h;
    for (int k = 0; k < segments; ++k) {
      const double mid = (k + 0.5) * h;
      const Eigen::RowVectorXd g =
          (basis.at(mid + delta, true) - 2.0 * basis.at(mid, true) + basis.at(mid - delta, true)) / (delta * delta);
      P += h * g.transpose() * g;
    }
  }
  Eigen::MatrixXd V(Eigen::Index(n), m);
  Eigen::VectorXd robust = Eigen::VectorXd::Ones(Eigen::Index(n));
  Eigen::MatrixXd C(m, 3);
  const auto solve_gcv = [&](const Eigen::VectorXd& w) {  // w = weights (not square-rooted)
    const Eigen::MatrixXd A = V.transpose() * w.asDiagonal() * V;
    const Eigen::MatrixXd b = V.transpose() * w.asDiagonal() * Y;
    const double unit = A.trace() / std::max(P.trace(), 1e-300);
    double best = std::numeric_limits<double>::infinity();
    const double n_eff = double((w.array() > 0.0).count());
    for (int k = -10; k <= 4; ++k) {
      const Eigen::LDLT<Eigen::MatrixXd> ldlt(A + unit * std::pow(10.0, k) * P);
      const Eigen::MatrixXd Ck = ldlt.solve(b);
      if (!Ck.allFinite()) continue;
      const double rss = (w.cwiseSqrt().asDiagonal() * (V * Ck - Y)).squaredNorm();
      const double trace = ldlt.solve(A).trace();  // trace of the hat matrix
      const double dof = n_eff - gcv_trace_factor * trace;
      if (!(dof > 0.5)) continue;
      const double gcv = n_eff * rss / (dof * dof);
      if (gcv < best * (1.0 - 1e-9)) {  // ties (exact data): the least smoothing
        best = gcv;
        C = Ck;
      }
    }
    return std::isfinite(best);
  };
  for (int pass = 0; pass < 3; ++pass) {
    for (std::size_t i = 0; i < n; ++i) V.row(Eigen::Index(i)) = basis.at(u[i], false);
    robust.setOnes();
    for (int it = 0; it < 8; ++it) {
      Eigen::VectorXd w = Eigen::VectorXd::Zero(Eigen::Index(n));
      for (std::size_t i = 0; i < n; ++i) w(Eigen::Index(i)) = std::max(0.0, weights[i]) * robust(Eigen::Index(i));
      if (!solve_gcv(w)) return std::nullopt;
      std::vector<double> r(n);
      for (std::size_t i = 0; i < n; ++i) r[i] = (V.row(Eigen::Index(i)) * C - Y.row(Eigen::Index(i))).norm();
      // Residual scale, at least 0.1 % of the chord: on (near) exact data a point beyond a view's last tracked
      // point (step 2 of docs/reconstruction.md) is off by micrometres, not an outlier.
      const double scale = std::max(1.4826 * median_of(r), 1e-3 * chord);
      const double c = 4.685 * scale;
      for (std::size_t i = 0; i < n; ++i) {
        const double q = r[i] / c;
        robust(Eigen::Index(i)) = q < 1.0 ? (1.0 - q * q) * (1.0 - q * q) : 0.0;
      }
    }
    if (pass == 2) break;
    // Parameter correction: each point's parameter becomes that of its foot point on the curve (Gauss-Newton),
    // then the parameters are rescaled to [0, 1]; noisy, interleaved points of the two views make chord
    // length zig-zag.
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d d = (basis.at(u[i], true) * C).transpose();
        const Eigen::Vector3d e = (basis.at(u[i], false) * C).transpose() - points[i];
        if (!(d.squaredNorm() > 0.0)) break;
        u[i] = u[i] - e.dot(d) / d.squaredNorm();
      }
    const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
    const double u0 = *lo, span = *hi - *lo;
    if (!(span > 0.0)) return std::nullopt;
    for (double& v : u) v = (v - u0) / span;
  }
  auto curve = [&](double t) { return Eigen::Vector3d((basis.at(t, false) * C).transpose()); };
  auto derivative = [&](double t) { return Eigen::Vector3d((basis.at(t, true) * C).transpose()); };
  FittedCurve out;
  out.nodes = resample_by_arc_length(curve, derivative, 1.0, nodes);
  out.tangent0 = derivative(0.0).normalized();
  out.dense = resample_by_arc_length(curve, derivative, 1.0, dense_links);
  for (const auto& p : out.nodes)
    if (!p.allFinite()) return std::nullopt;
  if (!out.tangent0.allFinite()) return std::nullopt;
  return out;
}

}  // namespace vibrissa::recon
