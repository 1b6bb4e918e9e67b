#pragma once
// A 3-vector templated on its scalar, so the forward model runs on doubles and on dual numbers
// (for exact Jacobians) with the same code. Deliberately tiny: no allocation, no expression templates.
#include <Eigen/Core>

namespace vibrissa {

template <class S>
struct V3 {
  S x{}, y{}, z{};
  V3() = default;
  V3(S x_, S y_, S z_) : x(x_), y(y_), z(z_) {}
  explicit V3(const Eigen::Vector3d& v)
    requires(!std::is_same_v<S, double>)
      : x(v.x()), y(v.y()), z(v.z()) {}
  V3(const Eigen::Vector3d& v)  // NOLINT(google-explicit-constructor): doubles convert freely
    requires std::is_same_v<S, double>
      : x(v.x()), y(v.y()), z(v.z()) {}

  friend V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend V3 operator*(const S& k, const V3& a) { return {k * a.x, k * a.y, k * a.z}; }
  V3& operator+=(const V3& b) { x += b.x; y += b.y; z += b.z; return *this; }
};

template <class S>
inline S dot(const V3<S>& a, const V3<S>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

template <class S>
inline V3<S> cross(const V3<S>& a, const V3<S>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// Product of a constant (double) rotation matrix with a templated vector.
template <class S>
inline V3<S> mul(const Eigen::Matrix3d& R, const V3<S>& v) {
  return {R(0, 0) * v.x + R(0, 1) * v.y + R(0, 2) * v.z, R(1, 0) * v.x + R(1, 1) * v.y + R(1, 2) * v.z,
          R(2, 0) * v.x + R(2, 1) * v.y + R(2, 2) * v.z};
}

/// A 3x3 matrix templated on its scalar (row-major), for rotations built from templated angles.
template <class S>
struct Mat3 {
  S m[9];
  [[nodiscard]] V3<S> operator*(const V3<S>& v) const {
    return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
            m[6] * v.x + m[7] * v.y + m[8] * v.z};
  }
};

/// Product of a constant (double) matrix with a templated one: Q R.
template <class S>
inline Mat3<S> mul(const Eigen::Matrix3d& Q, const Mat3<S>& R) {
  Mat3<S> P;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P.m[3 * i + j] = Q(i, 0) * R.m[j] + Q(i, 1) * R.m[3 + j] + Q(i, 2) * R.m[6 + j];
  return P;
}

inline Eigen::Vector3d to_eigen(const V3<double>& v) { return {v.x, v.y, v.z}; }

}  // namespace vibrissa
