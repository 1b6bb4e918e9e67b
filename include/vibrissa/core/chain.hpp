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
/// joint (size >= links; unloaded joints are zero) for shape reconstruction.
template <class S>
ContactKinematics<S> deflect(const Whisker& w, const V3<S>& force_L, const V3<S>& couple_L, const S& s,
                             Eigen::Vector3d* omega_out = nullptr) {
  if (w.properties().scheme == Scheme::paper) return deflect_published<S>(w, force_L, couple_L, s);
  int k;
  double h0;
  w.locate(value_of(s), k, h0);
  const S h = s - S(w.node_arc_lengths()[static_cast<std::size_t>(k)]);
  const auto& weight = w.joint_weight();
  const auto& Q = w.rest_joint_rotations();
  const auto& ell = w.link_lengths();
  const double base_extra = w.base_extra_compliance();

  // v[0] = r (node j -> contact), v[1] = F, v[2] = C, v[3] = tangent of the loaded link. Without a couple
  // v[2] stays zero and is not rotated.
  V3<S> v[4] = {V3<S>(h, S(0.0), S(0.0)), force_L, couple_L, V3<S>(S(1.0), S(0.0), S(0.0))};
  const bool couple = !(is_zero(couple_L.x) && is_zero(couple_L.y) && is_zero(couple_L.z));
  {  // load frame follows the smooth rest tangent at s (whisker.hpp)
    const Eigen::Vector3d& kappa = w.load_frame_curvature()[static_cast<std::size_t>(k)];
    const S offset = h - S(0.5 * ell[static_cast<std::size_t>(k)]);
    const V3<S> psi(offset * kappa.x(), offset * kappa.y(), offset * kappa.z());
    S a, b;
    detail::rodrigues_coefficients(dot(psi, psi), a, b);
    const Mat3<S> E = detail::rotation_matrix(psi, a, b);
    v[1] = E * v[1];
    if (couple) v[2] = E * v[2];
    v[3] = E * v[3];
  }
  if (omega_out)
    for (int j = k + 1; j < w.links(); ++j) omega_out[j].setZero();
  for (int j = k; j >= 0; --j) {
    const std::size_t u = static_cast<std::size_t>(j);
    // Joint weights: a force's moment falls linearly to zero at the load, a couple's does not, so on the
    // loaded joint they integrate over [s_k, s] with the trapezoid and the rectangle rule respectively.
    const V3<S> rxF = cross(v[0], v[1]);
    V3<S> M;
    if (j == k) {
      const double base_w = w.loaded_joint_weight_base(j), slope = w.loaded_joint_weight_slope();
      const S wf = S(base_w) + slope * h, wc = S(base_w) + (slope > 0.0 ? h : S(0.0));
      M = wf * rxF + wc * v[2];
    } else {
      M = S(weight[u]) * (rxF + v[2]);
    }
    // Split twist from bending in the joint's mid frame (rest half-rotation in the compliance matrix, the
    // elastic half-rotation by one predictor-corrector step): second order for curved, twisted rods.
    const Eigen::Matrix3d& K = w.joint_compliance_link()[u];
    const V3<S> predictor = mul(K, M);
    V3<S> omega = mul(K, M + S(0.5) * cross(predictor, M));
    if (j == 0 && base_extra > 0.0) {  // follicle spring in series (moment, not weighted)
      const V3<S> Mb = rxF + v[2];
      omega.y += base_extra * Mb.y;
      omega.z += base_extra * Mb.z;
    }
    if (omega_out) omega_out[j] = Eigen::Vector3d(value_of(omega.x), value_of(omega.y), value_of(omega.z));
    // One matrix, the rest rotation after the elastic one, turns every carried vector (eq. (3)).
    S a, b;
    detail::rodrigues_coefficients(dot(omega, omega), a, b);
    const Mat3<S> G = mul(Q[u], detail::rotation_matrix(omega, a, b));
    v[0] = G * v[0];
    v[1] = G * v[1];
    if (couple) v[2] = G * v[2];
    v[3] = G * v[3];
    if (j > 0) v[0].x += ell[u - 1];
  }
  return {v[0], v[1], v[2], v[3]};
}

/// Rotation matrix exp([omega]x) of a joint rotation vector (the one deflect() applies).
Eigen::Matrix3d joint_rotation_matrix(const Eigen::Vector3d& omega);

/// Nodes of the deflected whisker in B (size N+1) from the joint rotations written by deflect() (second-order
/// scheme; the paper scheme's are published_nodes_B()).
void deflected_nodes_B(const Whisker& w, const Eigen::Vector3d* omega, std::vector<Eigen::Vector3d>& nodes_B);

}  // namespace vibrissa
