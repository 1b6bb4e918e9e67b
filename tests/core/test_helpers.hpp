#pragma once
// Shared fixtures for the core and solve tests: whiskers with closed-form answers.
#include <cmath>
#include <stdexcept>
#include <string>
#include <numbers>

#include "vibrissa/core/whisker.hpp"
#include "vibrissa/solve/options.hpp"

namespace vibrissa::test {

/// Straight uniform rod (taper ratio 1), clamped: the textbook cantilever.
inline Whisker uniform_rod(int links, Scheme scheme = Scheme::second_order, double length = 0.05) {
  WhiskerProperties p;
  p.links = links;
  p.taper_ratio = 1.0;
  p.scheme = scheme;
  p.base = BaseJoint::rigid;
  return Whisker::from_parabola(length, 0.0, p);
}

/// A realistic tapered, curved whisker (spec §2.1 material, 40 mm, y = 12 x^2).
inline Whisker rat_whisker(int links = 100, const Pose& pose = {}) {
  WhiskerProperties p;
  p.links = links;
  return Whisker::from_parabola(0.040, 12.0, p, pose);
}

/// The message of the std::invalid_argument that `f()` throws (a marker string if it throws none).
template <class F>
inline std::string invalid_message(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "<no std::invalid_argument>";
}

inline double deg(double d) { return d * std::numbers::pi / 180.0; }

/// A vertical peg (an edge along world z) through (x, y, 0).
inline Edge vertical_peg(double x, double y) {
  Edge e;
  e.point = {x, y, 0.0};
  e.direction = {0.0, 0.0, 1.0};
  return e;
}

/// The 3D pose of the solve tests and benchmarks: theta = phi = 10 deg, zeta = 30 deg.
inline Pose tilted_pose() {
  Pose p;
  p.theta = deg(10);
  p.phi = deg(10);
  p.zeta = deg(30);
  return p;
}

}  // namespace vibrissa::test
