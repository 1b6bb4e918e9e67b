// Large-deflection motion and contact during motion (dynamics/simulate.hpp with objects, chain_kinematics.hpp,
// contact.hpp): exact Jacobians, the small-motion limit, the quasi-static limit, release, penetration, friction.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "contact_sweeps.hpp"
#include "vibrissa/core/pose.hpp"
#include "vibrissa/core/whisker.hpp"
#include "vibrissa/dynamics/chain_kinematics.hpp"
#include "vibrissa/dynamics/simulate.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa::dynamics {
namespace {

using sweeps::curved_whisker;
using sweeps::rest_point;
using sweeps::smooth_sweep;

/// A vertical edge (world z) `offset` [m] ahead (+y) of the rest whisker's centre line at arc length s.
LineObstacle edge_ahead(const Whisker& w, double s, double offset, double mu) {
  return line_obstacle(Edge{rest_point(w, s) + Eigen::Vector3d(0.0, offset, 0.0), Eigen::Vector3d::UnitZ()}, mu);
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
/// frame's contact point, from the touch's point on), and the largest gap of the base moment against the
/// dynamics' [N m], its peak, and the static solves' stick/slip per frame in contact.
struct Comparison {
  double worst = 0.0, peak = 0.0;
  std::vector<FrictionState> friction;
};
Comparison against_quasi_static(const Whisker& w, const BaseTrajectory& base, const LineObstacle& ob,
                                const TimeSeries& ts) {
  Comparison out;
  const Edge edge{ob.point_W, ob.direction_W};
  EXPECT_EQ(ts.events.at(0).type, ContactEventType::touch);
  Eigen::Vector3d previous = ts.events.at(0).point_W;  // where the whisker touched: the contact's history starts
  LoadState warm;
  bool have_warm = false;
  for (std::size_t f = 0; f < ts.time.size(); ++f) {
    if (ts.contacts[0].state[f] == ContactState::none) continue;  // before the touch (or after a release)
    const BaseMotion b = base(ts.time[f]);
    const Placement X(b.R_WB, b.p_W_base);
    const Solution s =
        solve_frictional_edge(w, X, edge, ob.friction_coefficient, previous, {}, have_warm ? &warm : nullptr);
    EXPECT_EQ(s.status, Status::converged) << "at t = " << ts.time[f];
    if (s.status != Status::converged) continue;
    previous = s.contact_point_W;
    warm = s.state;
    have_warm = true;
    out.friction.push_back(s.friction);
    out.peak = std::max(out.peak, s.moment_W.norm());
    out.worst = std::max(out.worst, (s.moment_W - ts.moment_W[f]).norm());
  }
  return out;
}

TEST(DynamicsContact, SlowSweepAgainstAnEdgeConvergesToTheQuasiStaticAnswerAndSettlesOnIt) {
  // A curved whisker (30 mm, N = 30) swept 0.2 rad into an edge 0.5 mm ahead of it at s = 20 mm (deflection up to
  // ~3.5 mm there: large), frictionless: the quasi-static answer is edge mode's. The gap closes in proportion to
  // the sweep rate (the joint dampers' forces), and once the base stops the whisker settles on the static answer.
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  const LineObstacle ob = edge_ahead(w, 0.02, 5e-4, 0.0);
  std::vector<double> errors;
  for (double T : {0.1, 0.2}) {
    SimulationOptions opt;
    opt.duration = T + 0.05;  // held still for the last 50 ms
    opt.output_rate = 200;
    opt.objects = {ob};
    const BaseTrajectory base = smooth_sweep(0.2, T);
    const TimeSeries ts = simulate(w, model, all, base, dp.gravity_W, opt);
    ASSERT_EQ(ts.status, SimulationStatus::completed);
    ASSERT_EQ(ts.events.size(), 1u);
    EXPECT_EQ(ts.events[0].type, ContactEventType::touch);
    const Comparison c = against_quasi_static(w, base, ob, ts);
    errors.push_back(c.worst / c.peak);
    // At rest after the sweep: the static solve at the final placement.
    const BaseMotion b = base(opt.duration);
    const Solution s = solve_edge(w, Placement(b.R_WB, b.p_W_base), Edge{ob.point_W, ob.direction_W});
    ASSERT_EQ(s.status, Status::converged);
    const std::size_t last = ts.time.size() - 1;
    EXPECT_LT((ts.moment_W[last] - s.moment_W).norm(), 2e-3 * s.moment_W.norm());
    // The force's direction is normal to the link's chord here, to the smooth rest tangent in the static solve:
    // they differ by O(curvature x link length) (0.015 rad at N = 30), the moment by far less.
    EXPECT_LT((ts.force_W[last] - s.force_W).norm(), 2e-2 * s.force_W.norm());
    EXPECT_NEAR(ts.contacts[0].arc_length[last], s.arc_length, 1e-5);
    std::printf("sweep over %.2f s: largest base-moment gap to the quasi-static sequence %.3g of its peak; at rest "
                "%.3g\n", T, errors.back(), (ts.moment_W[last] - s.moment_W).norm() / s.moment_W.norm());
  }
  EXPECT_LT(errors.back(), 5e-3);
  EXPECT_GT(errors[0] / errors[1], 1.6);  // first order in the sweep rate
  EXPECT_LT(errors[0] / errors[1], 2.4);
}

TEST(DynamicsContact, ATruncatedBasisWithItsStaticCorrectionKeepsTheQuasiStaticAnswer) {
  // The slow sweep above (0.2 s, then held) with only the lowest 10 of the 90 modes integrated, the others static
  // (SimulationOptions::modes): the residual flexibility makes the quasi-static limit exact again (at rest: the
  // static solve), and the run follows the full basis closely.
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  const LineObstacle ob = edge_ahead(w, 0.02, 5e-4, 0.0);
  SimulationOptions opt;
  opt.duration = 0.25;
  opt.output_rate = 200;
  opt.objects = {ob};
  const BaseTrajectory base = smooth_sweep(0.2, 0.2);
  const TimeSeries full = simulate(w, model, all, base, dp.gravity_W, opt);
  opt.modes = 10;
  const TimeSeries ts = simulate(w, model, all, base, dp.gravity_W, opt);
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  ASSERT_EQ(ts.events.size(), 1u);
  const BaseMotion b = base(opt.duration);
  const Solution s = solve_edge(w, Placement(b.R_WB, b.p_W_base), Edge{ob.point_W, ob.direction_W});
  ASSERT_EQ(s.status, Status::converged);
  const std::size_t last = ts.time.size() - 1;
  double gap = 0.0, peak = 0.0;
  for (std::size_t f = 0; f <= last; ++f) {
    gap = std::max(gap, (ts.moment_W[f] - full.moment_W[f]).norm());
    peak = std::max(peak, full.moment_W[f].norm());
  }
  const Comparison c = against_quasi_static(w, base, ob, ts);
  std::printf("10 of 90 modes: at rest %.3g of the static moment; largest gap to the full basis %.3g, to the "
              "quasi-static sequence %.3g of the peak\n",
              (ts.moment_W[last] - s.moment_W).norm() / s.moment_W.norm(), gap / peak, c.worst / c.peak);
  EXPECT_LT((ts.moment_W[last] - s.moment_W).norm(), 5e-4 * s.moment_W.norm());
  EXPECT_NEAR(ts.contacts[0].arc_length[last], s.arc_length, 1e-5);
  EXPECT_LT(c.worst / c.peak, 5e-3);
  EXPECT_LT(gap, 1e-3 * peak);
}

TEST(DynamicsContact, AFastSweepIntoAnEdgeStaysOutOfItWithinThePenaltyTolerance) {
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  SimulationOptions opt;
  opt.duration = 0.04;
  opt.output_rate = 5000;
  opt.objects = {edge_ahead(w, 0.02, 5e-4, 0.0)};
  const TimeSeries ts = simulate(w, model, all, smooth_sweep(0.2, 0.04), dp.gravity_W, opt);  // 5 rad/s at peak
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  double peak_force = 0.0;
  for (const Eigen::Vector3d& F : ts.contacts[0].force_W) peak_force = std::max(peak_force, F.norm());
  std::printf("fast sweep: penetration %.3g m, peak force %.3g N, F/k %.3g m, %zu events\n", ts.max_penetration,
              peak_force, peak_force / opt.contact.stiffness, ts.events.size());
  EXPECT_GT(peak_force, 1e-5);
  // The stated tolerance: penetration = F_n / k_n (at the deepest point the damper's share is zero): below 0.1 um for
  // forces below 1 mN. (The frames sample the force at 5 kHz; the impact's peak falls between them.)
  EXPECT_LT(ts.max_penetration, 1e-7);
}

TEST(DynamicsContact, AWhiskerSlippingOffAnEdgeAtItsTipRingsAtItsFirstInPlaneMode) {
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  dp.damping_ratio = 0.03;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  SimulationOptions opt;
  opt.duration = 0.3;
  opt.output_rate = 5000;
  opt.record_nodes = false;
  opt.objects = {edge_ahead(w, 0.027, 5e-4, 0.0)};
  const TimeSeries ts = simulate(w, model, all, smooth_sweep(0.4, 0.2), dp.gravity_W, opt);
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  ASSERT_GE(ts.events.size(), 2u);
  EXPECT_EQ(ts.events.front().type, ContactEventType::touch);
  EXPECT_EQ(ts.events.back().type, ContactEventType::release);
  EXPECT_NEAR(ts.events.back().arc_length, w.length(), 1e-4);  // it lets go at the tip
  EXPECT_LT(ts.max_penetration, 1e-7);
  // Free after the base stops (0.2 s): zero crossings of the in-plane tip displacement.
  std::vector<double> crossings;
  for (std::size_t f = 1; f < ts.time.size(); ++f) {
    const double a = ts.tip_displacement_B[f - 1].y(), b = ts.tip_displacement_B[f].y();
    if (ts.time[f - 1] >= 0.2 && a < 0.0 && b >= 0.0)
      crossings.push_back(ts.time[f - 1] + (ts.time[f] - ts.time[f - 1]) * a / (a - b));
  }
  ASSERT_GE(crossings.size(), 5u);
  const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  // The in-plane bending mode is the second of the two near-degenerate lowest ones (107.8 / 108.4 Hz).
  const double f_in_plane = all.damped_frequency_hz(1);
  std::printf("release at %.4f s; rings at %.3f Hz, in-plane first mode %.3f Hz\n", ts.events.back().time,
              1.0 / period, f_in_plane);
  EXPECT_NEAR(1.0 / period, f_in_plane, 0.01 * f_in_plane);
}

TEST(DynamicsContact, FrictionStaysInsideTheConeAndSlipIsReported) {
  // An edge tilted 45 degrees out of the whisking plane: the contact slides along it, resisted by friction.
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  LineObstacle ob = edge_ahead(w, 0.02, 5e-4, 0.3);
  ob.direction_W = Eigen::Vector3d(1.0, 0.0, 1.0).normalized();
  SimulationOptions opt;
  opt.duration = 0.1;
  opt.output_rate = 1000;
  opt.objects = {ob};
  const TimeSeries ts = simulate(w, model, all, smooth_sweep(0.2, 0.2), dp.gravity_W, opt);
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  ASSERT_GE(ts.events.size(), 2u);
  EXPECT_EQ(ts.events[0].type, ContactEventType::touch);
  bool slipped = false;
  for (const ContactEvent& e : ts.events) slipped = slipped || e.type == ContactEventType::slip;
  EXPECT_TRUE(slipped);
  int frames_in_contact = 0;
  for (std::size_t f = 0; f < ts.time.size(); ++f) {
    if (ts.contacts[0].state[f] == ContactState::none) continue;
    ++frames_in_contact;
    const Eigen::Vector3d& F = ts.contacts[0].force_W[f];
    const double along = F.dot(ob.direction_W), normal = (F - along * ob.direction_W).norm();
    EXPECT_LE(std::abs(along), 0.3 * normal * (1.0 + 1e-9));
    if (ts.contacts[0].state[f] == ContactState::slip) {
      EXPECT_NEAR(std::abs(along), 0.3 * normal, 1e-9 * normal);
    }
  }
  EXPECT_GT(frames_in_contact, 20);
}

}  // namespace
}  // namespace vibrissa::dynamics


