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
  /// x -> G x, dx -> G (dx + dtheta x x): turned by G whose rotation vector moved by J_r dtheta (see the
  /// header).
  void turn(const Mat3<double>& G, const V* dtheta) {
    for (int i = 0; i < K; ++i) dx[i] = G * (dx[i] + cross(dtheta[i], x));
    x = G * x;
  }
  /// The same for a joint's turn G = exp(omega): the value exactly as deflect() turns it (split form, plus
  /// `offset`), so that values here equal deflect<double>'s bit for bit.
  void turn(const Mat3<double>& G, const V* dtheta, const V& omega, double t2, double a, double b,
            const V* offset = nullptr) {
    for (int i = 0; i < K; ++i) dx[i] = G * (dx[i] + cross(dtheta[i], x));
    const detail::RotationTerms<double> terms(omega, t2, x);
    x = offset ? terms.turned(a, b, *offset) : terms.turned(a, b);
  }
};

}  // namespace

ContactKinematics<D> deflect_analytic(const Whisker& w, const V3<D>& force_L, const V3<D>& couple_L, const D& s) {
  if (w.properties().scheme == Scheme::paper) return deflect_published<D>(w, force_L, couple_L, s);
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
  Carried r, F, C;
  const V tangent(Eigen::Vector3d(R_link[uk].col(0)));
  r.x = scaled(h, tangent);
  F.x = value(force_L);
  C.x = value(couple_L);
  double dh[K];
  for (int i = 0; i < K; ++i) {
    dh[i] = s.d[static_cast<std::size_t>(i)];
    r.dx[i] = scaled(dh[i], tangent);
    F.dx[i] = direction(force_L, i);
    C.dx[i] = direction(couple_L, i);
  }
  const bool couple = !(is_zero(couple_L.x) && is_zero(couple_L.y) && is_zero(couple_L.z));
  {  // load frame at s, then link k's rest frame: psi is parallel to kappa, so J_r(psi) dpsi = dpsi = dh kappa
    const V kappa(w.load_frame_curvature()[uk]);
    const V psi = scaled(h - 0.5 * w.link_lengths()[uk], kappa);
    double a, b;
    detail::rodrigues_coefficients(dot(psi, psi), a, b);
    const Mat3<double> RE = mul(R_link[uk], detail::rotation_matrix(psi, a, b));
    V dtheta[K];
    for (int i = 0; i < K; ++i) dtheta[i] = scaled(dh[i], kappa);
    F.turn(RE, dtheta);
    if (couple) C.turn(RE, dtheta);
  }
  for (int j = k; j >= 0; --j) {
    const std::size_t u = static_cast<std::size_t>(j);
    const V rxF = cross(r.x, F.x);
    V drxF[K];
    for (int i = 0; i < K; ++i) drxF[i] = cross(r.dx[i], F.x) + cross(r.x, F.dx[i]);
    // m and omega exactly as deflect() forms them (chain.hpp)
    const V m = couple ? rxF + C.x : rxF;
    V omega, domega[K];
    if (j == k) {  // weights of the loaded joint (chain.hpp) depend on h
      const double base_w = w.loaded_joint_weight_base(j), slope = w.loaded_joint_weight_slope();
      const double wf = base_w + slope * h, wc = base_w + (slope > 0.0 ? h : 0.0);
      const V M = couple ? scaled(wf, rxF) + scaled(wc, C.x) : scaled(wf, m);
      const Eigen::Matrix3d& Kc = K_B[u];
      const V P = mul(Kc, M);
      omega = P + mul(Kc, cross(P, scaled(0.5, M)));
      for (int i = 0; i < K; ++i) {
        const V dM = scaled(slope * dh[i], rxF) + scaled(wf, drxF[i]) + scaled(slope > 0.0 ? dh[i] : 0.0, C.x) +
                     scaled(wc, C.dx[i]);
        const V dP = mul(Kc, dM);
        domega[i] = dP + mul(Kc, scaled(0.5, cross(dP, M) + cross(P, dM)));
      }
    } else {  // omega = P + Kw (P x (m / 2)), P = Kw m (chain.hpp)
      const Eigen::Matrix3d& Kc = Kw_B[u];
      const V P = mul(Kc, m);
      omega = P + mul(Kc, cross(P, scaled(0.5, m)));
      for (int i = 0; i < K; ++i) {
        const V dm = couple ? drxF[i] + C.dx[i] : drxF[i];
        const V dP = mul(Kc, dm);
        domega[i] = dP + mul(Kc, scaled(0.5, cross(dP, m) + cross(P, dm)));
      }
    }
    if (j == 0 && base_extra > 0.0) {  // follicle spring in series: bending part of the unweighted moment
      const V e(Eigen::Vector3d(R_link[0].col(0)));
      auto bending = [&e](const V& x) { return x - scaled(dot(x, e), e); };
      omega = omega + scaled(base_extra, bending(m));
      for (int i = 0; i < K; ++i) domega[i] = domega[i] + scaled(base_extra, bending(drxF[i] + C.dx[i]));
    }
    const double t2 = dot(omega, omega);
    double a, b;
    detail::rodrigues_coefficients(t2, a, b);
    const double c = detail::right_jacobian_coefficient(t2, a);
    const Mat3<double> G = detail::rotation_matrix(omega, a, b);
    V dtheta[K];
    for (int i = 0; i < K; ++i) {
      const V wd = cross(omega, domega[i]);
      dtheta[i] = domega[i] - scaled(b, wd) + scaled(c, cross(omega, wd));
    }
    if (j > 0) {
      const V link(link_B[u - 1]);
      r.turn(G, dtheta, omega, t2, a, b, &link);
    } else {
      r.turn(G, dtheta, omega, t2, a, b);
    }
    F.turn(G, dtheta, omega, t2, a, b);
    if (couple) C.turn(G, dtheta, omega, t2, a, b);
  }
  return {pack(r.x, r.dx), pack(F.x, F.dx), pack(C.x, C.dx)};
}

}  // namespace vibrissa
