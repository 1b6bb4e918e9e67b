#pragma once
// Geometry of a placed rest whisker relative to a straight edge: where it is nearest the edge, and in which
// direction it moves into it. Used to start contacts and to interpret them.
#include <Eigen/Core>

#include "vibrissa/core/whisker.hpp"
#include "vibrissa/solve/options.hpp"

namespace vibrissa {

/// Height of a point along the edge [m]: (p - edge.point) · d̂ (for a vertical peg, the world z of contact).
double height_along_edge(const Edge& edge, const Eigen::Vector3d& p_W);

struct NearestOnWhisker {
  double arc_length = 0.0;       ///< s of the rest-whisker point nearest the line [m]
  Eigen::Vector3d on_whisker_W;  ///< that point
  Eigen::Vector3d on_edge_W;     ///< its nearest point on the line ("touch point")
  double distance = 0.0;         ///< [m]
};
/// Nearest approach of the rest (undeflected) whisker polyline, placed at X_WB, to the edge line.
NearestOnWhisker nearest_rest_point(const Whisker& whisker, const Placement& X_WB, const Edge& edge);

/// Unit direction, normal to the edge, in which the rest whisker point at arc length s moves from placement
/// `before` to placement `after` (the approach direction of a contact onset). Zero if it does not move.
Eigen::Vector3d approach_direction(const Whisker& whisker, const Placement& before, const Placement& after,
                                   double arc_length, const Edge& edge);

}  // namespace vibrissa
