#pragma once
// Two known cameras for the recon tests: one looking down (top), one looking along +y (front), and the whisking
// whisker they film.
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "vibrissa/core/pose.hpp"
#include "vibrissa/recon/camera.hpp"

namespace vibrissa::recon::test_support {

inline Camera top_test_camera(double k1 = 0.0, double k2 = 0.0) {
  Eigen::Matrix3d K;
  K << 2400, 0, 320, 0, 2400, 240, 0, 0, 1;
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  const Eigen::Vector3d C(0.015, 0.01, 0.3);
  return pinhole_camera(K, R, -R * C, k1, k2);
}
inline Camera front_test_camera(double k1 = 0.0, double k2 = 0.0) {
  Eigen::Matrix3d K;
  K << 2400, 0, 320, 0, 2400, 240, 0, 0, 1;
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  const Eigen::Vector3d C(0.015, -0.3, 0.0);
  return pinhole_camera(K, R, -R * C, k1, k2);
}

/// A 30 mm whisker y = 8 x^2 (B frame) placed at `pose`, 25 points (world).
inline std::vector<Eigen::Vector3d> whisker_points(const Pose& pose) {
  const Placement X(pose);
  std::vector<Eigen::Vector3d> pts;
  for (int k = 0; k < 25; ++k) {
    const double x = 0.03 * k / 24.0;
    pts.push_back(X.to_world(Eigen::Vector3d(x, 8.0 * x * x, 0.0)));
  }
  return pts;
}

/// Frame i of that whisker whisking, its base moving with the pad (world).
inline std::vector<Eigen::Vector3d> whisker_at(int i) {
  constexpr double deg = std::numbers::pi / 180.0;
  Pose p;
  p.p_W_base = Eigen::Vector3d(0.001 + 0.0008 * std::sin(0.1 * i), -0.002 + 0.0003 * std::sin(0.15 * i), 0.0005);
  p.theta = (10.0 + 25.0 * std::sin(0.12 * i)) * deg;
  p.phi = 10.0 * deg;
  p.zeta = 20.0 * deg;
  return whisker_points(p);
}

}  // namespace vibrissa::recon::test_support
