// The record a contact solve leaves with its state (LoadState::sensitivity, issue 13): the kinematics at its
// solution and their derivatives, from which the next frame's warm start takes its first step without walking
// the chain. It may change what a solve costs, never which root it reaches: a warm start from a solution's state
// must give the results of a warm start from the same four numbers typed in (no record) to within what the
// tolerance fixes, with the same typed outcome; a record that does not belong to the whisker or to the state's
// load is ignored (results bit for bit those without it); wrong derivatives cost time, not the root.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "../core/test_helpers.hpp"
#include "vibrissa/objects/cylinder.hpp"
#include "vibrissa/objects/plane.hpp"
#include "vibrissa/solve/object_contact.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {
namespace {

using test::rat_whisker;
using test::tilted_pose;
using test::vertical_peg;

constexpr double deg = std::numbers::pi / 180.0;

SolveOptions fast() {
  SolveOptions o;
  o.compute_shape = false;
  return o;
}

/// The state's four numbers, as a user would type them in: no record.
LoadState typed_in(const LoadState& s) {
  LoadState out = s;
  out.sensitivity = LoadSensitivity{};
  return out;
}

/// The same root: same typed outcome; contact points within the tolerance (1e-12 m), arc length and force within
/// 1e-9 relative (a residual of 1e-12 m fixes the force to ~1e-9 of itself on these contacts).
void expect_same_root(const Solution& typed, const Solution& carried, const std::string& what) {
  ASSERT_EQ(typed.status, carried.status) << what;
  EXPECT_EQ(typed.contact_state, carried.contact_state) << what;
  EXPECT_EQ(typed.friction, carried.friction) << what;
  if (typed.status != Status::converged) return;
  EXPECT_LE(carried.residual, SolveOptions{}.tolerance) << what;
  EXPECT_LE((typed.contact_point_W - carried.contact_point_W).norm(), SolveOptions{}.tolerance) << what;
  EXPECT_NEAR(typed.arc_length, carried.arc_length, 1e-9 * typed.arc_length) << what;
  EXPECT_NEAR(typed.force_magnitude, carried.force_magnitude, 1e-9 * typed.force_magnitude) << what;
}

bool same_bits(const Solution& a, const Solution& b) {
  return a.status == b.status && a.iterations == b.iterations && a.residual == b.residual &&
         a.state.force_y == b.state.force_y && a.state.force_z == b.state.force_z &&
         a.state.arc_length == b.state.arc_length && a.contact_point_W == b.contact_point_W;
}

TEST(WarmStartRecord, TrackedWhiskMatchesTypedInStatesFrameByFrame) {
  // A 1 kHz protraction of 2 degrees, raising the whisker by 2 degrees, against a peg, then back: edge, point
  // and frictional edge (it sticks, slips up the edge, sticks on the reversal, slips back), each frame
  // warm-started from the previous frame's solution (with its record) and from its four numbers (without).
  const Whisker w = rat_whisker(100, tilted_pose());
  const Edge e = vertical_peg(0.020, 0.0);
  const double mu = 0.05;
  Solution edge, point, friction;
  Eigen::Vector3d contact = Eigen::Vector3d::Zero();
  int frames_in_contact = 0, stick = 0, slip = 0, recorded = 0;
  double worst = 0.0;  // largest relative change of a force or arc length, record vs typed-in state
  int differing = 0;  // solves whose numbers differ at all (the record was used: a different first step)
  auto change = [&worst, &differing](const Solution& a, const Solution& b) {
    if (a.status != Status::converged || b.status != Status::converged) return;
    differing += !same_bits(a, b);
    worst = std::max({worst, std::abs(a.force_magnitude - b.force_magnitude) / a.force_magnitude,
                      std::abs(a.arc_length - b.arc_length) / a.arc_length});
  };
  for (int i = 0; i <= 80; ++i) {
    Pose pose = w.placement().pose();
    pose.theta += (i <= 40 ? i : 80 - i) * 0.05 * deg;
    pose.phi += (i <= 40 ? i : 80 - i) * 0.05 * deg;
    const Placement X(pose);
    const Eigen::Vector3d target = X.to_world(Eigen::Vector3d(0.018, 0.0025, 0.0));
    const std::string frame = "frame " + std::to_string(i);
    const bool edge_warm = i > 0 && edge.status == Status::converged;
    const LoadState edge_typed = typed_in(edge.state), point_typed = typed_in(point.state);
    const Solution edge_now = solve_edge(w, X, e, std::nullopt, fast(), edge_warm ? &edge.state : nullptr);
    const Solution edge_plain = solve_edge(w, X, e, std::nullopt, fast(), edge_warm ? &edge_typed : nullptr);
    expect_same_root(edge_plain, edge_now, "edge " + frame);
    change(edge_plain, edge_now);
    const Solution point_now = solve_point(w, X, target, std::nullopt, fast(), i > 0 ? &point.state : nullptr);
    const Solution point_plain = solve_point(w, X, target, std::nullopt, fast(), i > 0 ? &point_typed : nullptr);
    expect_same_root(point_plain, point_now, "point " + frame);
    change(point_plain, point_now);
    recorded += point_now.state.sensitivity.whisker == w.mechanics_fingerprint();
    edge = edge_now;
    point = point_now;
    if (edge.status != Status::converged) continue;
    ++frames_in_contact;
    const bool touching = friction.status == Status::converged && i > 0;
    if (!touching) contact = edge.contact_point_W;
    const LoadState friction_typed = typed_in(friction.state);
    const Solution friction_now =
        solve_frictional_edge(w, X, e, mu, contact, fast(), touching ? &friction.state : nullptr);
    const Solution friction_plain =
        solve_frictional_edge(w, X, e, mu, contact, fast(), touching ? &friction_typed : nullptr);
    expect_same_root(friction_plain, friction_now, "frictional " + frame);
    change(friction_plain, friction_now);
    friction = friction_now;
    if (friction.status == Status::converged) contact = friction.contact_point_W;
    stick += friction.friction == FrictionState::stick;
    slip += friction.friction == FrictionState::slip;
  }
  EXPECT_GE(frames_in_contact, 60);
  EXPECT_GE(stick, 20);  // both friction states are exercised
  EXPECT_GE(slip, 15);
  EXPECT_EQ(recorded, 81);  // every point solve left a record
  EXPECT_LE(worst, 1e-12);  // 5e-13 when written
  // Without the record a warm start from a solution's state is bit for bit one from its numbers typed in.
  EXPECT_GT(differing, 20);
}

TEST(WarmStartRecord, EveryContactModeLeavesARecordForItsWhisker) {
  const Whisker w = rat_whisker(100, tilted_pose());
  const Edge e = vertical_peg(0.020, 0.0);
  const Solution edge = solve_edge(w, e, std::nullopt, fast());
  ASSERT_EQ(edge.status, Status::converged);
  EXPECT_EQ(edge.state.sensitivity.whisker, w.mechanics_fingerprint());
  const Solution point = solve_point(w, edge.contact_point_W + Eigen::Vector3d(0, 0, 1e-3), std::nullopt, fast());
  ASSERT_EQ(point.status, Status::converged);
  EXPECT_EQ(point.state.sensitivity.whisker, w.mechanics_fingerprint());
  const Solution slip =
      solve_frictional_edge(w, e, 0.01, edge.contact_point_W - Eigen::Vector3d(0, 0, 2e-3), fast(), &edge.state);
  ASSERT_EQ(slip.status, Status::converged);
  EXPECT_EQ(slip.friction, FrictionState::slip);
  EXPECT_EQ(slip.state.sensitivity.whisker, w.mechanics_fingerprint());
  // The fingerprint follows the mechanics, not the placement or the copy.
  Pose moved = w.placement().pose();
  moved.theta += 0.3;
  EXPECT_EQ(w.with_placement(Placement(moved)).mechanics_fingerprint(), w.mechanics_fingerprint());
  WhiskerProperties stiffer;
  stiffer.youngs_modulus *= 1.01;
  EXPECT_NE(Whisker::from_parabola(0.040, 12.0, stiffer, w.placement().pose()).mechanics_fingerprint(),
            w.mechanics_fingerprint());
  EXPECT_NE(Whisker::from_parabola(0.041, 12.0, WhiskerProperties{}, w.placement().pose()).mechanics_fingerprint(),
            w.mechanics_fingerprint());
  WhiskerProperties paper;
  paper.scheme = Scheme::paper;
  EXPECT_NE(Whisker::from_parabola(0.040, 12.0, paper, w.placement().pose()).mechanics_fingerprint(),
            w.mechanics_fingerprint());
}

TEST(WarmStartRecord, AForeignOrStaleRecordIsIgnoredAndAWrongOneCostsTimeNotTheRoot) {
  const Whisker w = rat_whisker(100, tilted_pose());
  Pose before_pose = w.placement().pose();
  before_pose.theta -= 0.2 * deg;
  const Edge e = vertical_peg(0.020, 0.0);
  // Another whisker with the same length and bending stiffness (the same scales of the unknowns), held by a
  // compliant follicle.
  WhiskerProperties held;
  held.base_stiffness = 0.05;
  const Whisker other = Whisker::from_parabola(0.040, 12.0, held, w.placement().pose());
  const Solution from_other = solve_edge(other, Placement(before_pose), e, std::nullopt, fast());
  const Solution from_w = solve_edge(w, Placement(before_pose), e, std::nullopt, fast());
  ASSERT_EQ(from_other.status, Status::converged);
  ASSERT_EQ(from_w.status, Status::converged);

  LoadState foreign = from_other.state;  // its numbers and record, given to w
  LoadState edited = from_w.state;  // the load moved after the record was made
  edited.force_y *= 1.01;
  LoadState axial = from_w.state;  // an axial force component: not a load the contact solves record
  axial.force_x = 1e-6;
  for (const LoadState* start : {&foreign, &edited, &axial}) {
    const LoadState plain = typed_in(*start);
    EXPECT_TRUE(same_bits(solve_edge(w, e, std::nullopt, fast(), &plain), solve_edge(w, e, std::nullopt, fast(), start)));
    EXPECT_TRUE(same_bits(solve_point(w, from_w.contact_point_W, std::nullopt, fast(), &plain),
                          solve_point(w, from_w.contact_point_W, std::nullopt, fast(), start)));
    EXPECT_TRUE(same_bits(solve_frictional_edge(w, e, 0.3, from_w.contact_point_W, fast(), &plain),
                          solve_frictional_edge(w, e, 0.3, from_w.contact_point_W, fast(), start)));
  }
  // The right whisker and load, wrong derivatives: the first step from them fails and is taken again from the
  // exact Jacobian.
  for (double sign : {-3.0, 0.2, 30.0}) {
    LoadState scrambled = from_w.state;
    for (std::size_t i = 0; i < scrambled.sensitivity.kinematics.size(); ++i)
      if (i % 4 != 0) scrambled.sensitivity.kinematics[i] *= (i % 3 == 0 ? sign : 1.0 / sign);
    const LoadState plain = typed_in(scrambled);
    const std::string what = "scrambled by " + std::to_string(sign);
    const Solution edge_plain = solve_edge(w, e, std::nullopt, fast(), &plain);
    const Solution edge_scrambled = solve_edge(w, e, std::nullopt, fast(), &scrambled);
    expect_same_root(edge_plain, edge_scrambled, "edge " + what);
    EXPECT_EQ(edge_plain.iterations, edge_scrambled.iterations) << "edge " << what;  // no damped step taken
    const Solution point_plain = solve_point(w, from_w.contact_point_W, std::nullopt, fast(), &plain);
    const Solution point_scrambled = solve_point(w, from_w.contact_point_W, std::nullopt, fast(), &scrambled);
    expect_same_root(point_plain, point_scrambled, "point " + what);
    EXPECT_EQ(point_plain.iterations, point_scrambled.iterations) << "point " << what;
  }
}

TEST(WarmStartRecord, ObjectSideContactsLeaveARecordThatChangesTheCostNotTheRoot) {
  // A 1 kHz protraction of 2 degrees and back against a peg of radius 1.5 mm and a wall across the whisker's convex
  // side (bench_objects' objects), each frame warm-started from the last frame's state with its record and from its
  // numbers typed in; then records with wrong derivatives, and an edge solve's record (no load frame axes).
  const Whisker w = rat_whisker(100, tilted_pose());
  const Cylinder peg({0.020, 0.0015, 0.0}, {0.0, 0.0, 1.0}, 0.0015);
  const Eigen::Vector3d at = w.placement().to_world(w.rest_point_B(0.022));
  const Eigen::Vector3d t = w.placement().R_WB * w.rest_link_frames_B()[55].col(0);
  const Eigen::Vector3d y = w.placement().R_WB.col(1);
  const Eigen::Vector3d n = (y - y.dot(t) * t).normalized();
  const Plane wall(at + 0.0004 * n, n);
  for (const Shape* shape : std::initializer_list<const Shape*>{&peg, &wall}) {
    const ObjectContact o{shape, {}, true};
    const std::string name(shape->type());
    Solution last;
    int recorded = 0, differing = 0, in_contact = 0;
    for (int i = 0; i <= 80; ++i) {
      Pose pose = w.placement().pose();
      pose.theta += (i <= 40 ? i : 80 - i) * 0.05 * deg;
      const Placement X(pose);
      const bool warm = i > 0 && last.status == Status::converged;
      const LoadState typed = typed_in(last.state);
      const Solution now = solve_object(w, X, o, std::nullopt, fast(), warm ? &last.state : nullptr);
      const Solution plain = solve_object(w, X, o, std::nullopt, fast(), warm ? &typed : nullptr);
      expect_same_root(plain, now, name + " frame " + std::to_string(i));
      if (now.status == Status::converged) {
        ++in_contact;
        EXPECT_LE((plain.surface->normal_W - now.surface->normal_W).norm(), 1e-9) << name << " frame " << i;
      }
      recorded += now.state.sensitivity.object && now.state.sensitivity.whisker == w.mechanics_fingerprint();
      differing += warm && !same_bits(plain, now);
      last = now;
    }
    EXPECT_GE(in_contact, 60) << name;  // (the wall is left behind 20 frames before the turn)
    EXPECT_EQ(recorded, in_contact) << name;  // every side contact left a record
    EXPECT_GE(differing, 40) << name;         // and the warm starts used it

    Pose before_pose = w.placement().pose();
    before_pose.theta -= 0.2 * deg;
    const Solution before = solve_object(w, Placement(before_pose), o, std::nullopt, fast());
    ASSERT_EQ(before.status, Status::converged) << name;
    const LoadState plain_state = typed_in(before.state);
    const Solution plain = solve_object(w, w.placement(), o, std::nullopt, fast(), &plain_state);
    for (double sign : {-3.0, 0.2, 30.0}) {
      LoadState scrambled = before.state;
      for (std::size_t i = 0; i < scrambled.sensitivity.kinematics.size(); ++i)
        if (i % 4 != 0) scrambled.sensitivity.kinematics[i] *= (i % 3 == 0 ? sign : 1.0 / sign);
      for (std::size_t i = 0; i < scrambled.sensitivity.followers.size(); ++i)
        if (i % 4 != 0) scrambled.sensitivity.followers[i] *= (i % 3 == 0 ? 1.0 / sign : sign);
      expect_same_root(plain, solve_object(w, w.placement(), o, std::nullopt, fast(), &scrambled),
                       name + " scrambled by " + std::to_string(sign));
    }
    LoadState edge_record = before.state;  // the same load with an edge solve's record (kinematics, no axes)
    edge_record.sensitivity.object = false;
    EXPECT_TRUE(same_bits(plain, solve_object(w, w.placement(), o, std::nullopt, fast(), &edge_record))) << name;
  }
}

}  // namespace
}  // namespace vibrissa
