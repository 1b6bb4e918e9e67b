#pragma once
// Newton's method with a backtracking line search, for the object modes' 3x3 systems (object_problem.cpp).
// Their residuals are smooth only piecewise on a scale the object sets: across the rounded edges and corners
// of a mesh or a box (the offset surface at the whisker's radius) the normal turns over a band a few radii wide.
// A Newton step from a face overshoots such a band; halving it lands in the band, from where Newton converges
// quadratically. (Levenberg-Marquardt's damping turns the step toward the gradient instead and then crawls
// across the band.) Where no halving of the Newton step reduces the residual, damped steps are tried as in
// levenberg_marquardt(), from which the evaluation helpers and the result come. Along a crease's band (a mesh's)
// the Newton step fails iteration after iteration and the damped steps crawl: there each iteration starts its
// damping from a tenth of the last accepted one instead of from 1e-6 (each trial costs a walk and queries), and
// 32 such iterations in a row count as a stall. (Fewer halvings there would save more, but change where some
// crease contacts end: measured, docs/performance.md.)
#include "levenberg_marquardt.hpp"

namespace vibrissa::detail {

/// Consecutive iterations that need a damped step before the search counts as stalled: it is then crawling along
/// a crease's band (docs/objects.md, "Speed").
inline constexpr int max_crawl = 32;

/// A step that shrinks the max-norm of the residual this many times is near the root: the next step is a chord
/// step from the same Jacobian instead of one formed at the new point (a walk with derivatives saved).
inline constexpr double chord_contraction = 1e-3;

/// `estimates`: the first Jacobian may be an estimate (a warm start's record, object_problem.hpp). A full Newton
/// step from an estimate, or from the Jacobian of the last point (a chord step: where the last step shrank the
/// residual chord_contraction times, the Jacobian at the new point is not formed), is kept only if it shrinks the
/// residual as a Newton step near the root does (estimate_contraction, levenberg_marquardt.hpp) or converges;
/// else it is taken again from the exact Jacobian (one walk more).
template <class Residual>
LMResult newton_line_search(Residual&& f, Eigen::Vector3d u, const LMBounds& bounds, double tolerance,
                            int max_iterations, JacobianEstimates* estimates = nullptr) {
  using Vec = Eigen::Matrix<double, 3, 1>;
  using Jac = Eigen::Matrix<double, 3, 3>;
  LMResult out;
  u = u.cwiseMax(bounds.lower).cwiseMin(bounds.upper);
  Vec r;
  Jac J;
  evaluate_with_jacobian(f, u, r, J);
  bool J_inexact = estimates && estimates->estimated();  // J is an estimate, or the last point's (chord)
  if (!r.allFinite()) return out;
  double cost = r.squaredNorm();
  double previous_r_max = 0.0;  // max-norm of the residual at the last accepted point (0: none yet)
  int it = 0;
  int crawl = 0;                // consecutive iterations that needed a damped step
  double damping_ratio = 0.0;   // the last accepted damping, relative to the largest diagonal of J^T J
  for (; it < max_iterations; ++it) {
    if (r.cwiseAbs().maxCoeff() <= tolerance) {
      out.converged = true;
      break;
    }
    bool accepted = false;
    // A trial point costs one forward evaluation, and the Jacobian is formed only where a step is accepted short
    // of the tolerance (a converged point needs none); a full Newton step is evaluated with its Jacobian at once
    // where Newton's quadratic model predicts the residual there to stay above the tolerance (speculation_margin,
    // levenberg_marquardt.hpp), so that an accepted step costs one walk.
    const double r_now = r.cwiseAbs().maxCoeff();
    const double predicted = previous_r_max > 0.0 ? r_now * (r_now / previous_r_max) * (r_now / previous_r_max)
                                                  : r_now * r_now;
    // (not where the model predicts a step that shrinks the residual chord_contraction times: then the Jacobian
    // at the new point is not needed)
    const bool speculative = predicted > speculation_margin * tolerance &&
                             (previous_r_max == 0.0 || predicted > chord_contraction * r_now);
    auto try_step = [&](const Eigen::Vector3d& step, bool speculate) {
      if (!step.allFinite()) return false;
      const Eigen::Vector3d u_new = (u + step).cwiseMax(bounds.lower).cwiseMin(bounds.upper);
      Vec r_new;
      Jac J_new;
      if (speculate) evaluate_with_jacobian(f, u_new, r_new, J_new);
      else evaluate(f, u_new, r_new);
      const double cost_new = r_new.squaredNorm();
      const double r_new_max = r_new.cwiseAbs().maxCoeff();
      if (!r_new.allFinite() || !(cost_new < cost)) return false;
      if (J_inexact && !(r_new_max <= std::max(estimate_contraction * r_now, tolerance))) return false;
      u = u_new;
      r = r_new;
      cost = cost_new;
      previous_r_max = r_now;
      J_inexact = false;
      if (speculate) J = J_new;
      else if (r_new_max <= chord_contraction * r_now) J_inexact = r_new_max > tolerance;  // chord step next
      else if (r_new_max > tolerance) evaluate_with_jacobian(f, u, r, J);
      return true;
    };
    Eigen::Vector3d newton = -J.partialPivLu().solve(r);
    if (J_inexact) {  // the full step from the estimate or the last point's Jacobian, else from the exact one
      accepted = try_step(newton, speculative);
      if (!accepted) {
        if (estimates && estimates->estimated()) estimates->forget_estimate();
        evaluate_with_jacobian(f, u, r, J);
        J_inexact = false;
        newton = -J.partialPivLu().solve(r);
      }
    }
    double t = 1.0;
    for (int halving = 0; halving < 12 && !accepted; ++halving, t *= 0.5)
      accepted = try_step(t * newton, halving == 0 && speculative);
    if (accepted) {
      crawl = 0;
    } else {  // damped steps, as levenberg_marquardt(), from a tenth of the last damping that was accepted
      const Eigen::Matrix3d A = J.transpose() * J;
      const Eigen::Vector3d g = J.transpose() * r;
      const double scale = std::max(A.diagonal().maxCoeff(), 1e-300);
      const double first = crawl > 0 ? std::max(1e-6, 0.1 * damping_ratio) : 1e-6;
      for (double ratio = first; ratio < 1e12 && !accepted; ratio *= 10.0) {
        Eigen::Matrix3d damped = A;
        damped.diagonal() += ratio * scale * A.diagonal().cwiseMax(1e-12 * scale);
        accepted = try_step(-damped.ldlt().solve(g), false);
        if (accepted) damping_ratio = ratio;
      }
      if (accepted) ++crawl;
      if (crawl > max_crawl) break;  // crawling along a crease: stalled
    }
    if (!accepted) break;  // stalled
  }
  out.u = u;
  out.residual = r.cwiseAbs().maxCoeff();
  out.cost = cost;
  out.converged = out.converged || out.residual <= tolerance;
  out.iterations = it;
  out.at_upper_bound = (u.array() >= bounds.upper.array() - 1e-12).any();
  return out;
}

}  // namespace vibrissa::detail
