#pragma once
// Rest-shape construction: a smooth curve resampled into N+1 nodes equally spaced in arc length, and the
// whisker-centred frame of spec §2.1 (x along emergence, x-y = best-fit plane of the proximal 70 % of arc
// length, concave toward +y, z by the right-hand rule).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
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

/// Nodes (N+1) on a parametric curve c(t) (derivative dc), the first at c(0), joined by N chords of equal length
/// (docs/conventions.md, "Discretisation"). Each node is the first point past the previous one at the chord's
/// distance (bracketed by arc length, then safeguarded Newton).
/// - With `length`: chords of `length` / N, so the polyline is `length` long (to round-off, ~1e-15 relative).
///   The curve may be evaluated past t_end (its natural continuation): the last node lies a little beyond arc
///   length `length` of the curve, by about length * (kappa l)^2 / 24 for curvature kappa and chord l.
/// - Without: the chord for which the last node is c(t_end) (secant iteration), so the tip is the curve's end.
template <class Curve, class Derivative>
std::vector<Eigen::Vector3d> equal_chord_nodes(const Curve& c, const Derivative& dc, double t_end,
                                               std::optional<double> length, int links) {
  // Arc-length table of the curve over [0, t_end], used to bracket each node.
  const int panels = std::max(400, 40 * links);
  std::vector<double> t(static_cast<std::size_t>(panels) + 1), cum(t.size(), 0.0);
  for (int i = 0; i <= panels; ++i) t[static_cast<std::size_t>(i)] = t_end * i / panels;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) cum[i + 1] = cum[i] + detail::speed_integral(dc, t[i], t[i + 1]);
  // Arc length of c from 0 to tt (tt >= 0; past t_end by the continuation).
  auto arc_at = [&](double tt) {
    if (tt >= t_end) return cum.back() + detail::speed_integral(dc, t_end, tt);
    auto it = std::upper_bound(t.begin(), t.end(), tt);
    const std::size_t p = std::min(static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - t.begin()) - 1),
                                   static_cast<std::size_t>(panels - 1));
    return cum[p] + detail::speed_integral(dc, t[p], tt);
  };
  // Parameter at arc length s (an estimate, to bracket): table inverse, then the end speed past t_end.
  auto t_at = [&](double s) {
    if (s >= cum.back()) {
      const double v = dc(t_end).norm();
      return t_end + (v > 0.0 ? (s - cum.back()) / v : 0.0);
    }
    auto it = std::upper_bound(cum.begin(), cum.end(), s);
    const std::size_t p = std::min(static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - cum.begin()) - 1),
                                   static_cast<std::size_t>(panels - 1));
    const double frac = (s - cum[p]) / std::max(cum[p + 1] - cum[p], 1e-300);
    return t[p] + frac * (t[p + 1] - t[p]);
  };
  // Walk N chords of length `chord` from c(0); returns the parameter of the last node.
  std::vector<Eigen::Vector3d> nodes(static_cast<std::size_t>(links) + 1);
  auto march = [&](double chord) {
    nodes[0] = c(0.0);
    double t_prev = 0.0;
    for (int i = 1; i <= links; ++i) {
      const Eigen::Vector3d p = nodes[static_cast<std::size_t>(i) - 1];
      auto g = [&](double tt) { return (c(tt) - p).norm() - chord; };  // < 0 before the node, > 0 after
      const double s_prev = arc_at(t_prev);
      // A chord is never longer than its arc: at arc length chord past the previous node g <= 0; step the
      // upper end out by arc length until the chord reaches the target.
      double lo = t_prev, hi = t_at(s_prev + chord);
      if (g(hi) <= 0.0) {
        lo = std::max(lo, hi);
        double extra = 1e-3 * chord;
        bool found = false;
        for (int k = 0; k < 60 && !found; ++k, extra *= 2.0) {
          hi = t_at(s_prev + chord + extra);
          if (g(hi) > 0.0)
            found = true;
          else
            lo = std::max(lo, hi);
        }
        if (!found)
          throw std::invalid_argument("the curve never reaches chord distance " + std::to_string(chord) +
                                      " m past node " + std::to_string(i - 1));
      }
      // Safeguarded Newton on g in [lo, hi] (g(lo) <= 0 < g(hi)).
      double tt = 0.5 * (lo + hi);
      for (int iter = 0; iter < 200; ++iter) {
        const Eigen::Vector3d d = c(tt) - p;
        const double r = d.norm(), f = r - chord;
        if (f == 0.0) break;
        if (f < 0.0)
          lo = tt;
        else
          hi = tt;
        const double slope = r > 0.0 ? d.dot(dc(tt)) / r : 0.0;
        double next = slope > 0.0 ? tt - f / slope : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (next == tt ||
            hi - lo <= 2.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo), std::abs(hi)))
          break;
        tt = next;
      }
      nodes[static_cast<std::size_t>(i)] = c(tt);
      t_prev = tt;
    }
    return t_prev;
  };
  const double total = length ? *length : cum.back();
  if (!(std::isfinite(total) && total > 0.0 && links >= 1))
    throw std::invalid_argument("the curve's arc length must be positive and finite, got " + std::to_string(total) +
                                " m (" + std::to_string(links) + " links)");
  if (length) {
    march(total / links);
    return nodes;
  }
  // To the end: the arc length at the last node, minus the curve's, is smooth and increasing in the chord
  // (slope about N): secant steps from the arc length's chord.
  double l0 = total / links, h0 = arc_at(march(l0)) - total;
  double l1 = l0 * total / (total + h0), h1 = arc_at(march(l1)) - total;
  for (int iter = 0; iter < 50 && std::abs(h1) > 1e-15 * total && h1 != h0; ++iter) {
    const double l2 = l1 - h1 * (l1 - l0) / (h1 - h0);
    l0 = l1, h0 = h1;
    l1 = l2, h1 = arc_at(march(l1)) - total;
  }
  if (!(std::abs(h1) <= 1e-12 * total))
    throw std::invalid_argument("cannot cut the curve into " + std::to_string(links) + " equal chords ending at its end");
  nodes.back() = c(t_end);  // the end itself (the last chord is off by |h1| at most)
  return nodes;
}

/// Nodes (N+1) on the clamped cubic spline (end slopes from 4-point interpolation) through `points`
/// (chord-length parametrised), cut into N equal chords from the first point to the last (equal_chord_nodes
/// without a length: the tip is the last point); `tangent0` receives the unit tangent of the spline at the base.
std::vector<Eigen::Vector3d> resample_points(const std::vector<Eigen::Vector3d>& points, int links,
                                             Eigen::Vector3d* tangent0 = nullptr);

/// Planar curve y = A x^3 + B x^2 cut into N equal chords of total length `length` (equal_chord_nodes), N+1
/// nodes in its own frame.
std::vector<Eigen::Vector3d> planar_polynomial_nodes(double length, double A, double B, int links);

/// R whose columns are the whisker-frame axes (x, y, z) expressed in the frame of `nodes`, for nodes that
/// start at the base; `tangent0` is the emergence direction.
Eigen::Matrix3d whisker_frame(const std::vector<Eigen::Vector3d>& nodes, const Eigen::Vector3d& tangent0);

}  // namespace vibrissa
