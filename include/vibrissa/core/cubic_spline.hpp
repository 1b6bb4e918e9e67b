#pragma once
// The interpolating cubic spline of MATLAB's spline() / interp1(..., 'spline'): not-a-knot end conditions
// (a parabola through three points, a line through two), extrapolated with the end pieces. The published
// model (spec §2.1, Elastica3D) places the nodes of its re-meshed chain and their stiffness with it, so the
// `paper` scheme evaluates the same spline. Templated evaluation runs on dual numbers (exact derivatives).
#include <algorithm>
#include <vector>

#include "vibrissa/core/dual.hpp"

namespace vibrissa {

/// Solves the tridiagonal system lower[i] x[i-1] + diag[i] x[i] + upper[i] x[i+1] = rhs[i] (Thomas
/// algorithm, no pivoting: for the diagonally dominant systems of spline fitting). Arguments are consumed.
std::vector<double> solve_tridiagonal(const std::vector<double>& lower, std::vector<double> diag,
                                      const std::vector<double>& upper, std::vector<double> rhs);

class CubicSpline {
 public:
  CubicSpline() = default;
  /// Not-a-knot spline through (x_i, y_i), x strictly increasing, at least two points.
  static CubicSpline not_a_knot(const std::vector<double>& x, const std::vector<double>& y);

  [[nodiscard]] bool empty() const { return x_.empty(); }

  /// Value at t (the piece holding t; the end pieces beyond the knots).
  template <class S>
  [[nodiscard]] S operator()(const S& t) const {
    const std::size_t i = piece(value_of(t));
    const S u = t - S(x_[i]);
    return S(a_[i]) + u * (S(b_[i]) + u * (S(c_[i]) + u * S(d_[i])));
  }

 private:
  [[nodiscard]] std::size_t piece(double t) const {
    const auto it = std::upper_bound(x_.begin(), x_.end(), t);
    const std::size_t i = it == x_.begin() ? 0 : static_cast<std::size_t>(it - x_.begin()) - 1;
    return std::min(i, x_.size() - 2);
  }
  std::vector<double> x_, a_, b_, c_, d_;  // piece i: a + b u + c u^2 + d u^3, u = t - x_i
};

}  // namespace vibrissa
