#pragma once
// A sphere of radius R about a centre.
#include "vibrissa/objects/shape.hpp"

namespace vibrissa {

class Sphere final : public Shape {
 public:
  /// Throws std::invalid_argument unless the centre is finite and the radius positive.
  Sphere(const Eigen::Vector3d& centre, double radius);
  [[nodiscard]] SurfacePoint nearest(const Eigen::Vector3d& p) const override;
  [[nodiscard]] double signed_distance(const Eigen::Vector3d& p) const override { return (p - centre_).norm() - radius_; }
  [[nodiscard]] Bounds bounds() const override;
  [[nodiscard]] ShapeDescription describe() const override;
  [[nodiscard]] const Eigen::Vector3d& centre() const { return centre_; }
  [[nodiscard]] double radius() const { return radius_; }

 private:
  Eigen::Vector3d centre_;
  double radius_;
};

}  // namespace vibrissa
