#pragma once
// Rotation of a vector by a rotation vector (exact exponential map, spec §2.1 eq. (3): each joint turns by
// its rotation vector), templated on the scalar. Joint angles of a discretised whisker are small, so the
// coefficients of the Rodrigues formula come from their Taylor series below a switch-over angle (no sin,
// cos or sqrt); the series are truncated where the next term is below 1e-18 (relative), so they agree with
// the closed forms to rounding.
#include <cmath>

#include "vibrissa/core/dual.hpp"
#include "vibrissa/core/small_vector.hpp"

namespace vibrissa {

namespace detail {

/// Squared angle below which the series are used: |t| < 0.2 rad. The first omitted terms are
/// t^12/13! < 7e-19 (a), t^12/14! < 5e-20 (b) and t^12/15! < 3e-21 (c).
inline constexpr double rodrigues_series_limit = 0.04;
/// Below this squared angle (|t| < 0.022 rad) four terms suffice: the first omitted ones are
/// t^8/9! < 2e-19 (a) and t^8/10! < 2e-20 (b).
inline constexpr double rodrigues_short_series_limit = 5e-4;

/// Rotate v by the rotation vector w (exact exponential map), given precomputed coefficients.
template <class S>
inline V3<S> rotate(const V3<S>& w, const S& a, const S& b, const V3<S>& v) {
  const V3<S> wv = cross(w, v);
  return v + a * wv + b * cross(w, wv);
}

/// The rotation of v by w (as rotate()) in split form, v + a (w x v) + b (w (w . v) - t2 v): the two products
/// depend on w and v only, so they can be formed before the coefficients a, b are known.
template <class S>
struct RotationTerms {
  V3<S> v, cross, square;  ///< v, w x v, w (w . v) - t2 v
  RotationTerms(const V3<S>& w, const S& t2, const V3<S>& v_) : v(v_), cross(vibrissa::cross(w, v_)) {
    const S wv = dot(w, v_);
    square = V3<S>(w.x * wv - t2 * v_.x, w.y * wv - t2 * v_.y, w.z * wv - t2 * v_.z);
  }
  [[nodiscard]] V3<S> turned(const S& a, const S& b) const { return v + a * cross + b * square; }
  /// offset + the turned v, with offset + v added first (off the coefficients' path).
  [[nodiscard]] V3<S> turned(const S& a, const S& b, const V3<S>& offset) const {
    return (offset + v) + a * cross + b * square;
  }
};

/// Coefficients a = sin(t)/t and b = (1 - cos t)/t^2 of the Rodrigues formula exp([w]x) = I + a [w]x +
/// b [w]x^2 (t = |w|, t2 = t^2), smooth at t = 0.
template <class S>
inline void rodrigues_coefficients(const S& t2, S& a, S& b) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  if (value_of(t2) < rodrigues_short_series_limit) {  // |t| < 0.022 rad: the common case in a chain
    const S t4 = t2 * t2;
    a = (S(1.0) - t2 * S(1.0 / 6.0)) + t4 * (S(1.0 / 120.0) - t2 * S(1.0 / 5040.0));
    b = (S(0.5) - t2 * S(1.0 / 24.0)) + t4 * (S(1.0 / 720.0) - t2 * S(1.0 / 40320.0));
  } else if (value_of(t2) < rodrigues_series_limit) {
    // Estrin's scheme in t2, t2^2 and t2^4: the terms are independent, so the coefficients take a few
    // multiply-add latencies instead of Horner's six on every joint's critical path.
    const S t4 = t2 * t2;
    const S t8 = t4 * t4;
    a = (S(1.0) - t2 * S(1.0 / 6.0)) + t4 * (S(1.0 / 120.0) - t2 * S(1.0 / 5040.0)) +
        t8 * (S(1.0 / 362880.0) - t2 * S(1.0 / 39916800.0));
    b = (S(0.5) - t2 * S(1.0 / 24.0)) + t4 * (S(1.0 / 720.0) - t2 * S(1.0 / 40320.0)) +
        t8 * (S(1.0 / 3628800.0) - t2 * S(1.0 / 479001600.0));
  } else {
    const S t = sqrt(t2);
    a = sin(t) / t;
    b = (S(1.0) - cos(t)) / t2;
  }
}

/// c = (t - sin t)/t^3 = (1 - a)/t^2, the second coefficient of the right Jacobian of the exponential map,
/// J_r(w) = I - b [w]x + c [w]x^2, with exp(w + dw) = exp(w) exp(J_r(w) dw) to first order.
inline double right_jacobian_coefficient(double t2, double a) {
  if (t2 < rodrigues_series_limit)
    return 1.0 / 6.0 -
           t2 * (1.0 / 120.0 -
                 t2 * (1.0 / 5040.0 - t2 * (1.0 / 362880.0 - t2 * (1.0 / 39916800.0 - t2 / 6227020800.0))));
  return (1.0 - a) / t2;
}

/// exp([w]x) as a matrix from the Rodrigues coefficients: I + a [w]x + b (w w^T - |w|^2 I).
template <class S>
inline Mat3<S> rotation_matrix(const V3<S>& w, const S& a, const S& b) {
  const S xx = w.x * w.x, yy = w.y * w.y, zz = w.z * w.z;
  const S bxy = b * (w.x * w.y), bxz = b * (w.x * w.z), byz = b * (w.y * w.z);
  const S ax = a * w.x, ay = a * w.y, az = a * w.z;
  Mat3<S> R;
  R.m[0] = S(1.0) - b * (yy + zz);
  R.m[1] = bxy - az;
  R.m[2] = bxz + ay;
  R.m[3] = bxy + az;
  R.m[4] = S(1.0) - b * (xx + zz);
  R.m[5] = byz - ax;
  R.m[6] = bxz - ay;
  R.m[7] = byz + ax;
  R.m[8] = S(1.0) - b * (xx + yy);
  return R;
}

}  // namespace detail

}  // namespace vibrissa
