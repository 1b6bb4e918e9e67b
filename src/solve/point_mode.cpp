// Contact-point mode (spec §2.1, "contact-point simulations"): find (F_y, F_z, s) such that the deflected
// whisker passes through the tracked point with the force normal to it there. Friction along the object is
// implicit: the tracked point fixes where the contact is.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/QR>

#include "contact_problem.hpp"
#include "solution_check.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {

namespace {

struct PointAttempt {
  detail::LMResult lm;
  Status status = Status::not_converged;
  detail::ContactEvaluations evaluations;  ///< the last kinematics evaluated (the solved point's among them)
};

PointAttempt attempt_point(const Whisker& w, const detail::Scales& sc, const Eigen::Vector3d& target_B,
                           const Eigen::Vector3d& u0, const SolveOptions& options,
                           const detail::ContactEvaluations* known = nullptr) {
  const Eigen::Vector3d t = target_B / sc.length;
  PointAttempt a;
  if (known) a.evaluations = *known;
  auto residual = [&](const auto& u) {
    using S = std::decay_t<decltype(u[0])>;
    const auto c = a.evaluations.contact_at<S>(w, sc, u);
    return std::array<S, 3>{c.p_contact_B.x / sc.length - t.x(), c.p_contact_B.y / sc.length - t.y(),
                            c.p_contact_B.z / sc.length - t.z()};
  };
  a.lm = detail::levenberg_marquardt(residual, u0, detail::contact_bounds(), options.tolerance / sc.length,
                                     options.max_iterations, &a.evaluations);
  if (a.lm.converged)
    a.status = a.lm.u[2] > 1.0 + 1e-12 ? Status::slipped_off : Status::converged;
  else
    a.status = a.lm.at_upper_bound ? Status::slipped_off : Status::not_converged;
  return a;
}

/// Damped Gauss-Newton on the two force components (scaled) with the arc length s (scaled) held fixed, from
/// `f`, toward the contact point `goal_B`, at most `iterations` steps; returns the force and the remaining gap
/// (scaled).
std::pair<Eigen::Vector2d, double> fixed_arc_length_force(const Whisker& w, const detail::Scales& sc,
                                                          const Eigen::Vector3d& goal_B, double s, Eigen::Vector2d f,
                                                          int iterations = 30) {
  using D = Dual<3>;
  auto evaluate = [&](const Eigen::Vector2d& f_, Eigen::Matrix<double, 3, 2>& J, Eigen::Vector3d& gap) {
    const std::array<D, 3> u{D::variable(f_[0], 0), D::variable(f_[1], 1), D(s)};
    const auto c = detail::contact_at<D>(w, sc, u);
    const D* p[3] = {&c.p_contact_B.x, &c.p_contact_B.y, &c.p_contact_B.z};
    for (int i = 0; i < 3; ++i) {
      gap[i] = (goal_B[i] - p[i]->v) / sc.length;
      J(i, 0) = p[i]->d[0] / sc.length;
      J(i, 1) = p[i]->d[1] / sc.length;
    }
  };
  Eigen::Matrix<double, 3, 2> J;
  Eigen::Vector3d gap;
  evaluate(f, J, gap);
  for (int it = 0; it < iterations; ++it) {
    const Eigen::Vector2d step = J.colPivHouseholderQr().solve(gap);
    double t = 1.0;
    Eigen::Matrix<double, 3, 2> J_try;
    Eigen::Vector3d gap_try;
    bool better = false;
    for (int halvings = 0; halvings < 20 && !better; ++halvings, t *= 0.5) {
      evaluate(f + t * step, J_try, gap_try);
      better = gap_try.norm() < gap.norm();
      if (better) f += t * step;
    }
    if (!better) break;
    const bool small = (gap.norm() - gap_try.norm()) < 1e-12 * (1.0 + gap.norm());
    J = J_try;
    gap = gap_try;
    if (small) break;
  }
  return {f, gap.norm()};
}

/// Unknowns at arc length s (scaled) with the force that brings the contact at s closest to the target, from
/// zero force. With `search`, if that leaves a gap, Gauss-Newton also runs a few steps from each of a grid of
/// forces (12 directions of (F_y, F_z) x magnitudes 1/2 to 16 in units of E I_0 / L^2) and then to the end
/// from the best of them: a large load (2 mN at 21 mm on a 30 mm whisker is ~7 units) is out of reach of the
/// start from zero, which stops in another minimum of the gap, and the scan would then return a neighbouring
/// root instead of the load at the hint.
Eigen::Vector3d fixed_arc_length_start(const Whisker& w, const detail::Scales& sc, const Eigen::Vector3d& target_B,
                                       double s, bool search, double tolerance) {
  auto [f, gap] = fixed_arc_length_force(w, sc, target_B, s, Eigen::Vector2d::Zero());
  if (search && gap > tolerance) {
    constexpr int screening_steps = 4;
    Eigen::Vector2d best = f;
    double best_gap = gap;
    for (int i = 0; i < 12 && best_gap > tolerance; ++i) {
      const double angle = 2.0 * std::numbers::pi * i / 12.0;
      for (double magnitude = 0.5; magnitude <= 16.0 && best_gap > tolerance; magnitude *= 2.0) {
        const Eigen::Vector2d start(magnitude * std::cos(angle), magnitude * std::sin(angle));
        const auto [g, gap_g] = fixed_arc_length_force(w, sc, target_B, s, start, screening_steps);
        if (gap_g < best_gap) std::tie(best, best_gap) = std::pair(g, gap_g);
      }
    }
    const auto [g, gap_g] = fixed_arc_length_force(w, sc, target_B, s, best);
    if (gap_g < gap) f = g;
  }
  return {f[0], f[1], s};
}

/// Scaled unknowns from which a cold solve without a hint starts: the cantilever guess toward the target
/// (detail::cantilever_start), else zero force where the rest whisker is as far from the base as the target.
Eigen::Vector3d cold_point_start(const Whisker& w, const detail::Scales& sc, const Eigen::Vector3d& target_B) {
  if (auto u = detail::cantilever_start(w, sc, target_B, Eigen::Vector3d::Zero())) return *u;
  return {0.0, 0.0, detail::arc_length_at_distance(w, target_B.norm()) / sc.length};
}

}  // namespace

