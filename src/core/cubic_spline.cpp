#include "vibrissa/core/cubic_spline.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace vibrissa {

std::vector<double> solve_tridiagonal(const std::vector<double>& lower, std::vector<double> diag,
                                      const std::vector<double>& upper, std::vector<double> rhs) {
  const std::size_t n = diag.size();
  for (std::size_t i = 1; i < n; ++i) {
    const double f = lower[i] / diag[i - 1];
    diag[i] -= f * upper[i - 1];
    rhs[i] -= f * rhs[i - 1];
  }
  std::vector<double> x(n);
  x[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) x[i] = (rhs[i] - upper[i] * x[i + 1]) / diag[i];
  return x;
}

CubicSpline CubicSpline::not_a_knot(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 2 || y.size() != n)
    throw std::invalid_argument("spline needs at least 2 knots and one value per knot, got " + std::to_string(n) +
                                " knots and " + std::to_string(y.size()) + " values");
  std::vector<double> h(n - 1), slope(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = x[i + 1] - x[i];
    if (!(h[i] > 0.0)) throw std::invalid_argument("spline knots must increase, knot " + std::to_string(i + 1));
    slope[i] = (y[i + 1] - y[i]) / h[i];
  }
  // First derivatives m_i at the knots.
  std::vector<double> m(n);
  if (n == 2) {
    m[0] = m[1] = slope[0];
  } else if (n == 3) {  // the parabola through the three points
    const double c = (slope[1] - slope[0]) / (x[2] - x[0]);
    m[0] = slope[0] - c * h[0];
    m[1] = slope[0] + c * h[0];
    m[2] = slope[1] + c * h[1];
  } else {
    // Tridiagonal system: C2 continuity at interior knots, third-derivative continuity across the second
    // and the second-to-last knots (not-a-knot).
    std::vector<double> lo(n, 0.0), di(n), up(n, 0.0), r(n);
    const double x31 = x[2] - x[0], xn = x[n - 1] - x[n - 3];
    di[0] = h[1];
    up[0] = x31;
    r[0] = ((h[0] + 2.0 * x31) * h[1] * slope[0] + h[0] * h[0] * slope[1]) / x31;
    for (std::size_t i = 1; i + 1 < n; ++i) {
      lo[i] = h[i];
      di[i] = 2.0 * (h[i - 1] + h[i]);
      up[i] = h[i - 1];
      r[i] = 3.0 * (h[i] * slope[i - 1] + h[i - 1] * slope[i]);
    }
    lo[n - 1] = xn;
    di[n - 1] = h[n - 3];
    r[n - 1] = (h[n - 2] * h[n - 2] * slope[n - 3] + (2.0 * xn + h[n - 2]) * h[n - 3] * slope[n - 2]) / xn;
    m = solve_tridiagonal(lo, std::move(di), up, std::move(r));
  }
  CubicSpline s;
  s.x_ = x;
  s.a_.assign(y.begin(), y.end() - 1);
  s.b_.assign(m.begin(), m.end() - 1);
  s.c_.resize(n - 1);
  s.d_.resize(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    s.c_[i] = (3.0 * slope[i] - 2.0 * m[i] - m[i + 1]) / h[i];
    s.d_[i] = (m[i] + m[i + 1] - 2.0 * slope[i]) / (h[i] * h[i]);
  }
  return s;
}

}  // namespace vibrissa
