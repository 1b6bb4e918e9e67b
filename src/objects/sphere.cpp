#include "vibrissa/objects/sphere.hpp"

#include "surface_math.hpp"
#include "vibrissa/core/checks.hpp"

namespace vibrissa {

Sphere::Sphere(const Eigen::Vector3d& centre, double radius) : Shape("sphere"), centre_(centre), radius_(radius) {
  require_finite(centre, "object.centre");
  require_positive(radius, "object.radius");
}

SurfacePoint Sphere::nearest(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d v = p - centre_;
  const double rho = v.norm();
  SurfacePoint out;
  out.normal = rho > 0.0 ? Eigen::Vector3d(v / rho) : Eigen::Vector3d::UnitZ();
  out.signed_distance = rho - radius_;
  out.closest = centre_ + radius_ * out.normal;
  // The distance field of a point, offset: d normal / dp = (I - n n^T) / |p - centre| (at the centre: 0).
  if (rho > 0.0) out.normal_derivative = (Eigen::Matrix3d::Identity() - out.normal * out.normal.transpose()) / rho;
  return out;
}

Bounds Sphere::bounds() const {
  return {centre_ - Eigen::Vector3d::Constant(radius_), centre_ + Eigen::Vector3d::Constant(radius_)};
}

ShapeDescription Sphere::describe() const {
  return {"sphere", {{"centre", detail::values_of(centre_)}, {"radius", {radius_}}}, ""};
}

}  // namespace vibrissa
