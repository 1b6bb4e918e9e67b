#pragma once
// Everything a solve reports (spec §2.4). World-frame quantities unless the name says otherwise; the
// whisker-centred frame B is the rest frame of spec §2.1 at the whisker's current pose.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/solve/status.hpp"

namespace vibrissa {

/// Unknowns of a contact solve: force components in the frame of the loaded link (x along the link) and
/// the arc length of contact. Pass a previous solution's state to warm-start the next frame.
struct LoadState {
  double force_x = 0.0;  ///< axial component [N] (zero for the model's normal load)
  double force_y = 0.0;  ///< [N]
  double force_z = 0.0;  ///< [N]
  double arc_length = 0.0;  ///< [m]
};

/// Base signals in the whisker-centred frame (spec §2.4, Fig. 3b).
struct WhiskerFrameSignals {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< (Fx, Fy, Fz) [N]
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  ///< (Mx, My, Mz) [N·m]
  double FT = 0.0;  ///< transverse force sqrt(Fy^2 + Fz^2) [N]
  double MB = 0.0;  ///< bending moment sqrt(My^2 + Mz^2) [N·m]
  double FD = 0.0;  ///< direction atan2(Fz, Fy) [rad]
  double MD = 0.0;  ///< direction atan2(Mz, My) [rad]
};

struct Solution {
  Status status = Status::not_converged;
  std::string message;
  double force_magnitude = 0.0;  ///< |F| [N]
  double arc_length = 0.0;       ///< s_applied [m]
  double angle = 0.0;            ///< direction of F about the loaded link's axis, atan2(F_z, F_y) [rad]
  Eigen::Vector3d contact_point = Eigen::Vector3d::Zero();  ///< [m], world
  /// Force the whisker transmits to the follicle: the contact force, world [N] (as the published model).
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  /// Moment of the contact force about the base, world [N·m].
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  WhiskerFrameSignals whisker_frame;
  std::optional<double> normal_force;  ///< component of F normal to the edge [N] (edge modes)
  std::optional<double> edge_force;    ///< component of F along the edge direction [N] (edge modes)
  double residual = 0.0;               ///< final residual [m]
  int iterations = 0;
  std::vector<Eigen::Vector3d> shape;  ///< deflected nodes, base to tip, world [m]
  std::optional<double> other_root_arc_length;  ///< another root exists at this arc length [m]
  LoadState state;                     ///< the solved unknowns, for warm starts
};

}  // namespace vibrissa
