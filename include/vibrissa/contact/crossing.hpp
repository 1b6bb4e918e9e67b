#pragma once
// Contact onset from the sweep of the rest whisker: between two frames the undeflected whisker crosses an
// edge when, seen along the edge (projected onto the plane normal to it), the edge's point passes from one
// side of the projected whisker polyline to the other. The test is carried out in the edge's own frame (p0;
// normal, direction × normal), so it moves rigidly with the object.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/contact/edge_segment.hpp"

namespace vibrissa {

struct Crossing {
  double tau = 0.0;              ///< fraction of the step [0, 1] at which the crossing happens (linear in time)
  double arc_length = 0.0;       ///< arc length on the rest whisker where it meets the line [m]
  double edge_coordinate = 0.0;  ///< λ of the meeting point along the edge from p0 [m]
  /// Direction in which the whisker moved into the edge, normal to the edge and to the whisker there
  /// (unit, world frame at the end of the step).
  Eigen::Vector3d approach_W = Eigen::Vector3d::Zero();
  /// The same direction in the edge's frame (normal, direction × normal), to follow a moving edge.
  Eigen::Vector2d approach_E = Eigen::Vector2d::Zero();
};

/// The earliest crossing of `edge_prev` → `edge_now` by the rest polyline `nodes_prev_W` → `nodes_now_W`
/// (same node count, base to tip; `arc` the nodes' arc lengths). With `within_extent`, a finite edge is
/// crossed only between its ends. nullopt when the whisker does not cross the edge's line.
std::optional<Crossing> find_crossing(const std::vector<Eigen::Vector3d>& nodes_prev_W,
                                      const std::vector<Eigen::Vector3d>& nodes_now_W,
                                      const std::vector<double>& arc, const EdgeSegment& edge_prev,
                                      const EdgeSegment& edge_now, bool within_extent = true);

/// A direction given in an edge's frame, in world coordinates.
Eigen::Vector3d edge_vector_to_world(const EdgeSegment& edge, const Eigen::Vector2d& v_E);

}  // namespace vibrissa
