// SolveOptions::secant_jacobians (issue 13): Broyden secant Jacobians within a solve and carried from one
// frame's state to the next (LoadSensitivity). The option must reach the same roots as the default (Newton
// on exact Jacobians), with the same typed outcome, to within what the tolerance fixes; a record that does
// not belong to the whisker or to the state's load must be ignored; a wrong record must cost time, not the root.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {
namespace {

constexpr double deg = std::numbers::pi / 180.0;

Whisker curved(double E_scale = 1.0) {
  Pose pose;
  pose.theta = 10.0 * deg;
  pose.phi = 10.0 * deg;
  pose.zeta = 30.0 * deg;
  WhiskerProperties props;
  props.youngs_modulus *= E_scale;
  return Whisker::from_parabola(0.040, 12.0, props, pose);
}

Edge peg(double x, double y) {
  Edge e;
  e.point = {x, y, 0.0};
  e.direction = {0.0, 0.0, 1.0};
  return e;
}

SolveOptions options(bool secant) {
  SolveOptions o;
  o.compute_shape = false;
  o.secant_jacobians = secant;
  return o;
}

/// The same root: same typed outcome; contact points within a few tolerances, load within 1e-6 relative
/// (a residual of 1e-12 m fixes the force to ~1e-9 of itself on these contacts).
void expect_same_root(const Solution& newton, const Solution& secant, const std::string& what) {
  ASSERT_EQ(newton.status, secant.status) << what;
  EXPECT_EQ(newton.contact_state, secant.contact_state) << what;
  EXPECT_EQ(newton.friction, secant.friction) << what;
  if (newton.status != Status::converged) return;
  EXPECT_LE(secant.residual, SolveOptions{}.tolerance) << what;
  EXPECT_LE((newton.contact_point_W - secant.contact_point_W).norm(), 5.0 * SolveOptions{}.tolerance) << what;
  EXPECT_NEAR(newton.arc_length, secant.arc_length, 1e-6 * newton.arc_length) << what;
  EXPECT_NEAR(newton.force_magnitude, secant.force_magnitude, 1e-6 * newton.force_magnitude) << what;
}

TEST(SecantJacobians, ColdSolvesReachTheSameRoots) {
  const Whisker w = curved();
  int compared = 0;
  for (double x : {0.010, 0.014, 0.018, 0.022})
    for (double y : {-0.004, 0.0, 0.003}) {
      const Edge e = peg(x, y);
      const Solution a = solve_edge(w, e, std::nullopt, options(false));
      const Solution b = solve_edge(w, e, std::nullopt, options(true));
      expect_same_root(a, b, "edge " + std::to_string(x) + " " + std::to_string(y));
      if (a.status != Status::converged) continue;
      ++compared;
      const Eigen::Vector3d target = a.contact_point_W + Eigen::Vector3d(0.0, 0.0, 1e-3);
      expect_same_root(solve_point(w, target, std::nullopt, options(false)),
                       solve_point(w, target, std::nullopt, options(true)), "point near edge " + std::to_string(x));
    }
  EXPECT_GE(compared, 6);
}

TEST(SecantJacobians, TrackedWhiskMatchesNewtonFrameByFrame) {
  // A 1 kHz protraction of 2 degrees, raising the whisker by 2 degrees, against a peg, then back: edge, point
  // and frictional edge (it sticks, slips up the edge, sticks on the reversal, slips back) tracked with each
  // option, every frame warm-started from the same option's previous frame.
  const Whisker w = curved();
  const Edge e = peg(0.020, 0.0);
  const double mu = 0.05;
  Solution edge[2], point[2], friction[2];
  Eigen::Vector3d contact[2];
  int frames_in_contact = 0, stick = 0, slip = 0;
  for (int i = 0; i <= 80; ++i) {
    Pose pose = w.placement().pose();
    pose.theta += (i <= 40 ? i : 80 - i) * 0.05 * deg;
    pose.phi += (i <= 40 ? i : 80 - i) * 0.05 * deg;
    const Placement X(pose);
    const Eigen::Vector3d target = X.to_world(Eigen::Vector3d(0.018, 0.0025, 0.0));
    for (int k = 0; k < 2; ++k) {
      const SolveOptions o = options(k == 1);
      const bool warm = i > 0 && edge[k].status == Status::converged;
      edge[k] = solve_edge(w, X, e, std::nullopt, o, warm ? &edge[k].state : nullptr);
      point[k] = solve_point(w, X, target, std::nullopt, o, i > 0 ? &point[k].state : nullptr);
      if (edge[k].status != Status::converged) continue;
      const bool touching = i > 0 && friction[k].status == Status::converged;
      if (!touching) contact[k] = edge[k].contact_point_W;
      friction[k] = solve_frictional_edge(w, X, e, mu, contact[k], o, touching ? &friction[k].state : nullptr);
      if (friction[k].status == Status::converged) contact[k] = friction[k].contact_point_W;
    }
    const std::string frame = "frame " + std::to_string(i);
    expect_same_root(edge[0], edge[1], "edge " + frame);
    expect_same_root(point[0], point[1], "point " + frame);
    if (edge[0].status != Status::converged) continue;
    ++frames_in_contact;
    expect_same_root(friction[0], friction[1], "frictional " + frame);
    stick += friction[0].friction == FrictionState::stick;
    slip += friction[0].friction == FrictionState::slip;
  }
  EXPECT_GE(frames_in_contact, 60);
  EXPECT_GE(stick, 20);  // both friction states are exercised
  EXPECT_GE(slip, 15);
}

TEST(SecantJacobians, OnlyTheOptionLeavesARecordAndOnlyForItsWhisker) {
  const Whisker w = curved();
  const Edge e = peg(0.020, 0.0);
  EXPECT_EQ(solve_edge(w, e, std::nullopt, options(false)).state.sensitivity.whisker, 0u);
  const Solution s = solve_edge(w, e, std::nullopt, options(true));
  ASSERT_EQ(s.status, Status::converged);
  EXPECT_EQ(s.state.sensitivity.whisker, w.mechanics_fingerprint());
  // The fingerprint follows the mechanics, not the placement or the copy.
  Pose moved = w.placement().pose();
  moved.theta += 0.3;
  EXPECT_EQ(w.with_placement(Placement(moved)).mechanics_fingerprint(), w.mechanics_fingerprint());
  EXPECT_NE(curved(1.01).mechanics_fingerprint(), w.mechanics_fingerprint());
  EXPECT_NE(Whisker::from_parabola(0.041, 12.0, WhiskerProperties{}, w.placement().pose()).mechanics_fingerprint(),
            w.mechanics_fingerprint());
}

TEST(SecantJacobians, AForeignOrStaleRecordCostsTimeNotTheRoot) {
  // The record of a stiffer whisker, a record whose load was edited, and a record with scrambled derivatives:
  // each warm start must reach the root Newton reaches from the same numbers.
  const Whisker w = curved();
  const Whisker stiffer = curved(1.5);
  Pose before_pose = w.placement().pose();
  before_pose.theta -= 0.2 * deg;
  const Edge e = peg(0.020, 0.0);
  const Solution from_stiffer = solve_edge(stiffer, Placement(before_pose), e, std::nullopt, options(true));
  const Solution from_w = solve_edge(w, Placement(before_pose), e, std::nullopt, options(true));
  ASSERT_EQ(from_stiffer.status, Status::converged);
  ASSERT_EQ(from_w.status, Status::converged);

  LoadState foreign = from_w.state;  // this whisker's numbers, the stiffer whisker's record
  foreign.sensitivity = from_stiffer.state.sensitivity;
  LoadState edited = from_w.state;  // the load moved after the record was made
  edited.force_y *= 1.01;
  LoadState scrambled = from_w.state;  // the right whisker and load, wrong derivatives
  for (std::size_t i = 0; i < scrambled.sensitivity.kinematics.size(); ++i)
    if (i % 4 != 0) scrambled.sensitivity.kinematics[i] *= (i % 3 == 0 ? -3.0 : 0.2);

  for (const LoadState* start : {&foreign, &edited, &scrambled}) {
    LoadState plain = *start;
    plain.sensitivity = LoadSensitivity{};
    const Solution newton = solve_edge(w, e, std::nullopt, options(false), &plain);
    const Solution secant = solve_edge(w, e, std::nullopt, options(true), start);
    expect_same_root(newton, secant, start == &foreign ? "foreign" : start == &edited ? "edited" : "scrambled");
    const Solution point_newton = solve_point(w, newton.contact_point_W, std::nullopt, options(false), &plain);
    const Solution point_secant = solve_point(w, newton.contact_point_W, std::nullopt, options(true), start);
    expect_same_root(point_newton, point_secant, "point");
  }
}

}  // namespace
}  // namespace vibrissa
