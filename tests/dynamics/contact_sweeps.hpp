#pragma once
// The whisker and base sweeps of the contact-in-motion tests (test_contact_dynamics.cpp: lines,
// test_surface_dynamics.cpp: surfaces).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "vibrissa/core/pose.hpp"
#include "vibrissa/core/whisker.hpp"
#include "vibrissa/dynamics/simulate.hpp"

namespace vibrissa::dynamics::sweeps {

inline Whisker curved_whisker(int links) {
  WhiskerProperties p;
  p.links = links;
  return Whisker::from_parabola(0.03, 15.0, p);
}

/// Protraction about world z from 0 to `angle` over `duration` with zero velocity at both ends:
/// theta(t) = angle (t / T - sin(2 pi t / T) / (2 pi)), held after T.
inline BaseTrajectory smooth_sweep(double angle, double duration) {
  return trajectory_from_placements([=](double t) {
    const double x = std::clamp(t / duration, 0.0, 1.0);
    Pose pose;
    pose.theta = angle * (x - std::sin(2.0 * std::numbers::pi * x) / (2.0 * std::numbers::pi));
    return Placement(pose);
  });
}

/// Protraction about world z to `angle` and back over `duration`: theta(t) = angle (1 - cos(2 pi t / T)) / 2.
inline BaseTrajectory sweep_there_and_back(double angle, double duration) {
  return trajectory_from_placements([=](double t) {
    const double x = std::clamp(t / duration, 0.0, 1.0);
    Pose pose;
    pose.theta = 0.5 * angle * (1.0 - std::cos(2.0 * std::numbers::pi * x));
    return Placement(pose);
  });
}

/// The rest whisker's centre-line point at arc length s (world frame: the rest placement is the identity).
inline Eigen::Vector3d rest_point(const Whisker& w, double s) {
  const auto& arc = w.node_arc_lengths();
  std::size_t i = 0;
  while (i + 2 < arc.size() && arc[i + 1] < s) ++i;
  const double u = (s - arc[i]) / (arc[i + 1] - arc[i]);
  return w.rest_nodes_B()[i] + u * (w.rest_nodes_B()[i + 1] - w.rest_nodes_B()[i]);
}

}  // namespace vibrissa::dynamics::sweeps
