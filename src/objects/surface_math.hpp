#pragma once
// The query's numbers from a nearest point q(p) and its derivative J = dq/dp: with u = (p - q)/|p - q|,
//   signed distance = sign |p - q|,  normal = sign u,  d normal/dp = sign (I - u u^T)(I - J) / |p - q|.
// A flat face has J = I - n n^T (so d normal/dp = 0), a straight edge J = d d^T, a vertex J = 0.
#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "vibrissa/objects/shape.hpp"

namespace vibrissa::detail {

/// `sign` = +1 outside, -1 inside. `fallback_normal` is used when p is on the surface (|p - q| = 0).
inline SurfacePoint surface_point(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Matrix3d& J,
                                  double sign, const Eigen::Vector3d& fallback_normal, SurfaceFeature feature) {
  SurfacePoint out;
  out.closest = q;
  out.feature = feature;
  const Eigen::Vector3d v = p - q;
  const double d = v.norm();
  if (!(d > 0.0)) {
    out.normal = fallback_normal;
    out.signed_distance = 0.0;
    return out;
  }
  const Eigen::Vector3d u = v / d;
  out.normal = sign * u;
  out.signed_distance = sign * d;
  out.normal_derivative = sign * (Eigen::Matrix3d::Identity() - u * u.transpose()) * (Eigen::Matrix3d::Identity() - J) / d;
  return out;
}

/// A unit vector normal to the unit vector d (deterministic).
inline Eigen::Vector3d any_normal(const Eigen::Vector3d& d) {
  const Eigen::Vector3d helper = std::abs(d.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (helper - helper.dot(d) * d).normalized();
}

inline std::vector<double> values_of(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace vibrissa::detail
