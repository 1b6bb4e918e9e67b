#pragma once
// A plane (a wall): the points with (p - point) . normal = 0; the outside is the side the normal points to.
#include "vibrissa/objects/shape.hpp"

namespace vibrissa {

class Plane final : public Shape {
 public:
  /// `normal` of any non-zero length (normalised). Throws std::invalid_argument naming the field.
  Plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
  [[nodiscard]] SurfacePoint nearest(const Eigen::Vector3d& p) const override;
  [[nodiscard]] double signed_distance(const Eigen::Vector3d& p) const override { return (p - point_).dot(normal_); }
  [[nodiscard]] Bounds bounds() const override { return {}; }
  [[nodiscard]] ShapeDescription describe() const override;
  [[nodiscard]] const Eigen::Vector3d& point() const { return point_; }
  [[nodiscard]] const Eigen::Vector3d& normal() const { return normal_; }

 private:
  Eigen::Vector3d point_, normal_;
};

}  // namespace vibrissa
