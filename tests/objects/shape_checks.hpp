#pragma once
// Checks every shape's query must pass at a point: the distance field's gradient is the normal, the normal's
// derivative is dn/dp (both against central differences), and the closest point is at |signed distance| along
// the normal.
#include <gtest/gtest.h>

#include "vibrissa/objects/shape.hpp"

namespace vibrissa::testing {

inline void expect_consistent_query(const Shape& shape, const Eigen::Vector3d& p, double fd_tolerance = 1e-6) {
  const SurfacePoint q = shape.nearest(p);
  SCOPED_TRACE("p = (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " + std::to_string(p.z()) + ")");
  EXPECT_NEAR(q.normal.norm(), 1.0, 1e-12);
  EXPECT_NEAR(shape.signed_distance(p), q.signed_distance, 1e-15);
  // The nearest point lies |d| along the normal (outside: p = closest + d n).
  EXPECT_LT((p - q.closest - q.signed_distance * q.normal).norm(), 1e-12);
  EXPECT_NEAR(shape.signed_distance(q.closest), 0.0, 1e-12);
  const double h = 1e-7;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(i);
    const SurfacePoint a = shape.nearest(p + e), b = shape.nearest(p - e);
    if (a.feature != q.feature || b.feature != q.feature) continue;  // straddles a crease of the field
    EXPECT_NEAR((a.signed_distance - b.signed_distance) / (2 * h), q.normal[i], fd_tolerance) << "gradient " << i;
    const Eigen::Vector3d dn = (a.normal - b.normal) / (2 * h);
    const double scale = std::max(1.0, q.normal_derivative.cwiseAbs().maxCoeff());
    EXPECT_LT((dn - q.normal_derivative.col(i)).cwiseAbs().maxCoeff(), fd_tolerance * scale) << "dn/dp column " << i;
  }
}

}  // namespace vibrissa::testing
