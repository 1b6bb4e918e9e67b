// Large-deflection motion and contact during motion (dynamics/simulate.hpp with objects, chain_kinematics.hpp,
// contact.hpp): exact Jacobians, the small-motion limit, the quasi-static limit, release, penetration, friction.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "vibrissa/core/pose.hpp"
#include "vibrissa/core/whisker.hpp"
#include "vibrissa/dynamics/chain_kinematics.hpp"
#include "vibrissa/dynamics/simulate.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa::dynamics {
namespace {

Whisker curved_whisker(int links) {
  WhiskerProperties p;
  p.links = links;
  return Whisker::from_parabola(0.03, 15.0, p);
}

/// Protraction about world z from 0 to `angle` over `duration` with zero velocity at both ends:
/// theta(t) = angle (t / T - sin(2 pi t / T) / (2 pi)), held after T.
BaseTrajectory smooth_sweep(double angle, double duration) {
  return trajectory_from_placements([=](double t) {
    const double x = std::clamp(t / duration, 0.0, 1.0);
    Pose pose;
    pose.theta = angle * (x - std::sin(2.0 * std::numbers::pi * x) / (2.0 * std::numbers::pi));
    return Placement(pose);
  });
}

/// A vertical edge (world z) `offset` [m] ahead (+y) of the rest whisker's centre line at arc length s.
LineObstacle edge_ahead(const Whisker& w, double s, double offset, double mu) {
  const auto& arc = w.node_arc_lengths();
  std::size_t i = 0;
  while (i + 2 < arc.size() && arc[i + 1] < s) ++i;
  const double u = (s - arc[i]) / (arc[i + 1] - arc[i]);
  const Eigen::Vector3d p = w.rest_nodes_B()[i] + u * (w.rest_nodes_B()[i + 1] - w.rest_nodes_B()[i]);
  return line_obstacle(Edge{p + Eigen::Vector3d(0.0, offset, 0.0), Eigen::Vector3d::UnitZ()}, mu);
}

TEST(DynamicsChainKinematics, PointJacobianMatchesFiniteDifferencesAtLargeRotations) {
  const Whisker w = curved_whisker(12);
  const int n = 3 * w.links();
  Eigen::VectorXd q(n);
  for (int i = 0; i < n; ++i) q(i) = 0.3 * std::sin(1.7 * i + 0.4);  // joints turned by up to 0.5 rad
  ChainKinematics k;
  chain_kinematics(w, q, k);
  const int link = 8;
  const double u = 0.37;
  auto point = [&](const Eigen::VectorXd& qq) {
    ChainKinematics kk;
    chain_kinematics(w, qq, kk);
    const auto L = static_cast<std::size_t>(link);
    return Eigen::Vector3d(kk.nodes_B[L] + u * (kk.nodes_B[L + 1] - kk.nodes_B[L]));
  };
  const Eigen::Vector3d x = point(q);
  const Eigen::MatrixXd J = point_jacobian(k, link, x);
  const double h = 1e-6;
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd qp = q, qm = q;
    qp(i) += h;
    qm(i) -= h;
    const Eigen::Vector3d fd = (point(qp) - point(qm)) / (2.0 * h);
    worst = std::max(worst, (fd - J.col(i)).norm());
  }
  EXPECT_LT(worst, 1e-9);  // |dx/dtheta| ~ 1e-2 m; central differences: O(h^2)
  // J^T F by add_generalized_force is the transpose of the same Jacobian.
  const Eigen::Vector3d F(0.3, -0.2, 0.7);
  Eigen::VectorXd Q = Eigen::VectorXd::Zero(n);
  add_generalized_force(k, link, x, F, Q);
  EXPECT_LT((Q - J.transpose() * F).norm(), 1e-15);
  // The composed rotation of a joint is exp(): left Jacobian by differences of the exponential.
  const Eigen::Vector3d th(0.4, -0.9, 0.3), d(1e-7, -2e-7, 0.5e-7);
  const Eigen::Matrix3d dR = rotation_from_vector(th + d) * rotation_from_vector(th).transpose();
  const Eigen::Vector3d jd = left_jacobian(th) * d;
  EXPECT_LT((Eigen::Vector3d(dR(2, 1), dR(0, 2), dR(1, 0)) - jd).norm(), 1e-12);
}

