// Contact-point, edge and frictional edge modes: roots, statuses, invariances, Jacobians.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../core/test_helpers.hpp"
#include "vibrissa/core/chain.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {
namespace {

using test::deg;
using test::rat_whisker;
using test::tilted_pose;
using test::vertical_peg;


TEST(PointMode, RecoversTheForceModeLoad) {
  const Whisker w = rat_whisker(100, tilted_pose());
  const Solution forward = solve_force(w, 1.5e-4, 0.0213, 0.8);
  const Solution sol = solve_point(w, forward.contact_point_W, 0.0213);
  ASSERT_EQ(sol.status, Status::converged) << sol.message;
  EXPECT_LE(sol.residual, 1e-12);
  EXPECT_NEAR(sol.arc_length, 0.0213, 1e-10);
  EXPECT_NEAR(sol.force_magnitude / 1.5e-4, 1.0, 1e-8);
  EXPECT_NEAR(sol.angle, 0.8, 1e-8);
}

TEST(PointMode, WarmFramesDoNotProbeForOtherRoots) {
  // The same point as below, warm-started from the far root: that root, and no scan (issue 13).
  const Whisker w = rat_whisker();
  const Solution far = solve_force(w, 1e-4, 0.030, 0.3);
  SolveOptions probing;
  probing.find_other_roots = true;
  const Solution warm = solve_point(w, far.contact_point_W, std::nullopt, probing, &far.state);
  const Solution plain = solve_point(w, far.contact_point_W, std::nullopt, SolveOptions{}, &far.state);
  ASSERT_EQ(warm.status, Status::converged);
  EXPECT_NEAR(warm.arc_length, 0.030, 1e-9);
  EXPECT_TRUE(warm.roots.empty());
  EXPECT_FALSE(warm.other_root_arc_length.has_value());
  EXPECT_EQ(warm.iterations, plain.iterations);
  EXPECT_EQ(warm.arc_length, plain.arc_length);
  const Solution cold = solve_point(w, far.contact_point_W, std::nullopt, probing);
  EXPECT_TRUE(cold.other_root_arc_length.has_value());  // the cold solve does scan
}

TEST(PointMode, ReportsAndSelectsAnotherRoot) {
  // A contact nearer the base with a smaller force can reach the same point (issue 2, item 6).
  const Whisker w = rat_whisker();
  const Solution far = solve_force(w, 1e-4, 0.030, 0.3);
  SolveOptions o;
  o.find_other_roots = true;
  const Solution cold = solve_point(w, far.contact_point_W, std::nullopt, o);
  ASSERT_EQ(cold.status, Status::converged);
  ASSERT_TRUE(cold.other_root_arc_length.has_value());
  const double s_other = std::abs(cold.arc_length - 0.030) < 1e-8 ? *cold.other_root_arc_length : cold.arc_length;
  const Solution a = solve_point(w, far.contact_point_W, 0.030);
  const Solution b = solve_point(w, far.contact_point_W, s_other);
  EXPECT_NEAR(a.arc_length, 0.030, 1e-9);
  EXPECT_NEAR(b.arc_length, s_other, 1e-9);
  EXPECT_GT(std::abs(a.arc_length - b.arc_length), 1e-3);
  EXPECT_LE((b.contact_point_W - far.contact_point_W).norm(), 1e-12);
}

TEST(PointMode, OutOfReachIsNoContactNotNaN) {
  const Whisker w = rat_whisker();
  const Solution s = solve_point(w, Eigen::Vector3d(0.1, 0.0, 0.0));
  EXPECT_EQ(s.status, Status::no_contact);
  EXPECT_TRUE(s.force_W.allFinite());
  EXPECT_EQ(s.force_magnitude, 0.0);
}

TEST(EdgeMode, ContactOnLineForceNormalToLineAndWhisker) {
  const Whisker w = rat_whisker(100, tilted_pose());
  const Edge peg = vertical_peg(0.020, 0.0);
  const Solution s = solve_edge(w, peg);
  ASSERT_EQ(s.status, Status::converged) << s.message;
  const Eigen::Vector3d d = peg.direction.normalized();
  Eigen::Vector3d off = s.contact_point_W - peg.point;
  off -= off.dot(d) * d;
  EXPECT_LE(off.norm(), 1e-12);
  EXPECT_LE(std::abs(s.force_W.dot(d)), 1e-12 * s.force_magnitude);
  EXPECT_NEAR(*s.edge_force, 0.0, 1e-15);
  EXPECT_NEAR(*s.normal_force, s.force_magnitude, 1e-15);
  // Normal to the whisker: orthogonal to the deflected tangent at the contact.
  const std::size_t k = static_cast<std::size_t>(s.arc_length / 0.0004);
  const Eigen::Vector3d t = (s.shape_W[k + 1] - s.shape_W[k]).normalized();
  EXPECT_LT(std::abs(s.force_W.normalized().dot(t)), 0.02);  // link vs smooth tangent: O(ds) in angle
  EXPECT_GT(std::abs(s.contact_point_W.z()), 1e-3);  // it slipped up the peg: the frictionless answer
}

TEST(EdgeMode, OutOfReachWrongSideAndSlipOff) {
  const Whisker w = rat_whisker();
  EXPECT_EQ(solve_edge(w, vertical_peg(0.2, 0.0)).status, Status::no_contact);
  // The peg in front of the whisker (concave side) would have to pull when approached by protraction.
  const Edge front = vertical_peg(0.020, 0.012);
  EXPECT_EQ(solve_edge(w, front, std::nullopt, {}, nullptr, Eigen::Vector3d(0, 1, 0)).status, Status::no_contact);
  // Near the tip and deep: equilibrium needs contact beyond the tip.
  const Edge deep = vertical_peg(0.037, -0.004);
  EXPECT_EQ(solve_edge(w, deep).status, Status::slipped_off);
  const Solution s = solve_edge(w, deep);
  EXPECT_TRUE(s.force_W.allFinite());
  EXPECT_TRUE(std::isfinite(s.arc_length));
}

TEST(EdgeMode, WarmStartFollowsTheSameBranchInFewIterations) {
  const Edge peg = vertical_peg(0.020, 0.0);
  LoadState state;
  const LoadState* warm = nullptr;
  for (double th = 0.0; th <= 10.0; th += 1.0) {
    Pose p = tilted_pose();
    p.theta = deg(th);
    const Whisker w = rat_whisker(100, p);
    const Solution s = solve_edge(w, peg, std::nullopt, {}, warm);
    const Solution cold = solve_edge(w, peg);
    ASSERT_EQ(s.status, Status::converged);
    EXPECT_NEAR(s.arc_length, cold.arc_length, 1e-10);
    if (warm) {
      EXPECT_LE(s.iterations, 5);
    }
    state = s.state;
    warm = &state;
  }
}

TEST(FrictionalEdge, LimitsAndFrictionCone) {
  const Whisker w = rat_whisker(100, tilted_pose());
  const Edge peg = vertical_peg(0.020, 0.0);
  const Solution free = solve_edge(w, peg);
  const Eigen::Vector3d previous = free.contact_point_W - Eigen::Vector3d(0, 0, 0.003);
  // mu = 0: the frictionless edge mode.
  const Solution zero = solve_frictional_edge(w, peg, 0.0, previous);
  EXPECT_LE((zero.contact_point_W - free.contact_point_W).norm(), 1e-12);
  // mu -> infinity: contact-point mode at the stuck point.
  const Solution stuck = solve_frictional_edge(w, peg, 1e6, previous);
  const Solution point = solve_point(w, previous, std::nullopt, {}, nullptr, peg.direction);
  ASSERT_EQ(stuck.status, Status::converged);
  EXPECT_LE((stuck.contact_point_W - previous).norm(), 1e-12);
  EXPECT_LE((stuck.force_W - point.force_W).norm(), 1e-8 * point.force_magnitude);
  // In between: on the cone, between the stuck and the frictionless points (§3.1).
  for (double mu : {0.05, 0.2, 0.48}) {
    const Solution s = solve_frictional_edge(w, peg, mu, previous);
    ASSERT_EQ(s.status, Status::converged) << s.message;
    EXPECT_LE(std::abs(*s.edge_force), mu * *s.normal_force * (1 + 1e-9));
    const double z = s.contact_point_W.z();
    EXPECT_GE(z, std::min(previous.z(), free.contact_point_W.z()) - 1e-12);
    EXPECT_LE(z, std::max(previous.z(), free.contact_point_W.z()) + 1e-12);
  }
}

TEST(Invariance, RigidMotionOfTheSceneRotatesEveryOutput) {
  const Whisker w = rat_whisker(100, tilted_pose());
  const Edge peg = vertical_peg(0.020, 0.0);
  const Solution a = solve_edge(w, peg);
  // Rotate and translate whisker pose and edge together.
  const Eigen::Matrix3d Q = rotation_from_angles(0.7, -0.4, 1.1);
  const Eigen::Vector3d t(0.01, -0.02, 0.005);
  std::vector<Eigen::Vector3d> pts;
  for (const auto& n : w.rest_nodes_B()) pts.push_back(Q * w.placement().to_world(n) + t);
  const Whisker w2 = Whisker::from_points(pts, WhiskerProperties{});
  Edge peg2;
  peg2.point = Q * peg.point + t;
  peg2.direction = Q * peg.direction;
  const Solution b = solve_edge(w2, peg2);
  ASSERT_EQ(b.status, Status::converged);
  EXPECT_NEAR(b.arc_length, a.arc_length, 1e-9);
  EXPECT_LT((b.contact_point_W - (Q * a.contact_point_W + t)).norm(), 1e-9);
  EXPECT_LT((b.force_W - Q * a.force_W).norm(), 1e-6 * a.force_magnitude);
  EXPECT_LT((b.moment_W - Q * a.moment_W).norm(), 1e-6 * a.moment_W.norm());
  EXPECT_LT((b.whisker_frame.force - a.whisker_frame.force).norm(), 1e-6 * a.force_magnitude);
  EXPECT_NEAR(b.whisker_frame.MD, a.whisker_frame.MD, 1e-6);
}

TEST(Jacobian, DualNumbersMatchFiniteDifferences) {
  const Whisker w = rat_whisker(100, tilted_pose());
  const double Fy = 1.2e-4, Fz = -0.7e-4, s = 0.0231;
  using D = Dual<3>;
  const auto c = deflect<D>(w, V3<D>(D(0.0), D::variable(Fy, 0), D::variable(Fz, 1)), V3<D>(D(0.0), D(0.0), D(0.0)),
                            D::variable(s, 2));
  const double h[3] = {1e-9, 1e-9, 1e-8};
  for (int j = 0; j < 3; ++j) {
    double x[3] = {Fy, Fz, s};
    x[j] += h[j];
    const auto p = deflect<double>(w, V3<double>(0, x[0], x[1]), V3<double>(0, 0, 0), x[2]);
    x[j] -= 2 * h[j];
    const auto m = deflect<double>(w, V3<double>(0, x[0], x[1]), V3<double>(0, 0, 0), x[2]);
    const Eigen::Vector3d fd = (to_eigen(p.p_contact_B) - to_eigen(m.p_contact_B)) / (2 * h[j]);
    const Eigen::Vector3d ad(c.p_contact_B.x.d[j], c.p_contact_B.y.d[j], c.p_contact_B.z.d[j]);
    EXPECT_LT((fd - ad).norm(), 1e-6 * ad.norm()) << "column " << j;
  }
}

TEST(Errors, BadLoadsNameTheField) {
  const Whisker w = rat_whisker();
  Edge e = vertical_peg(0.02, 0.0);
  e.direction = Eigen::Vector3d::Zero();
  EXPECT_THROW(solve_edge(w, e), std::invalid_argument);
  try {
    solve_edge(w, e);
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("edge.direction"), std::string::npos);
  }
  EXPECT_THROW(solve_force(w, 1e-4, 0.05, 0.0), std::invalid_argument);  // beyond the tip
  EXPECT_THROW(solve_force(w, std::nan(""), 0.02, 0.0), std::invalid_argument);
  EXPECT_THROW(solve_point(w, Eigen::Vector3d(std::nan(""), 0, 0)), std::invalid_argument);
  EXPECT_THROW(solve_frictional_edge(w, vertical_peg(0.02, 0), -0.1, Eigen::Vector3d::Zero()), std::invalid_argument);
}

}  // namespace
}  // namespace vibrissa