namespace vibrissa::dynamics {
namespace {

TEST(DynamicsContact, SlowSweepAgainstAFrictionalEdgeConvergesToTheQuasiStaticFrictionalEdgeSequence) {
  // The curved whisker swept 0.2 rad into an edge tilted 45 degrees out of the whisking plane, mu = 0.3: on touch
  // the contact slides along the edge (slip), then holds (stick) as the whisker presses on. The quasi-static answer
  // is solve_frictional_edge's sequence with the contact's history from the touch point. The dynamics' friction
  // force lies across the whisker (it slides freely along its length), |F . e| <= mu |F - (F . e) e| as the
  // static law; the gap to the static sequence closes in proportion to the sweep rate.
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  const double mu = 0.3;
  LineObstacle ob = edge_ahead(w, 0.02, 5e-4, mu);
  ob.direction_W = Eigen::Vector3d(1.0, 0.0, 1.0).normalized();
  std::vector<double> errors;
  for (double T : {0.1, 0.2}) {
    SimulationOptions opt;
    opt.duration = T + 0.05;
    opt.output_rate = 200;
    opt.record_nodes = false;
    opt.objects = {ob};
    const BaseTrajectory base = smooth_sweep(0.2, T);
    const TimeSeries ts = simulate(w, model, all, base, dp.gravity_W, opt);
    ASSERT_EQ(ts.status, SimulationStatus::completed);
    // touch, slip, stick, without release; at most one more slip/stick pair, within 1 ms of the first stick (the
    // slip -> stick transition; no chatter through the stick phase).
    ASSERT_GE(ts.events.size(), 3u);
    ASSERT_LE(ts.events.size(), 5u);
    EXPECT_EQ(ts.events[0].type, ContactEventType::touch);
    EXPECT_EQ(ts.events[1].type, ContactEventType::slip);
    EXPECT_EQ(ts.events[2].type, ContactEventType::stick);
    EXPECT_EQ(ts.events.back().type, ContactEventType::stick);
    EXPECT_LT(ts.events.back().time - ts.events[2].time, 1e-3);
    const Comparison c = against_quasi_static(w, base, ob, ts);
    // The static sequence slips, then sticks, as the dynamics.
    ASSERT_FALSE(c.friction.empty());
    EXPECT_EQ(c.friction.front(), FrictionState::slip);
    EXPECT_EQ(c.friction.back(), FrictionState::stick);
    errors.push_back(c.worst / c.peak);
    for (std::size_t f = 0; f < ts.time.size(); ++f) {
      if (ts.contacts[0].state[f] == ContactState::none) continue;
      const Eigen::Vector3d& F = ts.contacts[0].force_W[f];
      const double along = F.dot(ob.direction_W), normal = (F - along * ob.direction_W).norm();
      EXPECT_LE(std::abs(along), mu * normal * (1.0 + 1e-9));
      if (ts.contacts[0].state[f] == ContactState::slip) {
        EXPECT_NEAR(std::abs(along), mu * normal, 1e-9 * normal);
      }
    }
    std::printf("frictional sweep over %.2f s: %ld steps (%ld rejected), largest base-moment gap to the quasi-static "
                "frictional-edge sequence %.3g of its peak\n", T, ts.steps, ts.rejected_steps, errors.back());
  }
  EXPECT_LT(errors.back(), 6e-3);
  EXPECT_GT(errors[0] / errors[1], 1.6);  // first order in the sweep rate
  EXPECT_LT(errors[0] / errors[1], 2.4);
}

}  // namespace
}  // namespace vibrissa::dynamics
