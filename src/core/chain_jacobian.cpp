#include "vibrissa/core/chain_jacobian.hpp"

namespace vibrissa {

namespace {

using D = Dual<3>;
using V = V3<double>;
constexpr int K = 3;  // derivative directions

V value(const V3<D>& x) { return {x.x.v, x.y.v, x.z.v}; }
V direction(const V3<D>& x, int i) {
  const auto u = static_cast<std::size_t>(i);
  return {x.x.d[u], x.y.d[u], x.z.d[u]};
}
V3<D> pack(const V& x, const V* dx) {
  V3<D> r(D(x.x), D(x.y), D(x.z));
  for (int i = 0; i < K; ++i) {
    const auto u = static_cast<std::size_t>(i);
    r.x.d[u] = dx[i].x;
    r.y.d[u] = dx[i].y;
    r.z.d[u] = dx[i].z;
  }
  return r;
}
V scaled(double k, const V& a) { return {k * a.x, k * a.y, k * a.z}; }

/// A carried vector and its tangents.
struct Carried {
  V x;
  V dx[K];
  /// x -> G x, dx -> G (dx + dtheta x x): turned by G = Q exp(omega) whose rotation vector moved by
  /// J_r dtheta (see the header).
  void turn(const Mat3<double>& G, const V* dtheta) {
    for (int i = 0; i < K; ++i) dx[i] = G * (dx[i] + cross(dtheta[i], x));
    x = G * x;
  }
};

}  // namespace

ContactKinematics<D> deflect_analytic(const Whisker& w, const V3<D>& force_L, const V3<D>& couple_L, const D& s) {
  if (w.properties().scheme == Scheme::paper) return deflect_published<D>(w, force_L, couple_L, s);
  int k;
  double h0;
  w.locate(s.v, k, h0);
  const double h = s.v - w.node_arc_lengths()[static_cast<std::size_t>(k)];
  const auto& weight = w.joint_weight();
  const auto& Q = w.rest_joint_rotations();
  const auto& ell = w.link_lengths();
  const double base_extra = w.base_extra_compliance();

  Carried r, F, C, t;
  r.x = V(h, 0.0, 0.0);
  F.x = value(force_L);
  C.x = value(couple_L);
  t.x = V(1.0, 0.0, 0.0);
  double dh[K];
  for (int i = 0; i < K; ++i) {
    dh[i] = s.d[static_cast<std::size_t>(i)];
    r.dx[i] = V(dh[i], 0.0, 0.0);
    F.dx[i] = direction(force_L, i);
    C.dx[i] = direction(couple_L, i);
    t.dx[i] = V(0.0, 0.0, 0.0);
  }
  const bool couple = !(is_zero(couple_L.x) && is_zero(couple_L.y) && is_zero(couple_L.z));
  {  // load frame at s: psi is parallel to kappa, so J_r(psi) dpsi = dpsi = dh kappa
    const V kappa(w.load_frame_curvature()[static_cast<std::size_t>(k)]);
    const V psi = scaled(h - 0.5 * ell[static_cast<std::size_t>(k)], kappa);
    double a, b;
    detail::rodrigues_coefficients(dot(psi, psi), a, b);
    const Mat3<double> E = detail::rotation_matrix(psi, a, b);
    V dtheta[K];
    for (int i = 0; i < K; ++i) dtheta[i] = scaled(dh[i], kappa);
    F.turn(E, dtheta);
    if (couple) C.turn(E, dtheta);
    t.turn(E, dtheta);
  }
  for (int j = k; j >= 0; --j) {
    const std::size_t u = static_cast<std::size_t>(j);
    const V rxF = cross(r.x, F.x);
    V drxF[K];
    for (int i = 0; i < K; ++i) drxF[i] = cross(r.dx[i], F.x) + cross(r.x, F.dx[i]);
    V M, dM[K];
    if (j == k) {  // weights of the loaded joint (chain.hpp) depend on h
      const double base_w = w.loaded_joint_weight_base(j), slope = w.loaded_joint_weight_slope();
      const double wf = base_w + slope * h, wc = base_w + (slope > 0.0 ? h : 0.0);
      M = scaled(wf, rxF) + scaled(wc, C.x);
      for (int i = 0; i < K; ++i)
        dM[i] = scaled(slope * dh[i], rxF) + scaled(wf, drxF[i]) + scaled(slope > 0.0 ? dh[i] : 0.0, C.x) +
                scaled(wc, C.dx[i]);
    } else {
      M = scaled(weight[u], rxF + C.x);
      for (int i = 0; i < K; ++i) dM[i] = scaled(weight[u], drxF[i] + C.dx[i]);
    }
    const Eigen::Matrix3d& Kc = w.joint_compliance_link()[u];
    const V P = mul(Kc, M);
    V omega = mul(Kc, M + scaled(0.5, cross(P, M)));
    V domega[K];
    for (int i = 0; i < K; ++i) {
      const V dP = mul(Kc, dM[i]);
      domega[i] = mul(Kc, dM[i] + scaled(0.5, cross(dP, M) + cross(P, dM[i])));
    }
    if (j == 0 && base_extra > 0.0) {  // follicle spring in series
      const V Mb = rxF + C.x;
      omega.y += base_extra * Mb.y;
      omega.z += base_extra * Mb.z;
      for (int i = 0; i < K; ++i) {
        const V dMb = drxF[i] + C.dx[i];
        domega[i].y += base_extra * dMb.y;
        domega[i].z += base_extra * dMb.z;
      }
    }
    const double t2 = dot(omega, omega);
    double a, b;
    detail::rodrigues_coefficients(t2, a, b);
    const double c = detail::right_jacobian_coefficient(t2, a);
    const Mat3<double> G = mul(Q[u], detail::rotation_matrix(omega, a, b));
    V dtheta[K];
    for (int i = 0; i < K; ++i) {
      const V wd = cross(omega, domega[i]);
      dtheta[i] = domega[i] - scaled(b, wd) + scaled(c, cross(omega, wd));
    }
    r.turn(G, dtheta);
    F.turn(G, dtheta);
    if (couple) C.turn(G, dtheta);
    t.turn(G, dtheta);
    if (j > 0) r.x.x += ell[u - 1];
  }
  return {pack(r.x, r.dx), pack(F.x, F.dx), pack(C.x, C.dx), pack(t.x, t.dx)};
}

}  // namespace vibrissa
