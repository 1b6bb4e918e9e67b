#include "vibrissa/core/chain_jacobian.hpp"

#include <array>
#include <vector>

namespace vibrissa {

// The walk below is written once for two representations of the tangents (the derivatives of a carried vector
// along the three directions): `Each`, one vector per direction (portable), and `Lanes`, the three directions
// side by side in the lanes of a GCC/Clang vector, so that one vector operation serves all three. Where the
// CPU has AVX2 the Lanes build runs (one instruction per operation), compiled for AVX-512 (32 vector registers
// instead of 16: fewer spills) where it has that; elsewhere Each. All form every number with the same
// operations in the same order, without fused multiply-adds: the results are identical.
// The helpers have internal linkage and are inlined into each build, so the ABI of passing AVX-sized vectors
// (the -Wpsabi note of GCC and Clang) never applies.
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wpsabi"
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
#define VIBRISSA_LANE_INLINE [[gnu::always_inline]] inline

namespace {

using D = Dual<3>;
using V = V3<double>;

VIBRISSA_LANE_INLINE V value(const V3<D>& x) { return {x.x.v, x.y.v, x.z.v}; }
VIBRISSA_LANE_INLINE V scaled(double k, const V& a) { return {k * a.x, k * a.y, k * a.z}; }

/// Tangents one vector per direction; coefficients (one number per direction) as an array.
struct Each {
  using Coefficients = std::array<double, 3>;
  V d[3];
  VIBRISSA_LANE_INLINE friend Each operator+(const Each& a, const Each& b) {
    return {{a.d[0] + b.d[0], a.d[1] + b.d[1], a.d[2] + b.d[2]}};
  }
  VIBRISSA_LANE_INLINE friend Each operator-(const Each& a, const Each& b) {
    return {{a.d[0] - b.d[0], a.d[1] - b.d[1], a.d[2] - b.d[2]}};
  }
  template <class F>
  VIBRISSA_LANE_INLINE static Each each(F&& f) {
    return {{f(0), f(1), f(2)}};
  }
  VIBRISSA_LANE_INLINE static Coefficients coefficients(const D& x) { return {x.d[0], x.d[1], x.d[2]}; }
  VIBRISSA_LANE_INLINE static Each of(const V3<D>& x) {
    return each([&](std::size_t i) { return V(x.x.d[i], x.y.d[i], x.z.d[i]); });
  }
  VIBRISSA_LANE_INLINE static Each outer(const Coefficients& k, const V& v) {
    return each([&](std::size_t i) { return scaled(k[i], v); });
  }
  VIBRISSA_LANE_INLINE friend Each scaled(double k, const Each& a) {
    return each([&](std::size_t i) { return scaled(k, a.d[i]); });
  }
  VIBRISSA_LANE_INLINE friend Each cross(const Each& a, const V& b) {
    return each([&](std::size_t i) { return vibrissa::cross(a.d[i], b); });
  }
  VIBRISSA_LANE_INLINE friend Each cross(const V& a, const Each& b) {
    return each([&](std::size_t i) { return vibrissa::cross(a, b.d[i]); });
  }
  VIBRISSA_LANE_INLINE friend Coefficients dot(const Each& a, const V& b) {
    return {vibrissa::dot(a.d[0], b), vibrissa::dot(a.d[1], b), vibrissa::dot(a.d[2], b)};
  }
  VIBRISSA_LANE_INLINE friend Each mul(const Eigen::Matrix3d& R, const Each& a) {
    return each([&](std::size_t i) { return vibrissa::mul(R, a.d[i]); });
  }
  VIBRISSA_LANE_INLINE friend Each times(const Mat3<double>& G, const Each& a) {
    return each([&](std::size_t i) { return G * a.d[i]; });
  }
  VIBRISSA_LANE_INLINE static Coefficients scaled_coefficients(double k, const Coefficients& c) {
    return {k * c[0], k * c[1], k * c[2]};
  }
  VIBRISSA_LANE_INLINE static V3<D> pack(const V& x, const Each& dx) {
    V3<D> r(D(x.x), D(x.y), D(x.z));
    for (std::size_t i = 0; i < 3; ++i) {
      r.x.d[i] = dx.d[i].x;
      r.y.d[i] = dx.d[i].y;
      r.z.d[i] = dx.d[i].z;
    }
    return r;
  }
};

/// Tangents in lanes 0-2 of a vector per component (lane 3 unused, zero).
struct Lanes {
  using Coefficients = double __attribute__((vector_size(4 * sizeof(double))));
  using L = Coefficients;
  L x, y, z;
  VIBRISSA_LANE_INLINE friend Lanes operator+(const Lanes& a, const Lanes& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  VIBRISSA_LANE_INLINE friend Lanes operator-(const Lanes& a, const Lanes& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  VIBRISSA_LANE_INLINE static L coefficients(const D& v) { return L{v.d[0], v.d[1], v.d[2], 0.0}; }
  VIBRISSA_LANE_INLINE static Lanes of(const V3<D>& v) { return {coefficients(v.x), coefficients(v.y), coefficients(v.z)}; }
  VIBRISSA_LANE_INLINE static Lanes outer(const L& k, const V& v) { return {k * v.x, k * v.y, k * v.z}; }
  VIBRISSA_LANE_INLINE friend Lanes scaled(double k, const Lanes& a) { return {k * a.x, k * a.y, k * a.z}; }
  VIBRISSA_LANE_INLINE friend Lanes cross(const Lanes& a, const V& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  }
  VIBRISSA_LANE_INLINE friend Lanes cross(const V& a, const Lanes& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  }
  VIBRISSA_LANE_INLINE friend L dot(const Lanes& a, const V& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
  VIBRISSA_LANE_INLINE friend Lanes mul(const Eigen::Matrix3d& R, const Lanes& v) {
    return {R(0, 0) * v.x + R(0, 1) * v.y + R(0, 2) * v.z, R(1, 0) * v.x + R(1, 1) * v.y + R(1, 2) * v.z,
            R(2, 0) * v.x + R(2, 1) * v.y + R(2, 2) * v.z};
  }
  VIBRISSA_LANE_INLINE friend Lanes times(const Mat3<double>& G, const Lanes& v) {
    return {G.m[0] * v.x + G.m[1] * v.y + G.m[2] * v.z, G.m[3] * v.x + G.m[4] * v.y + G.m[5] * v.z,
            G.m[6] * v.x + G.m[7] * v.y + G.m[8] * v.z};
  }
  VIBRISSA_LANE_INLINE static L scaled_coefficients(double k, const L& c) { return k * c; }
  VIBRISSA_LANE_INLINE static D dual(double v, const L& d) {
    D r(v);
    for (std::size_t i = 0; i < 3; ++i) r.d[i] = d[i];
    return r;
  }
  VIBRISSA_LANE_INLINE static V3<D> pack(const V& v, const Lanes& dv) {
    return {dual(v.x, dv.x), dual(v.y, dv.y), dual(v.z, dv.z)};
  }
};

/// A carried vector and its tangents.
template <class T>
struct Carried {
  V x;
  T dx;
  /// x -> G x (+ offset), dx -> G (dx + dtheta x x): turned by G whose rotation vector moved by J_r dtheta (see
  /// the header). The value is turned by the matrix the tangents need anyway (9 multiplications, where
  /// deflect()'s split form, shorter on its critical path, takes 21): it agrees with deflect<double>'s to
  /// rounding, not bit for bit.
  VIBRISSA_LANE_INLINE void turn(const Mat3<double>& G, const T& dtheta, const V* offset = nullptr) {
    dx = times(G, dx + cross(dtheta, x));
    x = offset ? *offset + G * x : G * x;
  }
};

template <class T, bool Follow = false>
VIBRISSA_LANE_INLINE ContactKinematics<D> walk(const Whisker& w, const V3<D>& force_L, const V3<D>& couple_L,
                                               const D& s, FollowerVectors<D>* followers = nullptr) {
  using Coefficients = typename T::Coefficients;
  int k;
  double h0;
  w.locate(s.v, k, h0);
  const std::size_t uk = static_cast<std::size_t>(k);
  const double h = s.v - w.node_arc_lengths()[uk];
  const auto& K_B = w.joint_compliance_B();
  const auto& Kw_B = w.weighted_joint_compliance_B();
  const auto& link_B = w.rest_link_vectors_B();
  const auto& R_link = w.rest_link_frames_B();
  const double base_extra = w.base_extra_compliance();

  // The carried vectors in rest axes, as deflect() does (chain.hpp).
  Carried<T> r, F, C;
  const V tangent(Eigen::Vector3d(R_link[uk].col(0)));
  const Coefficients dh = T::coefficients(s);
  r.x = scaled(h, tangent);
  r.dx = T::outer(dh, tangent);
  F.x = value(force_L);
  F.dx = T::of(force_L);
  C.x = value(couple_L);
  C.dx = T::of(couple_L);
  const bool couple = !(is_zero(couple_L.x) && is_zero(couple_L.y) && is_zero(couple_L.z));
  [[maybe_unused]] Carried<T> follow[2];
  if constexpr (Follow)
    for (std::size_t i = 0; i < 2; ++i) {
      follow[i].x = value((*followers)[i]);
      follow[i].dx = T::of((*followers)[i]);
    }
  {  // load frame at s, then link k's rest frame: psi is parallel to kappa, so J_r(psi) dpsi = dpsi = dh kappa
    const V kappa(w.load_frame_curvature()[uk]);
    const V psi = scaled(h - 0.5 * w.link_lengths()[uk], kappa);
    double a, b;
    detail::rodrigues_coefficients(dot(psi, psi), a, b);
    const Mat3<double> RE = mul(R_link[uk], detail::rotation_matrix(psi, a, b));
    const T dtheta = T::outer(dh, kappa);
    F.turn(RE, dtheta);
    if (couple) C.turn(RE, dtheta);
    if constexpr (Follow)
      for (auto& v : follow) v.turn(RE, dtheta);
  }
  for (int j = k; j >= 0; --j) {
    const std::size_t u = static_cast<std::size_t>(j);
    const V rxF = cross(r.x, F.x);
    const T drxF = cross(r.dx, F.x) + cross(r.x, F.dx);
    // m and omega exactly as deflect() forms them (chain.hpp)
    const V m = couple ? rxF + C.x : rxF;
    V omega;
    T domega;
    if (j == k) {  // weights of the loaded joint (chain.hpp) depend on h
      const double base_w = w.loaded_joint_weight_base(j), slope = w.loaded_joint_weight_slope();
      const double wf = base_w + slope * h, wc = base_w + (slope > 0.0 ? h : 0.0);
      const V M = couple ? scaled(wf, rxF) + scaled(wc, C.x) : scaled(wf, m);
      const Eigen::Matrix3d& Kc = K_B[u];
      const V P = mul(Kc, M);
      omega = P + mul(Kc, cross(P, scaled(0.5, M)));
      const T dM = T::outer(T::scaled_coefficients(slope, dh), rxF) + scaled(wf, drxF) +
                   T::outer(slope > 0.0 ? dh : Coefficients{}, C.x) + scaled(wc, C.dx);
      const T dP = mul(Kc, dM);
      domega = dP + mul(Kc, scaled(0.5, cross(dP, M) + cross(P, dM)));
    } else {  // omega = P + Kw (P x (m / 2)), P = Kw m (chain.hpp)
      const Eigen::Matrix3d& Kc = Kw_B[u];
      const V P = mul(Kc, m);
      omega = P + mul(Kc, cross(P, scaled(0.5, m)));
      const T dm = couple ? drxF + C.dx : drxF;
      const T dP = mul(Kc, dm);
      domega = dP + mul(Kc, scaled(0.5, cross(dP, m) + cross(P, dm)));
    }
    if (j == 0 && base_extra > 0.0) {  // follicle spring in series: bending part of the unweighted moment
      const V e(Eigen::Vector3d(R_link[0].col(0)));
      omega = omega + scaled(base_extra, m - scaled(dot(m, e), e));
      const T dm = drxF + C.dx;
      domega = domega + scaled(base_extra, dm - T::outer(dot(dm, e), e));
    }
    const double t2 = dot(omega, omega);
    double a, b;
    detail::rodrigues_coefficients(t2, a, b);
    const double c = detail::right_jacobian_coefficient(t2, a);
    const Mat3<double> G = detail::rotation_matrix(omega, a, b);
    const T wd = cross(omega, domega);
    const T dtheta = domega - scaled(b, wd) + scaled(c, cross(omega, wd));
    if (j > 0) {
      const V link(link_B[u - 1]);
      r.turn(G, dtheta, &link);
    } else {
      r.turn(G, dtheta);
    }
    F.turn(G, dtheta);
    if (couple) C.turn(G, dtheta);
    if constexpr (Follow)
      for (auto& v : follow) v.turn(G, dtheta);
  }
  if constexpr (Follow)
    for (std::size_t i = 0; i < 2; ++i) (*followers)[i] = T::pack(follow[i].x, follow[i].dx);
  return {T::pack(r.x, r.dx), T::pack(F.x, F.dx), T::pack(C.x, C.dx)};
}

ContactKinematics<D> walk_portable(const Whisker& w, const V3<D>& force_L, const V3<D>& couple_L, const D& s) {
  return walk<Each>(w, force_L, couple_L, s);
}
ContactKinematics<D> follow_portable(const Whisker& w, const V3<D>& force_L, const V3<D>& couple_L, const D& s,
                                     FollowerVectors<D>& followers) {
  return walk<Each, true>(w, force_L, couple_L, s, &followers);
}

#if defined(__x86_64__) || defined(__i386__)
#define VIBRISSA_LANES_X86 1
// The Lanes builds, chosen at run time (the library itself targets baseline x86-64). __builtin_cpu_supports
// also checks that the operating system saves the AVX and AVX-512 registers.
[[gnu::target("avx2")]] ContactKinematics<D> walk_avx2(const Whisker& w, const V3<D>& force_L, const V3<D>& couple_L,
                                                       const D& s) {
  return walk<Lanes>(w, force_L, couple_L, s);
}
[[gnu::target("avx2,avx512f,avx512vl")]] ContactKinematics<D> walk_avx512(const Whisker& w, const V3<D>& force_L,
                                                                          const V3<D>& couple_L, const D& s) {
  return walk<Lanes>(w, force_L, couple_L, s);
}
[[gnu::target("avx2")]] ContactKinematics<D> follow_avx2(const Whisker& w, const V3<D>& force_L,
                                                         const V3<D>& couple_L, const D& s,
                                                         FollowerVectors<D>& followers) {
  return walk<Lanes, true>(w, force_L, couple_L, s, &followers);
}
[[gnu::target("avx2,avx512f,avx512vl")]] ContactKinematics<D> follow_avx512(const Whisker& w, const V3<D>& force_L,
                                                                            const V3<D>& couple_L, const D& s,
                                                                            FollowerVectors<D>& followers) {
  return walk<Lanes, true>(w, force_L, couple_L, s, &followers);
}
#endif

std::vector<detail::AnalyticBuild> builds_of_this_cpu() {
  std::vector<detail::AnalyticBuild> out{{"portable", &walk_portable, &follow_portable}};
#ifdef VIBRISSA_LANES_X86
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2")) out.push_back({"avx2", &walk_avx2, &follow_avx2});
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl"))
    out.push_back({"avx512", &walk_avx512, &follow_avx512});
#endif
  return out;
}

}  // namespace

std::vector<detail::AnalyticBuild> detail::analytic_builds() { return builds_of_this_cpu(); }

ContactKinematics<D> deflect_analytic(const Whisker& w, const V3<D>& force_L, const V3<D>& couple_L, const D& s) {
  if (w.properties().scheme == Scheme::paper) return deflect_published<D>(w, force_L, couple_L, s);
  static const auto fastest = builds_of_this_cpu().back().walk;
  return fastest(w, force_L, couple_L, s);
}

ContactKinematics<D> deflect_analytic(const Whisker& w, const V3<D>& force_L, const V3<D>& couple_L, const D& s,
                                      FollowerVectors<D>& followers) {
  if (w.properties().scheme == Scheme::paper) return deflect_published<D>(w, force_L, couple_L, s, nullptr, &followers);
  static const auto fastest = builds_of_this_cpu().back().follow;
  return fastest(w, force_L, couple_L, s, followers);
}

}  // namespace vibrissa
