// Surfaces in motion (dynamics/contact.hpp's SurfaceObstacle: planes, spheres, meshes through the shapes' own
// queries): the quasi-static limit (solve_object's sequence), the force along the surface's normal, the penetration
// tolerance, the friction cone, touch and release.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "contact_sweeps.hpp"
#include "vibrissa/dynamics/simulate.hpp"
#include "vibrissa/objects/plane.hpp"
#include "vibrissa/objects/sphere.hpp"
#include "vibrissa/solve/object_contact.hpp"

namespace vibrissa::dynamics {
namespace {

using sweeps::curved_whisker;
using sweeps::rest_point;
using sweeps::smooth_sweep;
using sweeps::sweep_there_and_back;

struct Chain {
  Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  LinearModel model = linear_model(w, dp);
  Modes all = modes(model, w);
};

/// A sphere of radius R whose surface is `offset` behind (-y, on the whisker's convex side, along its normal) the rest whisker's
/// surface at arc length s; retraction (a negative sweep angle) meets it there.
std::shared_ptr<const Shape> sphere_behind(const Whisker& w, double s, double offset, double R) {
  const double r = w.node_radii().front() + (w.node_radii().back() - w.node_radii().front()) * s / w.length();
  const Eigen::Vector3d t = (rest_point(w, s + 1e-4) - rest_point(w, s - 1e-4)).normalized();
  const Eigen::Vector3d ahead(-t.y(), t.x(), 0.0);  // normal to the whisker in its (xy) plane, toward +y
  return std::make_shared<const Sphere>(rest_point(w, s) - (r + offset + R) * ahead, R);
}

/// A wall (plane, normal -y) `offset` ahead (+y) of the rest whisker's tip.
std::shared_ptr<const Shape> wall_ahead(const Whisker& w, double offset) {
  return std::make_shared<const Plane>(w.rest_nodes_B().back() + Eigen::Vector3d(0.0, offset, 0.0),
                                       -Eigen::Vector3d::UnitY());
}

TimeSeries sweep(const Chain& s, const std::shared_ptr<const Shape>& shape, double mu, double T, double angle,
                 double rate = 200.0) {
  SimulationOptions opt;
  opt.duration = T + 0.05;  // held still for the last 50 ms
  opt.output_rate = rate;
  opt.record_nodes = false;
  opt.objects = {obstacle(shape, ObjectPose{}, true, mu)};
  return simulate(s.w, s.model, s.all, smooth_sweep(angle, T), s.dp.gravity_W, opt);
}

/// The largest gap of the base moment to solve_object's sequence along the sweep (frames in contact) [N m], and the
/// sequence's peak.
std::pair<double, double> against_solve_object(const Chain& s, const Shape& shape, const BaseTrajectory& base,
                                               const TimeSeries& ts) {
  double worst = 0.0, peak = 0.0;
  LoadState warm;
  bool have_warm = false;
  int frames = 0;
  for (std::size_t f = 0; f < ts.time.size(); ++f) {
    if (ts.contacts[0].state[f] == ContactState::none) continue;
    const BaseMotion b = base(ts.time[f]);
    const Solution q = solve_object(s.w, Placement(b.R_WB, b.p_W_base), ObjectContact{&shape, ObjectPose{}, true},
                                    ts.contacts[0].arc_length[f], {}, have_warm ? &warm : nullptr);
    EXPECT_EQ(q.status, Status::converged) << "at t = " << ts.time[f];
    if (q.status != Status::converged) continue;
    ++frames;
    warm = q.state;
    have_warm = true;
    peak = std::max(peak, q.moment_W.norm());
    worst = std::max(worst, (q.moment_W - ts.moment_W[f]).norm());
  }
  EXPECT_GT(frames, 10);
  return {worst, peak};
}

/// Frictionless: the force is along the surface's normal at the contact (the shape's own normal there), and the
/// penetration stays within F_n / k_n.
void expect_normal_force_and_penetration(const Shape& shape, const TimeSeries& ts, double stiffness) {
  for (std::size_t f = 0; f < ts.time.size(); ++f) {
    if (ts.contacts[0].state[f] == ContactState::none) continue;
    const Eigen::Vector3d& F = ts.contacts[0].force_W[f];
    const SurfacePoint q = shape.nearest(ts.contacts[0].point_W[f]);
    EXPECT_LT(F.cross(q.normal).norm(), 1e-9 * F.norm()) << "at t = " << ts.time[f];
    EXPECT_GE(F.dot(q.normal), 0.0);
    // At rest the damper's share is zero: the penetration is F_n / k_n (frames are at rest to ~1e-3).
    EXPECT_LE(-ts.contacts[0].gap[f], 1.01 * F.norm() / stiffness + 1e-12) << "at t = " << ts.time[f];
  }
}

TEST(DynamicsSurfaces, SlowSweepsIntoAWallAndASphereConvergeToTheObjectModeSequence) {
  // The curved whisker (30 mm, N = 30) swept 0.2 rad into a wall 2 mm ahead of its tip (a tip contact that slides
  // along the wall) and into a 2 mm sphere 0.5 mm ahead of its surface at s = 20 mm (a side contact), frictionless:
  // the quasi-static answer is solve_object's; the gap closes in proportion to the sweep rate.
  const Chain s;
  const ContactLaw law;
  struct Case {
    const char* name;
    std::shared_ptr<const Shape> shape;
    double angle;
    double tolerance;  // of the gap at the slower sweep, relative to the peak (the wall's tip load is small)
  };
  for (const Case& c :
       {Case{"wall", wall_ahead(s.w, 2e-3), 0.15, 0.05},
        Case{"sphere", sphere_behind(s.w, 0.02, 5e-4, 5e-3), -0.1, 1e-2}}) {
    std::vector<double> errors;
    for (double T : {0.1, 0.2}) {
      const TimeSeries ts = sweep(s, c.shape, 0.0, T, c.angle);
      ASSERT_EQ(ts.status, SimulationStatus::completed);
      ASSERT_EQ(ts.events.size(), 1u) << c.name;
      EXPECT_EQ(ts.events[0].type, ContactEventType::touch);
      const auto [worst, peak] = against_solve_object(s, *c.shape, smooth_sweep(c.angle, T), ts);
      errors.push_back(worst / peak);
      expect_normal_force_and_penetration(*c.shape, ts, law.stiffness);
      std::printf("%s, sweep over %.2f s: contact at s = %.4f m at the end, largest base-moment gap to the "
                  "object-mode sequence %.3g of its peak %.3g N m; %ld steps\n", c.name, T,
                  ts.contacts[0].arc_length.back(), errors.back(), peak, ts.steps);
    }
    EXPECT_LT(errors.back(), c.tolerance) << c.name;
    EXPECT_GT(errors[0] / errors[1], 1.6) << c.name;  // first order in the sweep rate
    EXPECT_LT(errors[0] / errors[1], 2.4) << c.name;
  }
}

TEST(DynamicsSurfaces, FrictionOnAWallStaysInsideTheConeAndSlipsAtItsBound) {
  // The tip pressed onto the wall (mu = 0.3) slides along it: friction in the wall's tangent plane, |F_t| <= mu F_n,
  // at the bound while it slips.
  const Chain s;
  const double mu = 0.3;
  const auto wall = wall_ahead(s.w, 2e-3);
  const TimeSeries ts = sweep(s, wall, mu, 0.1, 0.15, 1000.0);
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  ASSERT_GE(ts.events.size(), 2u);
  EXPECT_EQ(ts.events[0].type, ContactEventType::touch);
  int slipping = 0, sticking = 0;
  const Eigen::Vector3d n = -Eigen::Vector3d::UnitY();
  for (std::size_t f = 0; f < ts.time.size(); ++f) {
    if (ts.contacts[0].state[f] == ContactState::none) continue;
    const Eigen::Vector3d& F = ts.contacts[0].force_W[f];
    const double fn = F.dot(n), ft = (F - fn * n).norm();
    EXPECT_GT(fn, 0.0);
    EXPECT_LE(ft, mu * fn * (1.0 + 1e-9));
    if (ts.contacts[0].state[f] == ContactState::slip) {
      ++slipping;
      EXPECT_NEAR(ft, mu * fn, 1e-9 * fn);
    } else {
      ++sticking;
    }
  }
  std::printf("wall with friction: %d frames slipping, %d sticking, %zu events\n", slipping, sticking,
              ts.events.size());
  EXPECT_GT(slipping, 5);
  EXPECT_GT(sticking, 5);
}

TEST(DynamicsSurfaces, TouchAndReleaseOfASphereAreReportedWhereTheGapCrossesZero) {
  // Swept into the sphere and back out: one touch, one release, at the frames where the gap changes sign.
  const Chain s;
  const auto ball = sphere_behind(s.w, 0.02, 5e-4, 5e-3);
  SimulationOptions opt;
  opt.duration = 0.2;
  opt.output_rate = 2000;
  opt.record_nodes = false;
  opt.objects = {obstacle(ball, ObjectPose{}, true, 0.0)};
  const TimeSeries ts = simulate(s.w, s.model, s.all, sweep_there_and_back(-0.1, 0.15), s.dp.gravity_W, opt);
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  ASSERT_EQ(ts.events.size(), 2u);
  EXPECT_EQ(ts.events[0].type, ContactEventType::touch);
  EXPECT_EQ(ts.events[1].type, ContactEventType::release);
  for (const ContactEvent& e : ts.events) {
    const auto f = static_cast<std::size_t>(std::floor(e.time * opt.output_rate));
    ASSERT_LT(f + 1, ts.time.size());
    EXPECT_LE(ts.contacts[0].gap[f] * ts.contacts[0].gap[f + 1], 0.0) << to_string(e.type) << " at " << e.time;
    EXPECT_NEAR(e.arc_length, 0.02, 2e-3);
  }
  EXPECT_LT(ts.max_penetration, 1e-7);
}

}  // namespace
}  // namespace vibrissa::dynamics


