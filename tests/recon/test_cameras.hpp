#pragma once
// Two known cameras for the recon tests: one looking down (top), one looking along +y (front).
#include <Eigen/Geometry>

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

}  // namespace vibrissa::recon::test_support
