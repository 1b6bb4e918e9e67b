#pragma once
#include <optional>

#include <Eigen/Core>

namespace vibrissa {

struct SolveOptions {
  double tolerance = 1e-12;       ///< contact residual to reach [m] (and the edge-parallel force, scaled alike)
  int max_iterations = 100;       ///< Levenberg-Marquardt iterations per attempt
  bool compute_shape = true;      ///< fill Solution::shape_W (costs one extra O(N) pass)
  bool find_other_roots = false;  ///< probe for a second root and report it (cold solves only; costs extra solves)
};

/// Throws std::invalid_argument naming the field unless tolerance lies in (0, 1e-3] and max_iterations in
/// [1, limits::max_iterations]. Every solve checks its options.
void validate(const SolveOptions& options);

/// A straight edge: the infinite line through `point` along `direction` (world frame). A peg is one edge.
struct Edge {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();            ///< [m]
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();       ///< any non-zero length
};

void validate(const Edge& edge);

}  // namespace vibrissa
