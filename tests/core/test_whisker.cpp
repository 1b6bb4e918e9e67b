// Whisker construction: resampling, the whisker-centred frame (spec §2.1), material, validation.
#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.hpp"
#include "vibrissa/core/pose.hpp"
#include "vibrissa/core/whisker.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {
namespace {

using test::deg;

// The length a user gives is the whisker's arc length: the model's polyline (its links) is exactly that long,
// its N chords are equal and its nodes lie on the curve (docs/conventions.md, "Discretisation").
void expect_equal_chords(const Whisker& w, double length) {
  EXPECT_NEAR(w.length(), length, 1e-12 * length);
  EXPECT_NEAR(w.node_arc_lengths().back(), length, 1e-12 * length);
  for (double l : w.link_lengths()) EXPECT_NEAR(l, length / w.links(), 1e-12 * length / w.links());
}

TEST(Whisker, ParabolaHasRequestedArcLengthAndEqualLinks) {
  WhiskerProperties p;
  const Whisker w = Whisker::from_parabola(0.04, 12.0, p);
  EXPECT_EQ(w.links(), 100);
  expect_equal_chords(w, 0.04);
  for (const auto& n : w.rest_nodes_B()) EXPECT_NEAR(n.y(), 12.0 * n.x() * n.x(), 1e-12);
  // The case: length 0.03, curvature 40 (chords summed to 0.0299998 m before), at N = 2..1000, both
  // schemes; a load at s = L, the length given, is accepted.
  for (int links : {2, 3, 17, 100, 1000})
    for (Scheme scheme : {Scheme::second_order, Scheme::paper}) {
      p.links = links;
      p.scheme = scheme;
      const Whisker v = Whisker::from_parabola(0.03, 40.0, p);
      SCOPED_TRACE("links " + std::to_string(links));
      expect_equal_chords(v, 0.03);
      for (const auto& n : v.rest_nodes_B()) EXPECT_NEAR(n.y(), 40.0 * n.x() * n.x(), 1e-14);
    }
  p = WhiskerProperties{};
  const Whisker v = Whisker::from_parabola(0.03, 40.0, p);
  EXPECT_EQ(solve_force(v, 1e-4, 0.03, 0.0).status, Status::converged);
}

TEST(Whisker, CubicHasItsLengthAndPointsKeepTheirEnds) {
  WhiskerProperties p;
  p.links = 60;
  const double A = 300.0, B = 15.0, L = 0.035;
  const Whisker cubic = Whisker::from_cubic(L, A, B, p);
  expect_equal_chords(cubic, L);
  for (const auto& n : cubic.rest_nodes_B()) EXPECT_NEAR(n.y(), (A * n.x() + B) * n.x() * n.x(), 1e-14);
  // Points: no length is given; the tip is the last point and the N equal chords run along the spline through
  // the points from the first to the last. 401 points on the parabola y = 25 x^2, whose arc length to x = X is
  // known in closed form: the chords are shorter than it by at most (kappa l)^2 / 24 relative.
  const double a = 25.0, X = 0.03;
  auto arc = [a](double x) {  // integral of sqrt(1 + (2 a x)^2)
    const double u = 2.0 * a * x;
    return (u * std::sqrt(1.0 + u * u) + std::asinh(u)) / (4.0 * a);
  };
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i <= 400; ++i) {
    const double x = X * i / 400.0;
    pts.emplace_back(0.002 + x, -0.001 + a * x * x, 0.0005);
  }
  const Whisker w = Whisker::from_points(pts, p);
  expect_equal_chords(w, w.length());
  const double l = w.length() / w.links(), kappa_max = 2.0 * a;
  EXPECT_LT(w.length(), arc(X));
  EXPECT_GT(w.length(), arc(X) * (1.0 - kappa_max * kappa_max * l * l / 24.0));
  EXPECT_LT((w.placement().to_world(w.rest_nodes_B().back()) - pts.back()).norm(), 1e-15);
  for (const auto& n : w.rest_nodes_B()) {  // on the curve (the spline through the points, O(h^4) off it)
    const Eigen::Vector3d q = w.placement().to_world(n) - pts.front();
    EXPECT_NEAR(q.y(), a * q.x() * q.x(), 1e-12);
    EXPECT_NEAR(q.z(), 0.0, 1e-15);
  }
  // The paper scheme keeps the points as its nodes (Elastica3D: s = cumulative chord length).
  p.scheme = Scheme::paper;
  const Whisker kept = Whisker::from_points(pts, p);
  double chords = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) chords += (pts[i] - pts[i - 1]).norm();
  EXPECT_NEAR(kept.length(), chords, 1e-14);
}

TEST(Whisker, HairpinAndSelfCrossingPointsNameTheSegments) {
  const std::vector<Eigen::Vector3d> hairpin = {{0, 0, 0}, {0.01, 0, 0}, {0.02, 0, 0}, {0.012, 0.0001, 0},
                                                {0.005, 0.0002, 0}};
  EXPECT_NE(test::invalid_message([&] { (void)Whisker::from_points(hairpin, WhiskerProperties{}, std::nullopt); })
                .find("whisker.points: segments 1 and 2 (segment k joins points k and k+1) turn back by 179 deg"),
            std::string::npos);
  const std::vector<Eigen::Vector3d> crossing = {{0, 0, 0}, {0.02, 0, 0}, {0.02, 0.01, 0}, {0.01, 0.01, 0},
                                                 {0.01, -0.01, 0}};
  EXPECT_NE(test::invalid_message([&] { (void)Whisker::from_points(crossing, WhiskerProperties{}, std::nullopt); })
                .find("whisker.points: segments 0 and 3 (segment k joins points k and k+1) touch or cross"),
            std::string::npos);
  // The same crossing in 3D, lifted 1 mm apart, is a valid (if odd) curve: only touching is refused.
  std::vector<Eigen::Vector3d> lifted = crossing;
  lifted[3].z() = lifted[4].z() = 0.001;
  EXPECT_NO_THROW((void)Whisker::from_points(lifted, WhiskerProperties{}, std::nullopt));
}

