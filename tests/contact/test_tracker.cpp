// The contact tracker: one policy for onset, friction start, stick/slip, push-past and release
// (contact/tracker.hpp), checked against independent computations and single solves.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

#include "vibrissa/contact/contact_geometry.hpp"
#include "vibrissa/contact/tracker.hpp"
#include "vibrissa/solve/solvers.hpp"

// Heap allocations of this test program, counted by replacing the global allocation functions (kept out of
// line, so that the compiler does not pair an inlined new with free()).
namespace {
std::atomic<long> g_allocations{0};
}  // namespace
[[gnu::noinline]] void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void* operator new[](std::size_t n) { return ::operator new(n); }
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace vibrissa;

namespace {

constexpr double kPegRadius = 0.020;  // peg distance from the base [m]
constexpr double kPegAzimuth = 0.25;  // [rad]

// A 30 mm whisker concave toward +y, swept about world +z: increasing theta moves it toward the peg.
Whisker sweep_whisker(int links = 60) {
  WhiskerProperties p;
  p.links = links;
  return Whisker::from_parabola(0.030, 20.0, p);
}

EdgeSegment peg() {
  return infinite_segment(Edge{{kPegRadius * std::cos(kPegAzimuth), kPegRadius * std::sin(kPegAzimuth), 0.0},
                               Eigen::Vector3d::UnitZ()});
}

Placement at_theta(double theta) {
  Pose pose;
  pose.theta = theta;
  return Placement(pose);
}

// Azimuth about +z of the rest whisker where it is kPegRadius from the base (it lies in the z = 0 plane).
double azimuth_at_peg_radius(const Whisker& w, double theta) {
  const auto& nodes = w.rest_nodes_B();
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    const double r0 = nodes[i - 1].norm(), r1 = nodes[i].norm();
    if (r1 >= kPegRadius) {
      const Eigen::Vector3d p = nodes[i - 1] + (kPegRadius - r0) / (r1 - r0) * (nodes[i] - nodes[i - 1]);
      return theta + std::atan2(p.y(), p.x());
    }
  }
  return std::nan("");
}

}  // namespace

TEST(ContactTracker, OnsetIsTheFrameAfterTheRestWhiskerSweepsAcrossThePeg) {
  const Whisker w = sweep_whisker();
  const EdgeSegment e = peg();
  TrackerOptions o;
  o.mode = ContactMode::frictional_edge;
  o.mu = 10.0;  // sticks: the contact stays where it started
  o.solve.compute_shape = false;
  ContactTracker tracker(w, o);
  int onset = -1;
  for (int k = 0; k < 200 && onset < 0; ++k) {
    const TrackedFrame& f = tracker.step(at_theta(-0.3 + 0.002 * k), {&e, 1});
    if (f.onset) {
      onset = k;
      EXPECT_EQ(f.state, ContactState::contact);
      EXPECT_EQ(f.edge, 0);
      ASSERT_EQ(f.solution.status, Status::converged);
      EXPECT_EQ(f.solution.friction, FrictionState::stick);
      // Friction starts where the rest whisker met the peg: in the whisker's plane, on the peg.
      EXPECT_NEAR(f.solution.contact_point_W.z(), 0.0, 1e-10);
      EXPECT_NEAR(f.edge_coordinate, 0.0, 1e-10);
      EXPECT_EQ(f.onset_edge_coordinate, f.edge_coordinate);
      // The whisker moved in +theta: the approach is normal to the peg and to the rest whisker's tangent there,
      // toward +theta (the left normal z × t of the swept link).
      int link = 0;
      double h = 0.0;
      w.locate(tracker.frame().solution.arc_length, link, h);
      const Eigen::Vector3d t_W = at_theta(-0.3 + 0.002 * k).R_WB * w.rest_link_frames_B()[link].col(0);
      EXPECT_NEAR(f.approach_W.dot(Eigen::Vector3d::UnitZ().cross(t_W).normalized()), 1.0, 2e-3);
    } else {
      EXPECT_EQ(f.state, ContactState::free);
      EXPECT_FALSE(f.solved);
    }
  }
  ASSERT_GT(onset, 0);
  EXPECT_LT(azimuth_at_peg_radius(w, -0.3 + 0.002 * (onset - 1)), kPegAzimuth);
  EXPECT_GE(azimuth_at_peg_radius(w, -0.3 + 0.002 * onset), kPegAzimuth);
}

TEST(ContactTracker, PushedPastUntilTheWhiskerRetractsAcrossThePegAgain) {
  const Whisker w = sweep_whisker();
  const EdgeSegment e = peg();
  TrackerOptions o;
  o.mode = ContactMode::edge;
  o.solve.compute_shape = false;
  ContactTracker tracker(w, o);
  std::vector<double> thetas;
  for (int k = 0; k <= 300; ++k) thetas.push_back(-0.3 + 0.005 * k);     // protraction to 1.2 rad
  for (int k = 1; k <= 300; ++k) thetas.push_back(1.2 - 0.005 * k);      // and back
  std::vector<ContactState> states;
  for (double th : thetas) states.push_back(tracker.step(at_theta(th), {&e, 1}).state);
  // free -> contact -> pushed_past on the way out; pushed_past -> free exactly when retraction recrosses.
  std::size_t first_contact = states.size(), first_past = states.size(), back_free = states.size();
  for (std::size_t k = 0; k < states.size(); ++k) {
    if (states[k] == ContactState::contact && first_contact == states.size()) first_contact = k;
    if (states[k] == ContactState::pushed_past && first_past == states.size()) first_past = k;
    if (first_past < k && states[k] == ContactState::free && back_free == states.size()) back_free = k;
  }
  ASSERT_LT(first_contact, first_past);
  ASSERT_LT(first_past, 301u);  // pushed past during protraction
  ASSERT_LT(back_free, states.size());
  for (std::size_t k = first_past; k < back_free; ++k) EXPECT_EQ(states[k], ContactState::pushed_past) << k;
  EXPECT_GE(azimuth_at_peg_radius(w, thetas[back_free - 1]), kPegAzimuth);
  EXPECT_LT(azimuth_at_peg_radius(w, thetas[back_free]), kPegAzimuth);
  EXPECT_GT(tracker.solves(), 0u);
}