TEST(DynamicsContact, WithoutObjectsTheNonlinearPathAgreesWithTheLinearOneForSmallMotion) {
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  dp.damping_ratio = 0.05;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  InitialState init;
  init.q = 1e-5 * all.joint_shapes.col(0).normalized() + 3e-6 * all.joint_shapes.col(3).normalized();
  SimulationOptions opt;
  opt.duration = 0.03;
  opt.output_rate = 2000;
  opt.relative_tolerance = 1e-7;
  const TimeSeries lin = simulate(w, model, all, fixed_base(Placement{}), dp.gravity_W, opt, init);
  opt.model = ChainModel::nonlinear;
  const TimeSeries non = simulate(w, model, all, fixed_base(Placement{}), dp.gravity_W, opt, init);
  ASSERT_EQ(non.status, SimulationStatus::completed);
  EXPECT_EQ(non.model, ChainModel::nonlinear);
  double peak = 0.0, worst_q = 0.0, worst_tip = 0.0, tip_peak = 0.0;
  for (std::size_t f = 0; f < lin.time.size(); ++f) {
    const auto c = static_cast<Eigen::Index>(f);
    peak = std::max(peak, lin.q.col(c).norm());
    worst_q = std::max(worst_q, (lin.q.col(c) - non.q.col(c)).norm());
    tip_peak = std::max(tip_peak, lin.tip_displacement_B[f].norm());
    worst_tip = std::max(worst_tip, (lin.tip_displacement_B[f] - non.tip_displacement_B[f]).norm());
  }
  std::printf("small motion: q gap %.3g of %.3g, tip gap %.3g of %.3g\n", worst_q, peak, worst_tip, tip_peak);
  EXPECT_LT(worst_q, 1e-4 * peak);   // the same equations without contact: the integrators' errors only
  EXPECT_LT(worst_tip, 1e-2 * tip_peak);  // exact vs linearised kinematics of the shape: O(rotation)
}

/// The quasi-static frictional edge sequence along the sweep at the frames of `ts` (contact history: the previous
/// frame's contact point), and the largest gap of the base moment against the dynamics' [N m], and its peak.
struct Comparison {
  double worst = 0.0, peak = 0.0;
};
Comparison against_quasi_static(const Whisker& w, const BaseTrajectory& base, const LineObstacle& ob,
                                const TimeSeries& ts) {
  Comparison out;
  const Edge edge{ob.point_W, ob.direction_W};
  std::optional<Eigen::Vector3d> previous;
  LoadState warm;
  bool have_warm = false;
  for (std::size_t f = 0; f < ts.time.size(); ++f) {
    const BaseMotion b = base(ts.time[f]);
    const Placement X(b.R_WB, b.p_W_base);
    Solution s;
    if (!previous) {
      s = solve_edge(w, X, edge);
      if (s.status != Status::converged) continue;
      previous = s.contact_point_W;
    }
    s = solve_frictional_edge(w, X, edge, ob.friction_coefficient, *previous, {}, have_warm ? &warm : nullptr);
    if (s.status != Status::converged) continue;
    previous = s.contact_point_W;
    warm = s.state;
    have_warm = true;
    out.peak = std::max(out.peak, s.moment_W.norm());
    out.worst = std::max(out.worst, (s.moment_W - ts.moment_W[f]).norm());
  }
  return out;
}

TEST(DynamicsContact, SlowSweepAgainstAnEdgeConvergesToTheQuasiStaticFrictionalEdge) {
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  for (double mu : {0.0, 0.3}) {
    const LineObstacle ob = edge_ahead(w, 0.02, 5e-4, mu);
    std::vector<double> errors;
    for (double T : {0.1, 0.2, 0.4}) {
      SimulationOptions opt;
      opt.duration = T;
      opt.output_rate = 200;
      opt.objects = {ob};
      const BaseTrajectory base = smooth_sweep(0.2, T);
      const TimeSeries ts = simulate(w, model, all, base, dp.gravity_W, opt);
      ASSERT_EQ(ts.status, SimulationStatus::completed);
      const Comparison c = against_quasi_static(w, base, ob, ts);
      for (std::size_t f = 0; f < ts.time.size(); f += 10)
        std::printf("    t %.3f gap %.3g s %.4f state %d theta %.4f\n", ts.time[f], ts.contacts[0].gap[f],
                    ts.contacts[0].arc_length[f], static_cast<int>(ts.contacts[0].state[f]), ts.placements[f].pose().theta);
      std::printf("mu %.1f T %.2f: moment gap %.3g of %.3g, steps %ld (%ld rejected), penetration %.3g, events %zu\n",
                  mu, T, c.worst, c.peak, ts.steps, ts.rejected_steps, ts.max_penetration, ts.events.size());
      for (const ContactEvent& e : ts.events)
        std::printf("  %s at %.5f s, s = %.4f\n", std::string(to_string(e.type)).c_str(), e.time, e.arc_length);
      errors.push_back(c.worst / c.peak);
    }
  }
}

}  // namespace
}  // namespace vibrissa::dynamics
