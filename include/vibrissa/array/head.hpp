#pragma once
// Pose of the head in the world over time (spec §3.4: "the rat pitches its head"). The head frame H is the
// morphology's (x lateral right, y rostral, z dorsal). R_WH = Rz(yaw)·Rx(pitch)·Ry(roll):
//   pitch about the head's lateral x axis, positive = nose (+y) up toward +z;
//   yaw about the dorsal z axis, positive = nose toward the rat's left (-x);
//   roll about the rostral y axis, positive = right side (+x) down.
// The head frame's origin moves as p_W_head(t).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace vibrissa::array {

struct HeadPose {
  Eigen::Matrix3d R_WH = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_W_head = Eigen::Vector3d::Zero();  ///< [m]

  [[nodiscard]] Eigen::Vector3d point_to_world(const Eigen::Vector3d& p_H) const { return p_W_head + R_WH * p_H; }
  [[nodiscard]] Eigen::Vector3d vector_to_world(const Eigen::Vector3d& v_H) const { return R_WH * v_H; }
};

Eigen::Matrix3d head_rotation(double yaw, double pitch, double roll);

/// One sample of a user head trajectory.
struct HeadSample {
  double time = 0.0;                                  ///< [s]
  Eigen::Vector3d p_W_head = Eigen::Vector3d::Zero();  ///< [m]
  double yaw = 0.0, pitch = 0.0, roll = 0.0;          ///< [rad]
};

/// Head motion: constant rates from an initial pose, or a sampled trajectory (linear interpolation, held
/// outside its time range). A sweep's extra pitch is added on top of either.
struct HeadMotion {
  Eigen::Vector3d p_W_head = Eigen::Vector3d::Zero();  ///< at t = 0 [m]
  Eigen::Vector3d v_W_head = Eigen::Vector3d::Zero();  ///< [m/s]
  double yaw = 0.0, pitch = 0.0, roll = 0.0;          ///< at t = 0 [rad]
  double yaw_rate = 0.0, pitch_rate = 0.0, roll_rate = 0.0;  ///< [rad/s]
  std::vector<HeadSample> series;                     ///< if not empty, replaces the fields above

  [[nodiscard]] HeadPose at(double t, double extra_pitch = 0.0) const;
};
void validate(const HeadMotion& head, const std::string& field = "head");

}  // namespace vibrissa::array