TEST(ContactTracker, WarmFramesAllocateNothing) {
  const Whisker w = sweep_whisker(100);
  const EdgeSegment e = peg();
  for (ContactMode mode : {ContactMode::edge, ContactMode::frictional_edge}) {
    TrackerOptions o;
    o.mode = mode;
    o.mu = 0.3;
    o.solve.compute_shape = false;
    ContactTracker tracker(w, o);
    double theta = -0.2;
    while (tracker.step(at_theta(theta), {&e, 1}).state != ContactState::contact) theta += 0.001;
    for (int k = 0; k < 10; ++k) tracker.step(at_theta(theta += 1e-5), {&e, 1});  // per-thread workspace grown
    const long before = g_allocations.load();
    int contact_frames = 0;
    for (int k = 0; k < 1000; ++k)
      contact_frames += tracker.step(at_theta(theta += 1e-5), {&e, 1}).state == ContactState::contact;
    EXPECT_EQ(g_allocations.load() - before, 0) << to_string(mode);
    EXPECT_EQ(contact_frames, 1000) << to_string(mode);
  }
}

TEST(ContactTracker, TrackedEdgeFramesEqualWarmStartedSingleSolves) {
  const Whisker w = sweep_whisker();
  const EdgeSegment e = peg();
  TrackerOptions o;
  o.mode = ContactMode::edge;
  ContactTracker tracker(w, o);
  std::optional<LoadState> warm;
  std::optional<double> hint;
  int converged = 0;
  for (int k = 0; k < 40; ++k) {
    const Placement X = at_theta(0.0 + 0.004 * k);
    TrackedInput in;
    const TrackedFrame& f = tracker.step_tracked(X, &e, in);
    const Solution s = solve_edge(w, X, e.line(), hint, o.solve, warm ? &*warm : nullptr);
    ASSERT_EQ(f.solution.status, s.status) << k;
    EXPECT_EQ(f.solution.arc_length, s.arc_length) << k;
    EXPECT_EQ(f.solution.force_W, s.force_W) << k;
    EXPECT_EQ(f.solution.shape_W, s.shape_W) << k;
    EXPECT_EQ(f.onset, k == 0);
    if (s.status == Status::converged) {
      warm = s.state;
      hint = s.arc_length;
      ++converged;
    } else {
      warm.reset();
      hint.reset();
    }
  }
  EXPECT_GT(converged, 30);
}

TEST(ContactTracker, FrictionStateFollowsTheCoulombCone) {
  const Whisker w = sweep_whisker();
  const EdgeSegment e = infinite_segment(Edge{{0.018, 0.004, 0.0}, Eigen::Vector3d(0.0, 0.6, 0.8)});
  for (double mu : {0.0, 1e6}) {
    TrackerOptions o;
    o.mode = ContactMode::frictional_edge;
    o.mu = mu;
    ContactTracker tracker(w, o);
    for (int k = 0; k < 10; ++k) {
      TrackedInput in;
      const TrackedFrame& f = tracker.step_tracked(at_theta(0.002 * k), &e, in);
      ASSERT_EQ(f.solution.status, Status::converged) << mu << " " << k;
      const Solution& s = f.solution;
      EXPECT_EQ(s.friction, mu == 0.0 ? FrictionState::slip : FrictionState::stick);
      EXPECT_LE(std::abs(*s.edge_force), (mu * (1 + 1e-9) + 1e-9) * *s.normal_force);
      if (mu > 0.0) {  // stuck where the rest whisker first lay nearest the edge
        EXPECT_LT((s.contact_point_W - nearest_rest_point(w, at_theta(0.0), e.line()).on_edge_W).norm(), 1e-10);
      }
    }
  }
}

TEST(ContactTracker, MisuseIsRejectedNamingTheField) {
  const Whisker w = sweep_whisker(20);
  const EdgeSegment e = peg();
  TrackerOptions point;
  point.mode = ContactMode::contact_point;
  ContactTracker p(w, point);
  EXPECT_THROW(p.step(at_theta(0.0), {&e, 1}), std::invalid_argument);
  TrackedInput in;
  try {
    p.step_tracked(at_theta(0.0), nullptr, in);
    FAIL();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("p_W_contact"), std::string::npos);
  }
  TrackerOptions edge;
  ContactTracker t(w, edge);
  t.step(at_theta(0.0), {&e, 1});
  const EdgeSegment two[2] = {e, e};
  EXPECT_THROW(t.step(at_theta(0.0), {two, 2}), std::invalid_argument);
  EXPECT_THROW(t.step_tracked(at_theta(0.0), nullptr, in), std::invalid_argument);
  TrackerOptions bad;
  bad.mu = -1.0;
  EXPECT_THROW(ContactTracker(w, bad), std::invalid_argument);
  EXPECT_EQ(contact_mode_from_string("frictional_edge"), ContactMode::frictional_edge);
  EXPECT_THROW(contact_mode_from_string("slidey", "solver.mode"), std::invalid_argument);
}
