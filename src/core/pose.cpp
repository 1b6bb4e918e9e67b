#include "vibrissa/core/pose.hpp"

#include <algorithm>
#include <cmath>

namespace vibrissa {

Eigen::Matrix3d rotation_x(double a) {
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return R;
}
Eigen::Matrix3d rotation_y(double a) {
  Eigen::Matrix3d R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}
Eigen::Matrix3d rotation_z(double a) {
  Eigen::Matrix3d R;
  R << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return R;
}

Eigen::Matrix3d rotation_from_angles(double theta, double phi, double zeta) {
  return rotation_z(theta) * rotation_y(-phi) * rotation_x(zeta);
}

Pose pose_from_rotation(const Eigen::Matrix3d& R, const Eigen::Vector3d& p_W_base) {
  // Columns of R are the B axes in W. x_B = (cos phi cos theta, cos phi sin theta, sin phi).
  Pose pose;
  pose.p_W_base = p_W_base;
  const Eigen::Vector3d x = R.col(0);
  pose.phi = std::asin(std::clamp(x.z(), -1.0, 1.0));
  pose.theta = std::atan2(x.y(), x.x());
  // Remove theta and phi; what remains is Rx(zeta).
  const Eigen::Matrix3d Rx = (rotation_z(pose.theta) * rotation_y(-pose.phi)).transpose() * R;
  pose.zeta = std::atan2(Rx(2, 1), Rx(1, 1));
  return pose;
}

Placement::Placement(const Pose& pose) {
  validate(pose);
  R_WB = rotation_from_angles(pose.theta, pose.phi, pose.zeta);
  p_W_base = pose.p_W_base;
}

void validate(const Pose& pose) {
  require_finite(pose.p_W_base, "pose.base");
  require_finite(pose.theta, "pose.theta");
  require_finite(pose.phi, "pose.phi");
  require_finite(pose.zeta, "pose.zeta");
}

}  // namespace vibrissa
