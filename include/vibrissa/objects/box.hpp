#pragma once
// A box: centre, half extents along its own axes, and the rotation whose columns are those axes.
#include "vibrissa/objects/shape.hpp"

namespace vibrissa {

class Box final : public Shape {
 public:
  /// half_extents all positive; `rotation` orthonormal with determinant +1 (to 1e-9). Throws
  /// std::invalid_argument naming the field.
  Box(const Eigen::Vector3d& centre, const Eigen::Vector3d& half_extents,
      const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity());
  [[nodiscard]] SurfacePoint nearest(const Eigen::Vector3d& p) const override;
  [[nodiscard]] Bounds bounds() const override;
  [[nodiscard]] bool needs_thickness() const override { return true; }
  [[nodiscard]] ShapeDescription describe() const override;
  [[nodiscard]] const Eigen::Vector3d& centre() const { return centre_; }
  [[nodiscard]] const Eigen::Vector3d& half_extents() const { return half_; }
  [[nodiscard]] const Eigen::Matrix3d& rotation() const { return R_; }

 private:
  Eigen::Vector3d centre_, half_;
  Eigen::Matrix3d R_;
};

/// Throws std::invalid_argument naming `field` unless R is a proper rotation (orthonormal to 1e-9, det +1).
void require_rotation(const Eigen::Matrix3d& R, std::string_view field);

}  // namespace vibrissa
