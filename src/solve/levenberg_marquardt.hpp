#pragma once
// Levenberg-Marquardt over three unknowns: the square 3x3 systems of every contact solve, and (for the
// base-wrench inverse) M x 3 least squares. The residual is a generic functor evaluated on Dual<3>, returning
// std::array<Dual<3>, M> (its residual and exact Jacobian in one pass) and on doubles (the residual alone,
// for trial points).
// Pure Newton (Gauss-Newton when M != 3: minimum-norm least-squares) steps are tried first (quadratic
// convergence near the root); damping grows only when a step fails to reduce the residual, which globalises
// the method for thin, compliant tips. When M != 3 a fit also converges at a stationary point of the squares
// (|J^T r| <= tolerance * max|J|), since an over-determined fit need not reach zero residual.
// A trial point is evaluated with its Jacobian when the step is likely to be accepted short of the tolerance
// (speculation_margin), so an accepted step costs one walk; the results depend on it in their last bits at most.
// A warm start may begin from an estimated Jacobian (JacobianEstimates: the one the previous frame's solve left
// with its state): its first step is then a chord step whose Jacobian costs no walk. It is kept only if it shrinks the
// residual as a Newton step near the root does (estimate_contraction); otherwise it is taken again from the
// exact Jacobian, so a wrong estimate costs one walk, damping grows only on exact Jacobians, and every later
// Jacobian is evaluated.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>
#include <type_traits>

#include <Eigen/Dense>

#include "vibrissa/core/dual.hpp"

namespace vibrissa::detail {

struct LMResult {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  double cost = 0.0;      ///< squared 2-norm of the scaled residual
  double residual = 0.0;  ///< max-norm of the scaled residual
  int iterations = 0;
  bool converged = false;
  bool at_upper_bound = false;  ///< the bounded unknown ended on its upper bound
};

struct LMBounds {
  Eigen::Vector3d lower = Eigen::Vector3d::Constant(-1e300);
  Eigen::Vector3d upper = Eigen::Vector3d::Constant(1e300);
};

/// Speculative Jacobians: a pure Newton trial point of a square system is evaluated with its Jacobian (instead
/// of its value alone, then the Jacobian if accepted) when the residual there is predicted to stay above this
/// many tolerances, so that an accepted step needs no second walk. The prediction is Newton's quadratic model,
/// r_next = r^3 / r_previous^2 (r^2 for the first step), in the max-norm of the scaled residual. A Jacobian
/// evaluation's values agree with the forward evaluation's to rounding (core/chain_jacobian.hpp), so what is
/// speculated changes the cost, and a result in its last bits at most (a converged point's outputs come from
/// whichever evaluation it had): a wrong guess costs the Jacobian's extra work (a rejected or converged trial).
inline constexpr double speculation_margin = 1e3;

/// Whether the Jacobian a residual's evaluations served last is an estimate, and how to drop it
/// (ContactEvaluations: the Jacobian a warm start's state carries).
class JacobianEstimates {
 public:
  [[nodiscard]] virtual bool estimated() const = 0;
  /// Drops an estimate: the next Jacobian evaluation is exact.
  virtual void forget_estimate() = 0;

