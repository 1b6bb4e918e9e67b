// Scene objects: edges, pegs, prisms, in head or world coordinates; invalid geometry names the field.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "vibrissa/array/objects.hpp"

using namespace vibrissa::array;

namespace {
void expect_error_naming(const std::function<void()>& f, const std::string& field) {
  try {
    f();
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}
constexpr double inf = std::numeric_limits<double>::infinity();
}  // namespace

TEST(Objects, PegIsAVerticalLine) {
  const SceneObject peg = make_peg({0.02, 0.01, 0.0}, inf, ObjectFrame::world);
  ASSERT_EQ(peg.edges.size(), 1u);
  EXPECT_EQ(peg.edges[0].direction, Eigen::Vector3d::UnitZ());
  EXPECT_FALSE(peg.edges[0].finite());
  EXPECT_NEAR(peg.edges[0].normal.dot(peg.edges[0].direction), 0.0, 1e-15);
  EXPECT_NEAR(peg.edges[0].normal.norm(), 1.0, 1e-15);
}

TEST(Objects, FiniteEdgeExtent) {
  const SceneObject e = make_edge({0, 0, 0}, {0, 0, 2}, 0.01, ObjectFrame::world);
  EXPECT_NEAR(e.edges[0].direction.norm(), 1.0, 1e-15);
  EXPECT_TRUE(e.edges[0].contains(0.005));
  EXPECT_FALSE(e.edges[0].contains(0.011));
  EXPECT_FALSE(e.edges[0].contains(-0.001));
}

TEST(Objects, PrismHasThreeEdgesAlongItsAxis) {
  const SceneObject p = make_prism({{0.02, 0, 0}, {0.03, 0, 0}, {0.025, 0.01, 0}}, {0, 0, 1}, 0.02, ObjectFrame::world);
  ASSERT_EQ(p.edges.size(), 3u);
  for (const auto& e : p.edges) {
    EXPECT_EQ(e.direction, Eigen::Vector3d::UnitZ());
    EXPECT_DOUBLE_EQ(e.length, 0.02);
  }
  expect_error_naming([] { make_prism({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {0, 0, 1}, 1, ObjectFrame::world, "objects[2]"); },
                      "objects[2].vertices_mm");
}

TEST(Objects, InvalidGeometryNamesTheField) {
  expect_error_naming([] { make_edge({0, 0, 0}, {0, 0, 1}, 0.0, ObjectFrame::world, "objects[1]"); },
                      "objects[1].length_mm");
  expect_error_naming([] { make_edge({0, 0, 0}, {0, 0, 0}, inf, ObjectFrame::world, "objects[0]"); },
                      "objects[0].direction");
  expect_error_naming([] { make_peg({std::nan(""), 0, 0}, inf, ObjectFrame::world, "objects[3]"); },
                      "objects[3].point_mm");
  expect_error_naming([] { object_frame_from_string("lab", "objects[0].frame"); }, "objects[0].frame");
}

TEST(Objects, HeadFixedObjectsMoveWithTheHead) {
  const std::vector<SceneObject> scene{make_peg({0.02, 0.0, 0.0}, inf, ObjectFrame::head),
                                       make_peg({0.02, 0.0, 0.0}, inf, ObjectFrame::world)};
  HeadMotion h;
  h.pitch = std::numbers::pi / 6;
  h.p_W_head = {0.0, 0.0, 0.005};
  const auto edges = edges_in_world(scene, h.at(0.0));
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_NEAR((edges[0].p0 - Eigen::Vector3d(0.02, 0.0, 0.005)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(edges[0].direction.y(), -0.5, 1e-15);  // the head's z axis tilted back by the pitch
  EXPECT_NEAR(edges[0].normal.dot(edges[0].direction), 0.0, 1e-15);
  EXPECT_EQ(edges[1].direction, Eigen::Vector3d::UnitZ());
}
