#pragma once
// Fig. 2b (spec §2.3): mean over the simulated nodes from the base to the contact of each node's shortest
// Euclidean distance to the tracked (polyline) whisker.
#include <vector>

#include <Eigen/Core>

namespace vibrissa::trial {

/// Distance from p to the polyline through `curve` (>= 1 point).
double distance_to_polyline(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& curve);

/// Mean distance [m] of the simulated nodes with arc length <= s_applied to the tracked shape; NaN if the
/// tracked shape is empty or no node qualifies.
double mean_shape_error(const std::vector<Eigen::Vector3d>& simulated_nodes_W, const std::vector<double>& node_arc,
                        double s_applied, const std::vector<Eigen::Vector3d>& tracked_W);

}  // namespace vibrissa::trial
