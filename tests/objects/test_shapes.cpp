// Analytic shapes: distances, normals and their derivatives (finite differences), features, invalid input.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "shape_checks.hpp"
#include "vibrissa/objects/box.hpp"
#include "vibrissa/objects/cylinder.hpp"
#include "vibrissa/objects/plane.hpp"
#include "vibrissa/objects/sphere.hpp"

using namespace vibrissa;
using vibrissa::testing::expect_consistent_query;

namespace {

Eigen::Vector3d random_point(std::mt19937_64& rng, double half_width) {
  std::uniform_real_distribution<double> u(-half_width, half_width);
  return {u(rng), u(rng), u(rng)};
}

}  // namespace

TEST(Shapes, PlaneDistanceIsAlongItsNormal) {
  const Plane wall({0.01, 0.0, 0.0}, {2.0, 0.0, 0.0});
  const SurfacePoint q = wall.nearest({0.013, 0.004, -0.2});
  EXPECT_NEAR(q.signed_distance, 0.003, 1e-15);
  EXPECT_TRUE(q.closest.isApprox(Eigen::Vector3d(0.01, 0.004, -0.2)));
  EXPECT_EQ(q.normal, Eigen::Vector3d::UnitX());
  EXPECT_TRUE(q.normal_derivative.isZero(0.0));
  EXPECT_LT(wall.signed_distance({0.0, 1.0, 1.0}), 0.0);
}

TEST(Shapes, SphereAndCylinderAgreeWithCentralDifferences) {
  std::mt19937_64 rng(7);
  const Sphere ball({0.02, -0.01, 0.003}, 0.004);
  const Cylinder peg({0.02, 0.0, 0.0}, {0.1, 0.2, 1.0}, 0.0015);
  const Cylinder can({0.0, 0.01, -0.005}, {1.0, -1.0, 0.5}, 0.003, 0.01);
  for (int i = 0; i < 300; ++i) {
    expect_consistent_query(ball, ball.centre() + random_point(rng, 0.01));
    expect_consistent_query(peg, peg.point() + random_point(rng, 0.01));
    expect_consistent_query(can, can.point() + random_point(rng, 0.015));
  }
}

TEST(Shapes, SphereDistance) {
  const Sphere ball(Eigen::Vector3d::Zero(), 0.002);
  const SurfacePoint q = ball.nearest({0.0, 0.005, 0.0});
  EXPECT_NEAR(q.signed_distance, 0.003, 1e-18);
  EXPECT_TRUE(q.closest.isApprox(Eigen::Vector3d(0.0, 0.002, 0.0)));
  // Curvature of the distance field: (I - n n^T) / |p - centre|.
  EXPECT_NEAR(q.normal_derivative(0, 0), 1.0 / 0.005, 1e-9);
  EXPECT_NEAR(q.normal_derivative(1, 1), 0.0, 1e-12);
  EXPECT_NEAR(ball.signed_distance({0.0, 0.0, 0.001}), -0.001, 1e-18);
}

TEST(Shapes, FiniteCylinderHasCapsAndRims) {
  const Cylinder can(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0.002, 0.01);
  const SurfacePoint side = can.nearest({0.005, 0.0, 0.004});
  EXPECT_EQ(side.feature, SurfaceFeature::face);
  EXPECT_NEAR(side.signed_distance, 0.003, 1e-15);
  const SurfacePoint top = can.nearest({0.001, 0.0, 0.013});
  EXPECT_EQ(top.feature, SurfaceFeature::face);
  EXPECT_NEAR(top.signed_distance, 0.003, 1e-15);
  EXPECT_TRUE(top.normal.isApprox(Eigen::Vector3d::UnitZ()));
  const SurfacePoint rim = can.nearest({0.005, 0.0, -0.004});
  EXPECT_EQ(rim.feature, SurfaceFeature::edge);
  EXPECT_NEAR(rim.signed_distance, 0.005, 1e-15);
  EXPECT_TRUE(rim.closest.isApprox(Eigen::Vector3d(0.002, 0.0, 0.0)));
  EXPECT_NEAR(can.signed_distance({0.0, 0.0, 0.0005}), -0.0005, 1e-18);
  EXPECT_FALSE(can.line_core());
  const Cylinder peg(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0.0);
  ASSERT_TRUE(peg.line_core());
  EXPECT_EQ(peg.line_core()->radius, 0.0);
}

TEST(Shapes, BoxFacesEdgesAndVertices) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d c(0.01, 0.02, -0.01), h(0.002, 0.003, 0.004);
  const Box box(c, h, R);
  auto at = [&](const Eigen::Vector3d& local) { return Eigen::Vector3d(c + R * local); };
  const SurfacePoint face = box.nearest(at({0.001, 0.005, 0.0}));
  EXPECT_EQ(face.feature, SurfaceFeature::face);
  EXPECT_NEAR(face.signed_distance, 0.002, 1e-15);
  const SurfacePoint edge = box.nearest(at({0.005, 0.007, 0.001}));
  EXPECT_EQ(edge.feature, SurfaceFeature::edge);
  EXPECT_NEAR(edge.signed_distance, 0.005, 1e-15);
  EXPECT_NEAR(std::abs(edge.edge_direction.dot(R.col(2))), 1.0, 1e-15);
  const SurfacePoint corner = box.nearest(at({0.004, -0.005, 0.006}));
  EXPECT_EQ(corner.feature, SurfaceFeature::vertex);
  EXPECT_NEAR(corner.signed_distance, std::sqrt(3.0) * 0.002, 1e-15);
  EXPECT_NEAR(box.signed_distance(at({0.0, 0.0, 0.0035})), -0.0005, 1e-15);
  std::mt19937_64 rng(3);
  for (int i = 0; i < 300; ++i) expect_consistent_query(box, c + random_point(rng, 0.008));
}

TEST(Shapes, PlacedShapeQueriesInTheWorld) {
  const Sphere ball(Eigen::Vector3d::Zero(), 0.002);
  ObjectPose X;
  X.R_WO = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  X.p_WO = {0.01, 0.0, 0.0};
  const PlacedShape placed{&ball, X};
  const SurfacePoint q = placed.nearest_W({0.01, 0.004, 0.0});
  EXPECT_NEAR(q.signed_distance, 0.002, 1e-15);
  EXPECT_TRUE(q.normal.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(q.closest.isApprox(Eigen::Vector3d(0.01, 0.002, 0.0)));
}

TEST(Shapes, InvalidInputNamesTheField) {
  auto message = [](auto make) {
    try {
      make();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([] { Plane(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()); }).find("object.normal"), std::string::npos);
  EXPECT_NE(message([] { Sphere(Eigen::Vector3d::Zero(), -1.0); }).find("object.radius"), std::string::npos);
  EXPECT_NE(message([] { Cylinder(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0.001, -2.0); }).find("object.length"),
            std::string::npos);
  EXPECT_NE(message([] { Box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 1)); }).find("object.half_extents[1]"),
            std::string::npos);
  EXPECT_NE(message([] { Box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 1, 1), 2.0 * Eigen::Matrix3d::Identity()); })
                .find("object.rotation"),
            std::string::npos);
}
