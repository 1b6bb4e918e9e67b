#pragma once
// Rotation of a vector by a rotation vector (exact exponential map), templated on the scalar.
#include <cmath>

#include "vibrissa/core/dual.hpp"
#include "vibrissa/core/small_vector.hpp"

namespace vibrissa {

namespace detail {

/// Rotate v by the rotation vector w (exact exponential map), given precomputed coefficients.
template <class S>
inline V3<S> rotate(const V3<S>& w, const S& a, const S& b, const V3<S>& v) {
  const V3<S> wv = cross(w, v);
  return v + a * wv + b * cross(w, wv);
}

/// Coefficients sin(t)/t and (1 - cos t)/t^2 of the Rodrigues formula, smooth at t = 0.
template <class S>
inline void rodrigues_coefficients(const S& t2, S& a, S& b) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  if (value_of(t2) < 1e-6) {
    a = S(1.0) - t2 * (S(1.0 / 6.0) - t2 * (S(1.0 / 120.0) - t2 * S(1.0 / 5040.0)));
    b = S(0.5) - t2 * (S(1.0 / 24.0) - t2 * (S(1.0 / 720.0) - t2 * S(1.0 / 40320.0)));
  } else {
    const S t = sqrt(t2);
    a = sin(t) / t;
    b = (S(1.0) - cos(t)) / t2;
  }
}

}  // namespace detail

}  // namespace vibrissa
