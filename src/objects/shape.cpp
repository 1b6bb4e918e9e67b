#include "vibrissa/objects/shape.hpp"

#include <cmath>

namespace vibrissa {

std::string_view to_string(SurfaceFeature feature) {
  switch (feature) {
    case SurfaceFeature::face: return "face";
    case SurfaceFeature::edge: return "edge";
    case SurfaceFeature::vertex: return "vertex";
  }
  return "face";
}

double Bounds::distance(const Eigen::Vector3d& p) const {
  double d2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double below = lower[i] - p[i], above = p[i] - upper[i];
    const double out = std::max({below, above, 0.0});
    d2 += out * out;
  }
  return std::sqrt(d2);
}

SurfacePoint to_world(const SurfacePoint& q, const ObjectPose& X) {
  SurfacePoint out = q;
  out.closest = X.to_world(q.closest);
  out.normal = X.R_WO * q.normal;
  out.normal_derivative = X.R_WO * q.normal_derivative * X.R_WO.transpose();
  out.edge_direction = X.R_WO * q.edge_direction;
  return out;
}

SurfacePoint PlacedShape::nearest_W(const Eigen::Vector3d& p_W) const {
  return to_world(shape->nearest(X_WO.to_object(p_W)), X_WO);
}

}  // namespace vibrissa