Solution solve_point(const Whisker& w, const Placement& X, const Eigen::Vector3d& point_W, std::optional<double> hint,
                     const SolveOptions& options, const LoadState* warm,
                     const std::optional<Eigen::Vector3d>& edge_direction_W) {
  return detail::solve_point_from(w, X, point_W, hint, options, warm, edge_direction_W, nullptr);
}

Solution detail::solve_point_from(const Whisker& w, const Placement& X, const Eigen::Vector3d& point_W,
                                  std::optional<double> hint, const SolveOptions& options, const LoadState* warm,
                                  const std::optional<Eigen::Vector3d>& edge_direction_W,
                                  const ContactEvaluations* known) {
  validate(options);
  require_finite(point_W, "load.point");
  if (hint) require_finite(*hint, "load.arc_length_hint");
  if (edge_direction_W) {
    require_finite(*edge_direction_W, "load.edge_direction");
    require_normalizable(*edge_direction_W, "load.edge_direction");
  }
  const detail::Scales sc(w);
  const Eigen::Vector3d target_B = X.to_body(point_W);
  const double distance = target_B.norm();
  if (distance > w.length())
    return detail::unloaded_solution(w, X, Status::no_contact,
                                     "the target point lies beyond the whisker's length from the base", options);

  Eigen::Vector3d u0;
  ContactEvaluations carried;  // what the solve that produced `warm` left with it
  if (warm) {
    u0 = carried.start_at(w, sc, *warm);
    if (!known) known = &carried;
  } else if (hint) {
    u0 = Eigen::Vector3d(0.0, 0.0, std::clamp(*hint, 1e-6 * sc.length, w.length()) / sc.length);
  } else {
    u0 = cold_point_start(w, sc, target_B);
  }
  PointAttempt a = attempt_point(w, sc, target_B, u0, options, known);
  std::vector<Root> roots;
  if (!warm && (hint || options.find_other_roots)) {  // a warm frame keeps its root: no probing (issue 13)
    // Scan: start near the hint and all along the whisker, each start with the force that the linearised
    // model needs there; keep every distinct root, and with a hint the one nearest it.
    const double h = hint ? *hint / sc.length : a.lm.u[2];
    std::vector<PointAttempt> found;
    auto keep = [&](const PointAttempt& b) {
      if (b.status != Status::converged) return;
      for (const auto& f : found)
        if (std::abs(f.lm.u[2] - b.lm.u[2]) < 1e-7 && (f.lm.u.head<2>() - b.lm.u.head<2>()).norm() < 1e-7 * (1.0 + b.lm.u.head<2>().norm()))
          return;
      found.push_back(b);
    };
    keep(a);
    std::vector<double> starts = {h};
    for (double d : {0.01, 0.02, 0.05, 0.1, 0.2}) starts.insert(starts.end(), {h - d, h + d});
    for (int i = 1; i <= 10; ++i) starts.push_back(0.1 * i);
    for (std::size_t i = 0; i < starts.size(); ++i) {
      if (starts[i] <= 0.0 || starts[i] > 1.0) continue;
      const bool at_hint = hint && i == 0;  // the start that decides "the root nearest the hint"
      keep(attempt_point(w, sc, target_B,
                         fixed_arc_length_start(w, sc, target_B, starts[i], at_hint, options.tolerance / sc.length),
                         options));
    }
    if (hint && !warm)
      for (const auto& f : found)
        if (a.status != Status::converged || std::abs(f.lm.u[2] - h) < std::abs(a.lm.u[2] - h) - 1e-12) a = f;
    std::sort(found.begin(), found.end(), [](const PointAttempt& x, const PointAttempt& y) { return x.lm.u[2] < y.lm.u[2]; });
    for (const auto& f : found) {
      const LoadState st = detail::state_from_unknowns(f.lm.u, sc);
      roots.push_back({st.arc_length, std::hypot(st.force_x, std::hypot(st.force_y, st.force_z)), f.lm.residual * sc.length});
    }
  }
  if (a.status == Status::not_converged && warm) {  // a bad warm start: fall back to the rest-shape start (zero force)
    const double s0 = detail::arc_length_at_distance(w, distance);
    PointAttempt cold = attempt_point(w, sc, target_B, Eigen::Vector3d(0.0, 0.0, s0 / sc.length), options);
    cold.lm.iterations += a.lm.iterations;
    a = cold;
  }

  Solution out;
  detail::fill_solution(w, X, detail::state_from_unknowns(a.lm.u, sc), options, edge_direction_W, out, &a.evaluations);
  out.iterations = a.lm.iterations;
  out.residual = a.lm.residual * sc.length;
  switch (a.status) {
    case Status::converged: detail::set_status(out, a.status, "contact point reached"); break;
    case Status::slipped_off:
      detail::set_status(out, a.status, "reaching the point would need contact beyond the tip");
      break;
    default: detail::set_status(out, a.status, "no equilibrium through the point within the iteration limit"); break;
  }
  out.roots = std::move(roots);
  if (a.status == Status::converged && options.find_other_roots)
    for (const Root& r : out.roots)  // the nearest distinct root
      if (std::abs(r.arc_length - out.arc_length) > 0.01 * sc.length &&
          (!out.other_root_arc_length ||
           std::abs(r.arc_length - out.arc_length) < std::abs(*out.other_root_arc_length - out.arc_length)))
        out.other_root_arc_length = r.arc_length;
  return detail::checked_solution(std::move(out), options.tolerance, w, X, options);
}

}  // namespace vibrissa
