#include "vibrissa/objects/cylinder.hpp"

#include <algorithm>
#include <cmath>

#include "surface_math.hpp"
#include "vibrissa/core/checks.hpp"

namespace vibrissa {

Cylinder::Cylinder(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double radius, double length)
    : Shape("cylinder"), point_(point), radius_(radius), length_(length) {
  require_finite(point, "object.point");
  axis_ = unit_direction(axis, "object.axis");
  require_finite(radius, "object.radius");
  if (radius < 0.0) invalid_input("object.radius must be >= 0, got " + format_value(radius));
  if (std::isnan(length) || !(length > 0.0))
    invalid_input("object.length must be positive (omit it for an infinite cylinder), got " + format_value(length));
  if (finite() && radius == 0.0)
    invalid_input("object.radius must be positive for a finite cylinder (an infinite one of radius 0 is an edge)");
}

SurfacePoint Cylinder::nearest(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d d = p - point_;
  const double z = d.dot(axis_);
  const Eigen::Vector3d radial = d - z * axis_;
  const double rho = radial.norm();
  const Eigen::Vector3d u = rho > 0.0 ? Eigen::Vector3d(radial / rho) : detail::any_normal(axis_);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  auto side = [&] {
    SurfacePoint s;
    s.signed_distance = rho - radius_;
    s.normal = u;
    s.closest = point_ + z * axis_ + radius_ * u;
    // The distance field of a line, offset: (I - u u^T - a a^T) / rho.
    if (rho > 0.0) s.normal_derivative = (I - u * u.transpose() - axis_ * axis_.transpose()) / rho;
    return s;
  };
  if (!finite()) return side();
  auto cap = [&](bool top, double distance) {  // distance > 0 outside
    SurfacePoint s;
    s.normal = top ? axis_ : Eigen::Vector3d(-axis_);
    s.signed_distance = distance;
    s.closest = p - distance * s.normal;
    return s;
  };
  const bool within = z >= 0.0 && z <= length_;
  if (within && rho <= radius_) {  // inside: the nearest of side and caps
    const double to_side = radius_ - rho, to_bottom = z, to_top = length_ - z;
    if (to_side <= to_bottom && to_side <= to_top) return side();
    return to_top <= to_bottom ? cap(true, -to_top) : cap(false, -to_bottom);
  }
  if (within) return side();
  const bool top = z > length_;
  if (rho <= radius_) return cap(top, top ? z - length_ : -z);
  // Outside beyond a cap and the side: the nearest point is on the rim circle (an edge).
  const double zc = top ? length_ : 0.0;
  const Eigen::Vector3d q = point_ + zc * axis_ + radius_ * u;
  const Eigen::Matrix3d J = radius_ * (I - u * u.transpose() - axis_ * axis_.transpose()) / rho;
  SurfacePoint s = detail::surface_point(p, q, J, 1.0, u, SurfaceFeature::edge);
  s.edge_direction = axis_.cross(u);
  return s;
}

Bounds Cylinder::bounds() const {
  if (!finite()) return {};
  Bounds b;
  const Eigen::Vector3d a = point_, c = point_ + length_ * axis_;
  for (int i = 0; i < 3; ++i) {
    const double half = radius_ * std::sqrt(std::max(0.0, 1.0 - axis_[i] * axis_[i]));  // disc extent along i
    b.lower[i] = std::min(a[i], c[i]) - half;
    b.upper[i] = std::max(a[i], c[i]) + half;
  }
  return b;
}

std::optional<LineCore> Cylinder::line_core() const {
  if (finite()) return std::nullopt;
  return LineCore{point_, axis_, radius_};
}

ShapeDescription Cylinder::describe() const {
  ShapeDescription d{"cylinder",
                     {{"point", detail::values_of(point_)}, {"axis", detail::values_of(axis_)}, {"radius", {radius_}}},
                     ""};
  if (finite()) d.values.push_back({"length", {length_}});
  return d;
}

}  // namespace vibrissa
