#pragma once
// A cylinder (a peg with a radius): the points at `radius` from the axis through `point` along `axis`. Infinite,
// or `length` long from `point` along the axis with flat caps (then its rims are edges).
#include <limits>

#include "vibrissa/objects/shape.hpp"

namespace vibrissa {

class Cylinder final : public Shape {
 public:
  /// radius >= 0 (0: the axis line itself, an edge; only with an infinite length), length > 0 or +inf.
  /// Throws std::invalid_argument naming the field.
  Cylinder(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double radius,
           double length = std::numeric_limits<double>::infinity());
  [[nodiscard]] SurfacePoint nearest(const Eigen::Vector3d& p) const override;
  [[nodiscard]] Bounds bounds() const override;
  [[nodiscard]] std::optional<LineCore> line_core() const override;
  [[nodiscard]] ShapeDescription describe() const override;
  [[nodiscard]] bool finite() const { return length_ < std::numeric_limits<double>::infinity(); }
  [[nodiscard]] const Eigen::Vector3d& point() const { return point_; }
  [[nodiscard]] const Eigen::Vector3d& axis() const { return axis_; }
  [[nodiscard]] double radius() const { return radius_; }
  [[nodiscard]] double length() const { return length_; }

 private:
  Eigen::Vector3d point_, axis_;
  double radius_, length_;
};

}  // namespace vibrissa