TEST(Whisker, StiffnessFollowsSpecFormulas) {
  WhiskerProperties p;  // E 3.3 GPa, nu 0.38, r 100 um, ratio 15
  const Whisker w = Whisker::from_parabola(0.04, 12.0, p);
  const double I = std::numbers::pi * std::pow(1e-4, 4) / 4.0, J = 2.0 * I, G = 3.3e9 / (2.0 * 1.38);
  EXPECT_NEAR(w.base_bending_stiffness() / (3.3e9 * I), 1.0, 1e-14);
  EXPECT_NEAR(w.torsion_compliance()[0] * G * J, 1.0, 1e-14);
  EXPECT_NEAR(w.node_radii().back(), 1e-4 / 15.0, 1e-15);
}

TEST(Whisker, FrameFromWorldPointsRecoversPose) {
  // Place a parabola with a known pose, hand its nodes over as world points: the frame of spec §2.1 must
  // give back the same pose (concave toward +y, x along emergence).
  Pose pose;
  pose.p_W_base = {0.001, -0.002, 0.003};
  pose.theta = deg(35);
  pose.phi = deg(-12);
  pose.zeta = deg(50);
  const Whisker ref = Whisker::from_parabola(0.04, 12.0, WhiskerProperties{}, pose);
  std::vector<Eigen::Vector3d> pts;
  for (const auto& n : ref.rest_nodes_B()) pts.push_back(ref.placement().to_world(n));
  const Whisker w = Whisker::from_points(pts, WhiskerProperties{});
  EXPECT_LT((w.placement().R_WB - ref.placement().R_WB).norm(), 5e-6);
  EXPECT_LT((w.placement().p_W_base - ref.placement().p_W_base).norm(), 1e-15);
  // The equal chords through a whisker's own nodes, first to last, are its links: the same whisker again.
  EXPECT_NEAR(w.length(), ref.length(), 1e-15);
  for (std::size_t i = 0; i < pts.size(); ++i)
    EXPECT_LT((w.placement().to_world(w.rest_nodes_B()[i]) - pts[i]).norm(), 1e-15);
  const Pose back = w.placement().pose();
  EXPECT_NEAR(back.theta, pose.theta, 5e-6);
  EXPECT_NEAR(back.phi, pose.phi, 5e-6);
  EXPECT_NEAR(back.zeta, pose.zeta, 5e-6);
}

TEST(Whisker, PoseAnglesRoundTrip) {
  for (double th : {-1.0, 0.3, 2.5})
    for (double ph : {-0.7, 0.0, 1.2})
      for (double ze : {-2.0, 0.4}) {
        const Pose p = pose_from_rotation(rotation_from_angles(th, ph, ze), Eigen::Vector3d::Zero());
        EXPECT_NEAR(p.theta, th, 1e-12);
        EXPECT_NEAR(p.phi, ph, 1e-12);
        EXPECT_NEAR(p.zeta, ze, 1e-12);
      }
  // Worked example of docs/conventions.md: theta = 90 deg points the whisker along world +y.
  const Eigen::Matrix3d R = rotation_from_angles(deg(90), 0.0, 0.0);
  EXPECT_LT((R.col(0) - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  EXPECT_LT((R.col(1) + Eigen::Vector3d::UnitX()).norm(), 1e-15);
}

TEST(Whisker, InvalidInputNamesFieldAndValue) {
  WhiskerProperties p;
  auto expect_message = [](auto&& f, const std::string& needle) {
    try {
      f();
      ADD_FAILURE() << "no exception; expected one mentioning " << needle;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_message([&] { Whisker::from_parabola(-0.01, 1.0, p); }, "whisker.length");
  expect_message([&] { Whisker::from_parabola(std::nan(""), 1.0, p); }, "whisker.length");
  expect_message([&] { Whisker::from_parabola(0.04, std::nan(""), p); }, "whisker.curvature");
  expect_message([&] { Whisker::from_points({{0, 0, 0}, {1e-3, 0, 0}}, p); }, "at least 3 points");
  expect_message([&] { Whisker::from_points({{0, 0, 0}, {1e-3, 0, 0}, {1e-3, 0, 0}}, p); }, "coincide");
  expect_message([&] { Whisker::from_points({{0, 0, 0}, {1e-3, std::nan(""), 0}, {2e-3, 0, 0}}, p); }, "whisker.points[1]");
  WhiskerProperties bad = p;
  bad.base_radius = 0.0;
  expect_message([&] { Whisker::from_parabola(0.04, 1.0, bad); }, "whisker.base_radius");
  bad = p;
  bad.radii = {1e-4, -1e-5};
  expect_message([&] { Whisker::from_parabola(0.04, 1.0, bad); }, "whisker.radii[1]");
  bad = p;
  bad.links = 1;
  expect_message([&] { Whisker::from_parabola(0.04, 1.0, bad); }, "whisker.links");
  bad = p;
  bad.poisson_ratio = 0.7;
  expect_message([&] { Whisker::from_parabola(0.04, 1.0, bad); }, "whisker.poisson_ratio");
  Pose pose;
  pose.theta = std::nan("");
  expect_message([&] { Whisker::from_parabola(0.04, 1.0, p, pose); }, "pose.theta");
}

}  // namespace
}  // namespace vibrissa
