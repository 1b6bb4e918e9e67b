#pragma once
// A straight edge of an object in the world at one frame: what a whisker touches in the edge modes (spec
// §2.1). Pegs, prism edges and straight edges are all edge segments (array/objects.hpp builds them); a
// trial's peg line is an infinite one.
#include <limits>

#include <Eigen/Core>

#include "vibrissa/solve/options.hpp"

namespace vibrissa {

/// Points p0 + λ·direction, λ in [0, length] (finite) or all λ (length = +inf).
struct EdgeSegment {
  Eigen::Vector3d p0 = Eigen::Vector3d::Zero();            ///< [m]
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();    ///< unit
  double length = std::numeric_limits<double>::infinity();  ///< [m]
  /// A unit vector normal to `direction`, fixed to the object: with direction × normal it spans the plane in
  /// which contact onset is tested (contact/crossing.hpp), so that test moves rigidly with the object.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();

  [[nodiscard]] bool finite() const { return length < std::numeric_limits<double>::infinity(); }
  [[nodiscard]] bool contains(double lambda, double slack = 0.0) const {
    return !finite() || (lambda >= -slack && lambda <= length + slack);
  }
  /// Position of a point along the edge from p0 [m].
  [[nodiscard]] double coordinate(const Eigen::Vector3d& p_W) const { return (p_W - p0).dot(direction); }
  /// The solver's infinite line through this edge.
  [[nodiscard]] Edge line() const { return Edge{p0, direction}; }
};

/// The infinite edge segment along a solver Edge (direction normalised, a fixed normal chosen); validates it.
EdgeSegment infinite_segment(const Edge& edge);

}  // namespace vibrissa
