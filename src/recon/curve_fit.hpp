#pragma once
// Smooth 3D curve through noisy points (private to src/recon): a polynomial in normalised chord length,
// fitted by weighted least squares with Tukey biweights (iteratively reweighted), then resampled at equal arc
// length with core/rest_curve.hpp.
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace vibrissa::recon {

struct FittedCurve {
  std::vector<Eigen::Vector3d> nodes;  ///< nodes + 1 points equally spaced in arc length, base first
  Eigen::Vector3d tangent0;            ///< unit tangent at the base
};
/// nullopt when fewer than degree + 2 points carry weight.
std::optional<FittedCurve> fit_curve(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& weights,
                                     int degree, int nodes);

}  // namespace vibrissa::recon
