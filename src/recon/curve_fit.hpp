#pragma once
// Smooth 3D curve through noisy points (private to src/recon): a clamped cubic B-spline with `segments` equal
// knot intervals of a curve parameter (chord length, corrected to the foot points), fitted by penalised
// weighted least squares (integrated squared third derivative, weight by generalised cross-validation with
// the trace counted twice) with Tukey biweights (iteratively reweighted), then resampled at equal arc length
// with core/rest_curve.hpp. Unlike one global polynomial, the spline is local: the jump in the curvature's
// derivative at a contact point does not tilt the base tangent.
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace vibrissa::recon {

struct FittedCurve {
  std::vector<Eigen::Vector3d> nodes;  ///< nodes + 1 points equally spaced in arc length, base first
  Eigen::Vector3d tangent0;            ///< unit tangent at the base
  std::vector<Eigen::Vector3d> dense;  ///< dense_links + 1 points equally spaced in arc length (reprojection)
};
/// Segments of FittedCurve::dense: on a 30 mm whisker 0.19 mm each, whose chords depart from the curve by
/// well under 0.01 px at the validation's 125 um per pixel.
inline constexpr int dense_links = 160;
/// nullopt when fewer than segments + 4 points carry weight (the points must be ordered base to tip).
std::optional<FittedCurve> fit_curve(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& weights,
                                     int segments, int nodes);

}  // namespace vibrissa::recon
