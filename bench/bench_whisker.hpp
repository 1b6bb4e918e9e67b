// The whisker every engine benchmark uses (bench_solve, bench_objects, bench_dynamics): 40 mm, curvature
// 12 /m, N = 100 (default properties), posed at theta = phi = 10 deg, zeta = 30 deg.
#pragma once

#include <numbers>

#include "vibrissa/core/whisker.hpp"

namespace vibrissa::bench {

inline Whisker bench_whisker() {
  Pose pose;
  pose.theta = 10.0 * std::numbers::pi / 180.0;
  pose.phi = 10.0 * std::numbers::pi / 180.0;
  pose.zeta = 30.0 * std::numbers::pi / 180.0;
  return Whisker::from_parabola(0.040, 12.0, WhiskerProperties{}, pose);
}

}  // namespace vibrissa::bench
