#pragma once
// Forward-mode dual numbers with K partial derivatives. The forward model is templated on its scalar;
// evaluating it on Dual<3> yields the exact Jacobian of the contact point with respect to the three
// unknowns of every solve (two force components and the arc length) in one pass.
#include <array>
#include <cmath>

namespace vibrissa {

template <int K>
struct Dual {
  double v = 0.0;
  std::array<double, K> d{};

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT(google-explicit-constructor): constants promote
  static Dual variable(double value, int index) {
    Dual r(value);
    r.d[static_cast<std::size_t>(index)] = 1.0;
    return r;
  }

  friend Dual operator+(const Dual& a, const Dual& b) {
    Dual r(a.v + b.v);
    for (int i = 0; i < K; ++i) r.d[i] = a.d[i] + b.d[i];
    return r;
  }
  friend Dual operator-(const Dual& a, const Dual& b) {
    Dual r(a.v - b.v);
    for (int i = 0; i < K; ++i) r.d[i] = a.d[i] - b.d[i];
    return r;
  }
  friend Dual operator-(const Dual& a) {
    Dual r(-a.v);
    for (int i = 0; i < K; ++i) r.d[i] = -a.d[i];
    return r;
  }
  friend Dual operator*(const Dual& a, const Dual& b) {
    Dual r(a.v * b.v);
    for (int i = 0; i < K; ++i) r.d[i] = a.d[i] * b.v + a.v * b.d[i];
    return r;
  }
  friend Dual operator*(double k, const Dual& a) {
    Dual r(k * a.v);
    for (int i = 0; i < K; ++i) r.d[i] = k * a.d[i];
    return r;
  }
  friend Dual operator*(const Dual& a, double k) { return k * a; }
  // Values are computed exactly as on doubles (a / b, not a * (1 / b)), so that a residual evaluated on
  // doubles and on Dual<3> at the same point compares equal (the solvers mix the two).
  friend Dual operator/(const Dual& a, const Dual& b) {
    const double inv = 1.0 / b.v;
    Dual r(a.v / b.v);
    for (int i = 0; i < K; ++i) r.d[i] = (a.d[i] - r.v * b.d[i]) * inv;
    return r;
  }
  friend Dual operator/(const Dual& a, double k) {
    Dual r(a.v / k);
    for (int i = 0; i < K; ++i) r.d[i] = a.d[i] / k;
    return r;
  }
  Dual& operator+=(const Dual& b) { return *this = *this + b; }
  Dual& operator-=(const Dual& b) { return *this = *this - b; }
  Dual& operator*=(const Dual& b) { return *this = *this * b; }
  friend bool operator<(const Dual& a, const Dual& b) { return a.v < b.v; }
};

template <int K>
inline Dual<K> chain(const Dual<K>& a, double value, double derivative) {
  Dual<K> r(value);
  for (int i = 0; i < K; ++i) r.d[i] = derivative * a.d[i];
  return r;
}
template <int K>
inline Dual<K> sqrt(const Dual<K>& a) {
  const double s = std::sqrt(a.v);
  return chain(a, s, 0.5 / s);
}
template <int K>
inline Dual<K> sin(const Dual<K>& a) { return chain(a, std::sin(a.v), std::cos(a.v)); }
template <int K>
inline Dual<K> cos(const Dual<K>& a) { return chain(a, std::cos(a.v), -std::sin(a.v)); }

inline double value_of(double x) { return x; }
/// Exactly zero, derivatives included.
inline bool is_zero(double x) { return x == 0.0; }
template <int K>
inline bool is_zero(const Dual<K>& x) {
  for (int i = 0; i < K; ++i)
    if (x.d[i] != 0.0) return false;
  return x.v == 0.0;
}
template <int K>
inline double value_of(const Dual<K>& x) { return x.v; }

}  // namespace vibrissa
