#pragma once
// The cross-product matrix: skew(a) b = a x b (the dynamics code's Eigen form of the chain's rotations).
#include <Eigen/Core>

namespace vibrissa::dynamics {

/// [a]x, the matrix with skew(a) * b == a.cross(b).
inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

}  // namespace vibrissa::dynamics
