#include "vibrissa/objects/box.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "surface_math.hpp"
#include "vibrissa/core/checks.hpp"

namespace vibrissa {

void require_rotation(const Eigen::Matrix3d& R, std::string_view field) {
  if (!R.allFinite()) invalid_input(std::string(field) + " must be finite");
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > 1e-9 || R.determinant() < 0.0)
    invalid_input(std::string(field) + " must be a rotation matrix (orthonormal rows, determinant +1); R^T R - I is " +
                  format_value(off) + " off");
}

Box::Box(const Eigen::Vector3d& centre, const Eigen::Vector3d& half_extents, const Eigen::Matrix3d& rotation)
    : Shape("box"), centre_(centre), half_(half_extents), R_(rotation) {
  require_finite(centre, "object.centre");
  for (int i = 0; i < 3; ++i) require_positive(half_extents[i], "object.half_extents[" + std::to_string(i) + "]");
  require_rotation(rotation, "object.rotation");
}

SurfacePoint Box::nearest(const Eigen::Vector3d& p_W) const {
  const Eigen::Vector3d q = R_.transpose() * (p_W - centre_);  // in the box's axes
  int clamped = 0;
  Eigen::Vector3d c = q;
  Eigen::Matrix3d J = Eigen::Matrix3d::Identity();  // d closest / d q: 1 along free axes, 0 along clamped ones
  int free_axis = 0;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(q[i]) > half_[i]) {
      c[i] = std::copysign(half_[i], q[i]);
      J(i, i) = 0.0;
      ++clamped;
    } else {
      free_axis = i;
    }
  }
  SurfacePoint s;
  if (clamped == 0) {  // inside: the nearest face
    int axis = 0;
    double depth = half_[0] - std::abs(q[0]);
    for (int i = 1; i < 3; ++i)
      if (half_[i] - std::abs(q[i]) < depth) {
        depth = half_[i] - std::abs(q[i]);
        axis = i;
      }
    const double sign = q[axis] >= 0.0 ? 1.0 : -1.0;
    s.signed_distance = -depth;
    s.normal = sign * Eigen::Vector3d::Unit(axis);
    s.closest = q;
    s.closest[axis] = sign * half_[axis];
  } else {
    const SurfaceFeature f = clamped == 1 ? SurfaceFeature::face : (clamped == 2 ? SurfaceFeature::edge : SurfaceFeature::vertex);
    s = detail::surface_point(q, c, J, 1.0, Eigen::Vector3d::UnitZ(), f);
    if (f == SurfaceFeature::edge) s.edge_direction = Eigen::Vector3d::Unit(free_axis);
  }
  // Back to the box's frame O (its parameters' frame).
  s.closest = centre_ + R_ * s.closest;
  s.normal = R_ * s.normal;
  s.normal_derivative = R_ * s.normal_derivative * R_.transpose();
  s.edge_direction = R_ * s.edge_direction;
  return s;
}

Bounds Box::bounds() const {
  const Eigen::Vector3d extent = R_.cwiseAbs() * half_;
  return {centre_ - extent, centre_ + extent};
}

ShapeDescription Box::describe() const {
  std::vector<double> rotation;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rotation.push_back(R_(i, j));
  return {"box",
          {{"centre", detail::values_of(centre_)}, {"half_extents", detail::values_of(half_)}, {"rotation", rotation}},
          ""};
}

}  // namespace vibrissa