 protected:
  JacobianEstimates() = default;
  JacobianEstimates(const JacobianEstimates&) = default;
  JacobianEstimates& operator=(const JacobianEstimates&) = default;
  ~JacobianEstimates() = default;
};

/// A step from an estimated Jacobian is kept only if it shrinks the max-norm of the residual at least this many
/// times (Newton's steps from the previous frame's solution shrink it 50 times and more on the benchmark cases).
inline constexpr double estimate_contraction = 0.1;

/// Number of residuals of a functor (the size of the array it returns).
template <class Residual>
inline constexpr int residual_count =
    static_cast<int>(std::tuple_size_v<std::invoke_result_t<Residual&, const std::array<Dual<3>, 3>&>>);

template <class Residual, int M>
void evaluate_with_jacobian(Residual& f, const Eigen::Vector3d& u, Eigen::Matrix<double, M, 1>& r,
                            Eigen::Matrix<double, M, 3>& J) {
  using D = Dual<3>;
  const std::array<D, 3> x = {D::variable(u[0], 0), D::variable(u[1], 1), D::variable(u[2], 2)};
  const std::array<D, M> y = f(x);
  for (int i = 0; i < M; ++i) {
    r[i] = y[static_cast<std::size_t>(i)].v;
    for (int j = 0; j < 3; ++j) J(i, j) = y[static_cast<std::size_t>(i)].d[static_cast<std::size_t>(j)];
  }
}

/// The residual alone (doubles: one forward evaluation, no Jacobian), for trial points.
template <class Residual, int M>
void evaluate(Residual& f, const Eigen::Vector3d& u, Eigen::Matrix<double, M, 1>& r) {
  const std::array<double, M> y = f(std::array<double, 3>{u[0], u[1], u[2]});
  for (int i = 0; i < M; ++i) r[i] = y[static_cast<std::size_t>(i)];
}

template <class Residual>
LMResult levenberg_marquardt(Residual&& f, Eigen::Vector3d u, const LMBounds& bounds, double tolerance,
                             int max_iterations, JacobianEstimates* estimates = nullptr) {
  constexpr int M = residual_count<std::remove_reference_t<Residual>>;
  using Vec = Eigen::Matrix<double, M, 1>;
  using Jac = Eigen::Matrix<double, M, 3>;
  // Converged: the residual is within tolerance, or (least squares) the gradient of the squares vanishes
  // except for components held by an active bound.
  auto done = [tolerance, &bounds](const Eigen::Vector3d& u_, const Vec& r_, const Jac& J_) {
    if (r_.cwiseAbs().maxCoeff() <= tolerance) return true;
    if constexpr (M == 3) {
      (void)bounds;  // square systems converge on the residual alone
      (void)u_;
      (void)J_;
      return false;
    } else {
      Eigen::Vector3d g_ = J_.transpose() * r_;
      for (int i = 0; i < 3; ++i)
        if ((u_[i] <= bounds.lower[i] && g_[i] > 0.0) || (u_[i] >= bounds.upper[i] && g_[i] < 0.0)) g_[i] = 0.0;
      return g_.cwiseAbs().maxCoeff() <= tolerance * std::max(J_.cwiseAbs().maxCoeff(), 1e-300);
    }
  };
  LMResult out;
  u = u.cwiseMax(bounds.lower).cwiseMin(bounds.upper);
  Vec r;
  Jac J;
  evaluate_with_jacobian(f, u, r, J);
  bool J_estimated = M == 3 && estimates && estimates->estimated();  // a fit's convergence test needs an exact J
  if (!r.allFinite()) return out;
  double cost = r.squaredNorm();
  double lambda = 0.0;
  double previous_r_max = 0.0;  // max-norm of the residual at the last accepted point (0: none yet)
  int it = 0;
  for (; it < max_iterations; ++it) {
    if (done(u, r, J)) {
      out.converged = true;
      break;
    }
    Eigen::Matrix3d A = J.transpose() * J;
    Eigen::Vector3d g = J.transpose() * r;
    double scale = std::max(A.diagonal().maxCoeff(), 1e-300);
    // A failed step from an estimated Jacobian: the exact one at u instead (true), or damping as usual.
    auto exact_instead = [&] {
      if (!J_estimated) return false;
      estimates->forget_estimate();
      evaluate_with_jacobian(f, u, r, J);
      J_estimated = false;
      A = J.transpose() * J;
      g = J.transpose() * r;
      scale = std::max(A.diagonal().maxCoeff(), 1e-300);
      return true;
    };
    bool accepted = false;
    for (int attempt = 0; attempt < 30 && !accepted; ++attempt) {
      Eigen::Vector3d step;
      if (lambda == 0.0) {
        if constexpr (M == 3) step = -J.partialPivLu().solve(r);
        else step = -Eigen::MatrixXd(J).completeOrthogonalDecomposition().solve(Eigen::VectorXd(r));
      } else {
        Eigen::Matrix3d A_damped = A;
        A_damped.diagonal() += lambda * (A.diagonal().cwiseMax(1e-12 * scale));
        step = -A_damped.ldlt().solve(g);
      }
      if (!step.allFinite()) {
        if (exact_instead()) --attempt;
        else lambda = lambda == 0.0 ? 1e-6 * scale : lambda * 10.0;
        continue;
      }
      const Eigen::Vector3d u_new = (u + step).cwiseMax(bounds.lower).cwiseMin(bounds.upper);
      // Trial points cost one forward evaluation; the Jacobian is formed only where a step is accepted and
      // the residual is not yet within tolerance (a square system's converged point needs none), at once with
      // the value where that is predicted (speculation_margin).
      Vec r_new;
      Jac J_new;
      const double r_now = r.cwiseAbs().maxCoeff();
      const double predicted = previous_r_max > 0.0 ? r_now * (r_now / previous_r_max) * (r_now / previous_r_max)
                                                    : r_now * r_now;
      const bool speculate = M == 3 && lambda == 0.0 && predicted > speculation_margin * tolerance;
      if (speculate) evaluate_with_jacobian(f, u_new, r_new, J_new);
      else evaluate(f, u_new, r_new);
      const double cost_new = r_new.squaredNorm();
      const double r_new_max = r_new.cwiseAbs().maxCoeff();
      const bool keep = !J_estimated || r_new_max <= estimate_contraction * r_now || r_new_max <= tolerance;
      if (r_new.allFinite() && cost_new < cost && keep) {
        const bool tiny = (u_new - u).cwiseAbs().maxCoeff() <= 1e-16 * std::max(1.0, u.cwiseAbs().maxCoeff());
        u = u_new;
        if (speculate) J = J_new;
        else if (M != 3 || r_new_max > tolerance) evaluate_with_jacobian(f, u, r_new, J);
        J_estimated = false;
        previous_r_max = r_now;
        r = r_new;
        cost = r.squaredNorm();
        accepted = true;
        lambda = lambda < 1e-9 * scale ? 0.0 : lambda / 10.0;
        if (tiny) break;
      } else if (exact_instead()) {
        --attempt;  // the same step, from the exact Jacobian (same damping)
      } else {
        lambda = lambda == 0.0 ? 1e-6 * scale : lambda * 10.0;
      }
    }
    if (!accepted) break;  // stalled: no descent direction reduces the residual
  }
  out.u = u;
  out.residual = r.cwiseAbs().maxCoeff();
  out.cost = cost;
  out.converged = out.converged || done(u, r, J);
  out.iterations = it;
  out.at_upper_bound = (u.array() >= bounds.upper.array() - 1e-12).any();
  return out;
}

/// Continuation in a load factor lambda from 0 to 1: `solve_at(lambda, u, first)` solves the problem at
/// lambda from u (`first`: no converged step yet, u is the given start). The step doubles after a success
/// (up to 1/4) and halves after a failure, giving up below `min_step`. Returns the last converged result
/// (cost +inf if none) with `converged` only if lambda reached 1, and the iterations of every attempt.
template <class SolveAt>
LMResult load_continuation(SolveAt&& solve_at, Eigen::Vector3d u, double min_step) {
  LMResult last;
  last.u = u;
  last.cost = std::numeric_limits<double>::infinity();
  int iterations = 0;
  double lambda = 0.0, step = 0.125;
  while (lambda < 1.0 && step >= min_step) {
    const double next = std::min(1.0, lambda + step);
    const LMResult a = solve_at(next, u, lambda == 0.0);
    iterations += a.iterations;
    if (a.converged) {
      u = a.u;
      lambda = next;
      last = a;
      step = std::min(2.0 * step, 0.25);
    } else {
      step *= 0.5;
    }
  }
  last.converged = last.converged && lambda >= 1.0;
  last.iterations = iterations;
  return last;
}

}  // namespace vibrissa::detail
