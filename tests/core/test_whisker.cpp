// Whisker construction: resampling, the whisker-centred frame (spec §2.1), material, validation.
#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.hpp"
#include "vibrissa/core/pose.hpp"
#include "vibrissa/core/whisker.hpp"

namespace vibrissa {
namespace {

using test::deg;

TEST(Whisker, ParabolaHasRequestedArcLengthAndEqualLinks) {
  WhiskerProperties p;
  const Whisker w = Whisker::from_parabola(0.04, 12.0, p);
  EXPECT_EQ(w.links(), 100);
  EXPECT_NEAR(w.length(), 0.04, 5e-7);  // chords fall short of the arc by O(ds^2)
  for (double l : w.link_lengths()) EXPECT_NEAR(l, 0.0004, 1e-8);
  for (const auto& n : w.rest_nodes_B()) EXPECT_NEAR(n.y(), 12.0 * n.x() * n.x(), 1e-12);
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
  EXPECT_NEAR(w.length(), ref.length(), 1e-8);
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
