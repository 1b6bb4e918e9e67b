#include "vibrissa/objects/plane.hpp"

#include "surface_math.hpp"
#include "vibrissa/core/checks.hpp"

namespace vibrissa {

Plane::Plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) : Shape("plane"), point_(point) {
  require_finite(point, "object.point");
  normal_ = unit_direction(normal, "object.normal");
}

SurfacePoint Plane::nearest(const Eigen::Vector3d& p) const {
  SurfacePoint out;
  out.signed_distance = (p - point_).dot(normal_);
  out.closest = p - out.signed_distance * normal_;
  out.normal = normal_;
  return out;  // a flat face: d normal / dp = 0
}

ShapeDescription Plane::describe() const {
  return {"plane", {{"point", detail::values_of(point_)}, {"normal", detail::values_of(normal_)}}, ""};
}

}  // namespace vibrissa
