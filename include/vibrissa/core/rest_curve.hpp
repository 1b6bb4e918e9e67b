#pragma once
// Rest-shape construction: a smooth curve resampled into N+1 nodes equally spaced in arc length, and the
// whisker-centred frame of spec §2.1 (x along emergence, x-y = best-fit plane of the proximal 70 % of arc
// length, concave toward +y, z by the right-hand rule).
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace vibrissa {

/// Nodes at arc lengths i L / N of a parametric curve c(t), t in [0, t_end], with derivative dc(t).
std::vector<Eigen::Vector3d> resample_by_arc_length(const std::function<Eigen::Vector3d(double)>& c,
                                                    const std::function<Eigen::Vector3d(double)>& dc,
                                                    double t_end, int links, double* total_length = nullptr);

/// Nodes (N+1) of the clamped cubic spline (end slopes from 4-point interpolation) through `points` (chord-length parametrised), equally spaced in
/// arc length; `tangent0` receives the unit tangent of the spline at the base.
std::vector<Eigen::Vector3d> resample_points(const std::vector<Eigen::Vector3d>& points, int links,
                                             Eigen::Vector3d* tangent0 = nullptr);

/// Planar curve y = A x^3 + B x^2 of arc length `length`, N+1 nodes in its own frame.
std::vector<Eigen::Vector3d> planar_polynomial_nodes(double length, double A, double B, int links);

/// R whose columns are the whisker-frame axes (x, y, z) expressed in the frame of `nodes`, for nodes that
/// start at the base; `tangent0` is the emergence direction.
Eigen::Matrix3d whisker_frame(const std::vector<Eigen::Vector3d>& nodes, const Eigen::Vector3d& tangent0);

}  // namespace vibrissa
