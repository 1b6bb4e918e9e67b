// Contact onset from the sweep of the rest whisker across an edge.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "vibrissa/array/objects.hpp"
#include "vibrissa/contact/crossing.hpp"

using namespace vibrissa;
using namespace vibrissa::array;

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();

// A straight whisker of length L in the x-y plane at angle alpha, n links.
std::vector<Eigen::Vector3d> straight(double alpha, double L, int n, double z = 0.0) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i <= n; ++i) p.emplace_back(L * i / n * std::cos(alpha), L * i / n * std::sin(alpha), z);
  return p;
}
std::vector<double> arcs(double L, int n) {
  std::vector<double> a;
  for (int i = 0; i <= n; ++i) a.push_back(L * i / n);
  return a;
}
}  // namespace

TEST(Crossing, RotatingWhiskerCrossesAPegWhereItsRestShapeMeetsIt) {
  const double L = 0.03, d = 0.017, beta = 0.4;
  const SceneObject peg = make_peg({d * std::cos(beta), d * std::sin(beta), 0.0}, inf, ObjectFrame::world);
  const EdgeSegment& e = peg.edges[0];
  // Before the step the whisker is at beta - 0.01 (short of the peg), after it at beta + 0.03.
  const auto c = find_crossing(straight(beta - 0.01, L, 40), straight(beta + 0.03, L, 40), arcs(L, 40), e, e);
  ASSERT_TRUE(c.has_value());
  // Linear interpolation in time moves points along chords, which shortens them by ~(1 - cos 0.02) ~ 2e-4.
  EXPECT_NEAR(c->arc_length, d, 3e-4 * d);
  EXPECT_GT(c->arc_length, d);
  // Crossing when alpha = beta: the perpendicular distance is linear in sin(alpha - beta), tau ~ 0.25.
  EXPECT_NEAR(c->tau, std::sin(0.01) / (std::sin(0.01) + std::sin(0.03)), 1e-12);
  // Approach: the direction the whisker moved, +alpha (counter-clockwise), normal to it and to the peg.
  EXPECT_NEAR(c->approach_W.dot(Eigen::Vector3d(-std::sin(beta), std::cos(beta), 0.0)), 1.0, 1e-3);
  EXPECT_NEAR(c->approach_W.z(), 0.0, 1e-15);
  EXPECT_NEAR(c->edge_coordinate, 0.0, 1e-15);
  // Moving the other way gives the opposite approach.
  const auto back = find_crossing(straight(beta + 0.03, L, 40), straight(beta - 0.01, L, 40), arcs(L, 40), e, e);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(back->approach_W.dot(c->approach_W), -1.0, 1e-3);
}

TEST(Crossing, NoCrossingWithoutASignChangeOrBeyondTheTip) {
  const double L = 0.03, beta = 0.4;
  const SceneObject near = make_peg({0.02 * std::cos(beta), 0.02 * std::sin(beta), 0.0}, inf, ObjectFrame::world);
  // Both frames short of the peg.
  EXPECT_FALSE(find_crossing(straight(beta - 0.05, L, 30), straight(beta - 0.01, L, 30), arcs(L, 30),
                             near.edges[0], near.edges[0]));
  // A peg beyond the tip is passed without contact.
  const SceneObject far = make_peg({0.035 * std::cos(beta), 0.035 * std::sin(beta), 0.0}, inf, ObjectFrame::world);
  EXPECT_FALSE(find_crossing(straight(beta - 0.01, L, 30), straight(beta + 0.01, L, 30), arcs(L, 30), far.edges[0],
                             far.edges[0]));
}

TEST(Crossing, FiniteEdgeIsCrossedOnlyWithinItsExtent) {
  const double L = 0.03, beta = 0.4;
  const Eigen::Vector3d p(0.02 * std::cos(beta), 0.02 * std::sin(beta), 0.0);
  // A vertical segment from z = 1 mm to 5 mm does not reach the whisker's plane z = 0.
  const SceneObject above = make_edge(p + Eigen::Vector3d(0, 0, 0.001), {0, 0, 1}, 0.004, ObjectFrame::world);
  const auto prev = straight(beta - 0.01, L, 30), now = straight(beta + 0.01, L, 30);
  EXPECT_FALSE(find_crossing(prev, now, arcs(L, 30), above.edges[0], above.edges[0], true));
  const auto line = find_crossing(prev, now, arcs(L, 30), above.edges[0], above.edges[0], false);
  ASSERT_TRUE(line.has_value());
  EXPECT_NEAR(line->edge_coordinate, -0.001, 1e-12);
  const SceneObject through = make_edge(p - Eigen::Vector3d(0, 0, 0.002), {0, 0, 1}, 0.004, ObjectFrame::world);
  EXPECT_TRUE(find_crossing(prev, now, arcs(L, 30), through.edges[0], through.edges[0], true));
}

TEST(Crossing, InclinedEdgeIsTestedAlongItsOwnDirection) {
  // An edge inclined in the whisker's plane's normal direction: the whisker in plane z = 0 crosses its line
  // where the edge pierces that plane.
  const double L = 0.03, beta = 0.2;
  const Eigen::Vector3d pierce(0.015 * std::cos(beta), 0.015 * std::sin(beta), 0.0);
  const Eigen::Vector3d dir = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  const SceneObject e = make_edge(pierce - 0.004 * dir, dir, 0.01, ObjectFrame::world);
  const auto c = find_crossing(straight(beta - 0.2, L, 60), straight(beta + 0.2, L, 60), arcs(L, 60), e.edges[0],
                               e.edges[0]);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->edge_coordinate, 0.004, 2e-4);
}
