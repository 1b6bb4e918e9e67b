#pragma once
// The forward model (spec §2.1, eqs. (1)-(3)): a load at arc length s, fixed in the frame of the link it
// acts on (a follower load, as in the published model), bends the chain. Walking from the loaded link to
// the base, each joint j sees the moment M = r x F + C of the distal load (r from node j to the contact, all
// in link j's frame); the joint turns by
//     omega_j = w_j · (M_x / GJ_j, M_y / EI_j, M_z / EI_j)                      (eqs. (1), (3))
// and everything distal turns with it. Because the load follows its link, the walk is explicit and exact
// for the discrete chain: O(N), no iteration, no allocation. It is templated on the scalar so that the
// same code evaluated on Dual<3> gives exact Jacobians for the solvers. This walk is the second-order
// scheme's; the paper scheme's (Elastica3D's re-meshed chain) is deflect_published() in published_chain.hpp.
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/contact_kinematics.hpp"
#include "vibrissa/core/dual.hpp"
#include "vibrissa/core/published_chain.hpp"
#include "vibrissa/core/rodrigues.hpp"
#include "vibrissa/core/small_vector.hpp"
#include "vibrissa/core/whisker.hpp"

namespace vibrissa {

/// Deflects the whisker under a follower force `force_L` and couple `couple_L` (components in the frame of
/// the loaded link) at arc length s. If `omega_out` is given it receives the rotation vector of every
/// joint in its link's frame (size >= links; unloaded joints are zero) for shape reconstruction.
///
/// The walk carries its vectors in the axes of B at rest ("rest axes"): a vector v_j in link j's frame is
/// carried as R_j v_j, R_j the rest frame of link j in B. Because R_{j-1} Q_j = R_j, the turn of joint j,
/// v_{j-1} = Q_j exp([omega_j]x) v_j, becomes y_{j-1} = exp([R_j omega_j]x) y_j: one rotation by the joint's
/// rotation vector in rest axes, and the joint law (eqs. (1), (3)) holds there with the compliance
/// R_j K_j R_j^T (cross products and rotations commute with R_j). No rest rotation is applied in the walk;
/// at the base the rest axes are B's, so the carried vectors come out in B.
/// With Follow, `followers` (vectors fixed in the load frame, given in it) are turned with the load and come out
/// in B (contact_kinematics.hpp); they take no part in the mechanics, so every other output is the same.
template <class S, bool Follow = false>
ContactKinematics<S> deflect(const Whisker& w, const V3<S>& force_L, const V3<S>& couple_L, const S& s,
                             Eigen::Vector3d* omega_out = nullptr, FollowerVectors<S>* followers = nullptr) {
  if (w.properties().scheme == Scheme::paper)
    return deflect_published<S>(w, force_L, couple_L, s, nullptr, Follow ? followers : nullptr);
  int k;
  double h0;
  w.locate(value_of(s), k, h0);
  const std::size_t uk = static_cast<std::size_t>(k);
  const S h = s - S(w.node_arc_lengths()[uk]);
  const auto& K_B = w.joint_compliance_B();
  const auto& Kw_B = w.weighted_joint_compliance_B();
  const auto& link_B = w.rest_link_vectors_B();
  const auto& R_link = w.rest_link_frames_B();
  const double base_extra = w.base_extra_compliance();

  // r (node j -> contact), F and C in rest axes. Without a couple C stays zero and is not turned.
  const bool couple = !(is_zero(couple_L.x) && is_zero(couple_L.y) && is_zero(couple_L.z));
  V3<S> r, F, C;
  {  // load frame follows the smooth rest tangent at s (whisker.hpp), then link k's rest frame
    const Eigen::Vector3d& kappa = w.load_frame_curvature()[uk];
    const S offset = h - S(0.5 * w.link_lengths()[uk]);
    const V3<S> psi(offset * kappa.x(), offset * kappa.y(), offset * kappa.z());
    S a, b;
    detail::rodrigues_coefficients(dot(psi, psi), a, b);
    const Mat3<S> RE = mul(R_link[uk], detail::rotation_matrix(psi, a, b));
    const Eigen::Vector3d tangent = R_link[uk].col(0);
    r = V3<S>(h * tangent.x(), h * tangent.y(), h * tangent.z());
    F = RE * force_L;
    C = couple ? RE * couple_L : V3<S>(S(0.0), S(0.0), S(0.0));
    if constexpr (Follow)
      for (auto& v : *followers) v = RE * v;
  }
  if (omega_out)
    for (int j = k + 1; j < w.links(); ++j) omega_out[j].setZero();
  for (int j = k; j >= 0; --j) {
    const std::size_t u = static_cast<std::size_t>(j);
    // m: moment of the distal load about the joint per unit weight; P = K M is the predictor of the rotation.
    const V3<S> m = couple ? cross(r, F) + C : cross(r, F);
    V3<S> omega;
    if (j == k) {
      // Joint weights: a force's moment falls linearly to zero at the load, a couple's does not, so on the
      // loaded joint they integrate over [s_k, s] with the trapezoid and the rectangle rule respectively.
      const double base_w = w.loaded_joint_weight_base(j), slope = w.loaded_joint_weight_slope();
      const S wf = S(base_w) + slope * h, wc = S(base_w) + (slope > 0.0 ? h : S(0.0));
      const V3<S> M = couple ? wf * cross(r, F) + wc * C : wf * m;
      const V3<S> P = mul(K_B[u], M);
      omega = P + mul(K_B[u], cross(P, S(0.5) * M));
    } else {
      // Split twist from bending in the joint's mid frame (rest half-rotation in the compliance matrix, the
      // elastic half-rotation by one predictor-corrector step): second order for curved, twisted rods.
      // With the joint weight in the matrix, omega = K (M + (K M) x M / 2) reads P + Kw (P x (m / 2)) (m / 2
      // is formed alongside P: halving is exact).
      const V3<S> P = mul(Kw_B[u], m);
      omega = P + mul(Kw_B[u], cross(P, S(0.5) * m));
    }
    if (j == 0 && base_extra > 0.0) {  // follicle spring in series: bending part of the unweighted moment
      const Eigen::Vector3d e = R_link[0].col(0);
      const S twist = m.x * e.x() + m.y * e.y() + m.z * e.z();
      omega = omega + S(base_extra) * (m - V3<S>(twist * e.x(), twist * e.y(), twist * e.z()));
    }
    if (omega_out) {
      const Eigen::Vector3d o(value_of(omega.x), value_of(omega.y), value_of(omega.z));
      omega_out[j] = R_link[u].transpose() * o;
    }
    // One rotation turns every carried vector (eq. (3)): y -> y + a (omega x y) + b (omega (omega . y) - t2 y).
    // The products need omega and y only, so they are formed while a and b are evaluated; the joint's
    // critical path is then t2, the coefficients, and one multiply-add.
    const S t2 = dot(omega, omega);
    S a, b;
    detail::rodrigues_coefficients(t2, a, b);
    const detail::RotationTerms<S> tr(omega, t2, r);
    // node j-1 -> contact: the turned r plus the rest link below the joint (added to r first, off the path)
    r = j > 0 ? tr.turned(a, b, V3<S>(link_B[u - 1])) : tr.turned(a, b);
    F = detail::RotationTerms<S>(omega, t2, F).turned(a, b);
    if (couple) C = detail::RotationTerms<S>(omega, t2, C).turned(a, b);
    if constexpr (Follow)
      for (auto& v : *followers) v = detail::RotationTerms<S>(omega, t2, v).turned(a, b);
  }
  return {r, F, C};
}

// One instantiation of each scalar's walk, in the library (src/core/chain.cpp): callers and benchmarks run the
// same code.
extern template ContactKinematics<double> deflect<double>(const Whisker&, const V3<double>&, const V3<double>&,
                                                          const double&, Eigen::Vector3d*, FollowerVectors<double>*);
extern template ContactKinematics<Dual<3>> deflect<Dual<3>>(const Whisker&, const V3<Dual<3>>&,
                                                            const V3<Dual<3>>&, const Dual<3>&, Eigen::Vector3d*,
                                                            FollowerVectors<Dual<3>>*);
extern template ContactKinematics<double> deflect<double, true>(const Whisker&, const V3<double>&, const V3<double>&,
                                                                const double&, Eigen::Vector3d*,
                                                                FollowerVectors<double>*);
extern template ContactKinematics<Dual<3>> deflect<Dual<3>, true>(const Whisker&, const V3<Dual<3>>&,
                                                                  const V3<Dual<3>>&, const Dual<3>&,
                                                                  Eigen::Vector3d*, FollowerVectors<Dual<3>>*);

/// Rotation matrix exp([omega]x) of a joint rotation vector in its link's frame (as deflect() records them in
/// omega_out; the walk itself turns by the same rotation in rest axes).
Eigen::Matrix3d joint_rotation_matrix(const Eigen::Vector3d& omega);

/// Nodes of the deflected whisker in B (size N+1) from the joint rotations written by deflect() (second-order
/// scheme; the paper scheme's are published_nodes_B()).
void deflected_nodes_B(const Whisker& w, const Eigen::Vector3d* omega, std::vector<Eigen::Vector3d>& nodes_B);

}  // namespace vibrissa
