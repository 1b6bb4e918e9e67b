#pragma once
// Reprojection error of a fitted 3D curve (private to src/recon; docs/reconstruction.md, step 4): the distance
// of each tracked pixel to the curve projected into its view (with distortion). Pairing a point with its
// epipolar partner and reprojecting that pair measures nothing (such a pair always reprojects exactly); the
// distance to the projected curve includes the pixel noise, wild points, and calibration errors where they
// show (the ends, and every point once a third view sees it).
#include <vector>

#include <Eigen/Core>

#include "vibrissa/recon/camera.hpp"

namespace vibrissa::recon {

/// The curve `dense_W` (a fine polyline, base first) projected by `camera` [px].
std::vector<Eigen::Vector2d> project_curve(const std::vector<Eigen::Vector3d>& dense_W, const Camera& camera);

/// Distance [px] of `pixel` to the projected polyline `curve_px` (nearest point of any segment).
double distance_to_curve(const std::vector<Eigen::Vector2d>& curve_px, const Eigen::Vector2d& pixel);

/// Distance [px] of `pixel` across the projected polyline `curve_px`: as distance_to_curve, but beyond an end
/// the distance to the line of the end segment. For a pixel found by intersecting an epipolar line with a
/// view's curve, whose position along the curve carries the other view's noise divided by the sine of the
/// angle between line and curve (several pixels where they meet at a grazing angle) and only its position
/// across the curve is measured.
double distance_across_curve(const std::vector<Eigen::Vector2d>& curve_px, const Eigen::Vector2d& pixel);

}  // namespace vibrissa::recon
