#pragma once
// Placement of the whisker-centred frame B in the world frame W (docs/conventions.md).
//   R_WB = Rz(theta) · Ry(-phi) · Rx(zeta)
// theta: protraction (azimuth) about world +z [rad]; phi: elevation, positive toward world +z [rad];
// zeta: roll about the whisker's own x axis [rad]. With all three zero the whisker emerges along world +x
// and curves (concave) toward world +y.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "vibrissa/core/checks.hpp"

namespace vibrissa {

struct Pose {
  Eigen::Vector3d p_W_base = Eigen::Vector3d::Zero();  ///< base point in world [m]
  double theta = 0.0;                                   ///< protraction [rad]
  double phi = 0.0;                                     ///< elevation [rad]
  double zeta = 0.0;                                    ///< roll [rad]
};

Eigen::Matrix3d rotation_x(double angle);
Eigen::Matrix3d rotation_y(double angle);
Eigen::Matrix3d rotation_z(double angle);

/// R_WB from the pose angles.
Eigen::Matrix3d rotation_from_angles(double theta, double phi, double zeta);
/// The pose angles of a rotation R_WB (inverse of rotation_from_angles; phi in [-pi/2, pi/2]).
Pose pose_from_rotation(const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_W_base);

/// Where a whisker is: the rigid transform X_WB from the whisker frame B to the world W. A small value
/// (12 doubles) given to every solve, so one immutable Whisker serves any number of frames and threads.
struct Placement {
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();  ///< columns: B's axes in W
  Eigen::Vector3d p_W_base = Eigen::Vector3d::Zero();  ///< base point in W [m]

  Placement() = default;
  Placement(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) : R_WB(R), p_W_base(p) {}
  /// From pose angles (R_WB = Rz(theta) Ry(-phi) Rx(zeta)); validates the pose. Implicit, so a Pose can be
  /// passed wherever a Placement is expected.
  Placement(const Pose& pose);  // NOLINT(google-explicit-constructor)

  [[nodiscard]] Pose pose() const { return pose_from_rotation(R_WB, p_W_base); }
  [[nodiscard]] Eigen::Vector3d to_world(const Eigen::Vector3d& p_B) const { return p_W_base + R_WB * p_B; }
  [[nodiscard]] Eigen::Vector3d to_body(const Eigen::Vector3d& p_W) const {
    return R_WB.transpose() * (p_W - p_W_base);
  }
};

/// Throws std::invalid_argument naming the field unless every value is finite.
void validate(const Pose& pose);

}  // namespace vibrissa
