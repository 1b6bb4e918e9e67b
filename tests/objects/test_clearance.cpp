// Clearance's lower bound (objects/clearance.hpp): no point of a polyline of cone frusta has a smaller gap to the
// object, checked against dense sampling of every link, for polylines near, across and far from a sphere and a
// tessellated sphere, with and without a threshold; and it is not vacuous (positive for a polyline clear of the
// object, within a link's length of the true smallest gap).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "vibrissa/objects/clearance.hpp"
#include "vibrissa/objects/mesh.hpp"
#include "vibrissa/objects/sphere.hpp"

using namespace vibrissa;

namespace {

struct Polyline {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<double> arc, radii;
};

/// A random walk of n links of about `step` from `start`, radii tapering from r0 to zero.
Polyline random_polyline(std::mt19937_64& rng, const Eigen::Vector3d& start, int n, double step, double r0) {
  std::normal_distribution<double> g(0.0, 1.0);
  Polyline p;
  Eigen::Vector3d dir(g(rng), g(rng), g(rng));
  dir.normalize();
  p.nodes.push_back(start);
  p.arc.push_back(0.0);
  for (int i = 0; i < n; ++i) {
    dir = (dir + 0.3 * Eigen::Vector3d(g(rng), g(rng), g(rng))).normalized();
    p.nodes.push_back(p.nodes.back() + step * dir);
    p.arc.push_back(p.arc.back() + step);
  }
  for (int i = 0; i <= n; ++i) p.radii.push_back(r0 * (1.0 - static_cast<double>(i) / n));
  return p;
}

/// The smallest gap over 100 points of every link.
double sampled_minimum(const PlacedShape& o, const Polyline& p) {
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < p.nodes.size(); ++i)
    for (int k = 0; k <= 100; ++k) {
      const double t = k / 100.0;
      const Eigen::Vector3d x = (1.0 - t) * p.nodes[i] + t * p.nodes[i + 1];
      lowest = std::min(lowest, o.signed_distance_W(x) - ((1.0 - t) * p.radii[i] + t * p.radii[i + 1]));
    }
  return lowest;
}

}  // namespace

TEST(Clearance, LowerBoundHoldsOnEveryLinkAndIsNotVacuous) {
  const Eigen::Vector3d centre(0.01, 0.0, -0.002);
  const Sphere sphere(centre, 0.003);
  const Mesh ball(tessellated_sphere(centre, 0.003, 3));
  ObjectPose pose;
  pose.R_WO = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  pose.p_WO = Eigen::Vector3d(0.001, -0.002, 0.0005);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.006, 0.006);
  int inside = 0, clear = 0;
  for (const Shape* shape : {static_cast<const Shape*>(&sphere), static_cast<const Shape*>(&ball)}) {
    const PlacedShape o{shape, pose};
    for (int trial = 0; trial < 60; ++trial) {
      const Eigen::Vector3d start = pose.to_world(centre + Eigen::Vector3d(u(rng), u(rng), u(rng)));
      const Polyline p = random_polyline(rng, start, 12, 0.0008, 5e-5);
      const double lowest = sampled_minimum(o, p);
      for (double threshold : {0.0, std::numeric_limits<double>::infinity()}) {
        const Clearance c = clearance(o, p.nodes, p.arc, p.radii, threshold);
        EXPECT_LE(c.lower_bound, lowest + 1e-15) << shape->type() << " " << trial;
        EXPECT_LE(c.lower_bound, c.gap) << shape->type() << " " << trial;
        // Within a link's length (the Lipschitz bound's slack) of the smallest gap.
        EXPECT_GE(c.lower_bound, std::min(lowest, 0.0) - 2.0 * 0.0008) << shape->type() << " " << trial;
      }
      if (lowest < 0.0) ++inside;
      if (lowest > 0.0016) {
        ++clear;
        EXPECT_GT(clearance(o, p.nodes, p.arc, p.radii, 0.0).lower_bound, 0.0) << shape->type() << " " << trial;
      }
    }
  }
  EXPECT_GT(inside, 8);  // the cases cover both sides
  EXPECT_GT(clear, 8);
}
