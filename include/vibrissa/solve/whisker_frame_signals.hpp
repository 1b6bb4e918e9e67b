#pragma once
// The base signals of spec §2.4 from the force and moment on the follicle in the whisker frame: one place for
// every solve, the array's frames and the dynamics' time series.
#include <cmath>

#include <Eigen/Core>

#include "vibrissa/solve/solution.hpp"

namespace vibrissa {

/// F_T = sqrt(Fy^2 + Fz^2), M_B = sqrt(My^2 + Mz^2), F_D = atan2(Fz, Fy), M_D = atan2(Mz, My) (spec §2.4) of the
/// force `F_B` [N] and moment `M_B` [N·m] on the follicle, whisker frame.
inline WhiskerFrameSignals whisker_frame_signals(const Eigen::Vector3d& F_B, const Eigen::Vector3d& M_B) {
  WhiskerFrameSignals s;
  s.force = F_B;
  s.moment = M_B;
  s.FT = std::hypot(F_B.y(), F_B.z());
  s.MB = std::hypot(M_B.y(), M_B.z());
  s.FD = std::atan2(F_B.z(), F_B.y());
  s.MD = std::atan2(M_B.z(), M_B.y());
  return s;
}

}  // namespace vibrissa
