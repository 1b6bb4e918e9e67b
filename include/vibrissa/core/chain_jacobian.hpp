#pragma once
// The analytic Jacobian of the second-order chain (issue 13): deflect() with forward tangents written out
// by hand instead of carried by Dual<3> arithmetic. Differentiating the walk of chain.hpp: with M, omega
// the joint moment and rotation vector (spec eqs. (1), (3)) in rest axes, P = K M the predictor,
//     dM     = w (dr x F + r x dF + dC)               (weights of the loaded joint also move with s)
//     domega = K (dM + (dP x M + P x dM) / 2),  dP = K dM
//     dtheta = J_r(omega) domega                       (exp(omega + d) = exp(omega) exp(J_r d) to first order)
//     dv'    = exp(omega) (dv + dtheta x v)            for every carried vector v (rest axes: no Q),
// so a tangent costs a few cross products and one product with the joint's matrix per carried vector.
// The result equals deflect<Dual<3>> to rounding (tests/core/test_chain_jacobian.cpp); the Dual<3>
// version stays the reference. deflect_for_solve() picks the fastest exact evaluation for a scalar.
#include <type_traits>

#include "vibrissa/core/chain.hpp"

namespace vibrissa {

/// deflect() of the second-order scheme on Dual<3> inputs by analytic tangents (the derivatives of the
/// outputs along the three derivative directions of the inputs). Values equal deflect<double>'s bit for bit.
/// Where the CPU has AVX2 the three directions run side by side in vector lanes (same numbers).
/// The paper scheme falls back to deflect_published<Dual<3>>.
ContactKinematics<Dual<3>> deflect_analytic(const Whisker& w, const V3<Dual<3>>& force_L,
                                            const V3<Dual<3>>& couple_L, const Dual<3>& s);

namespace detail {
/// deflect_analytic() in its portable build (one vector per derivative direction), the one that runs where the
/// CPU lacks AVX2; elsewhere deflect_analytic() runs the three directions in vector lanes. The two give the
/// same numbers bit for bit (tested).
ContactKinematics<Dual<3>> deflect_analytic_portable(const Whisker& w, const V3<Dual<3>>& force_L,
                                                     const V3<Dual<3>>& couple_L, const Dual<3>& s);
}  // namespace detail

/// deflect() for the solvers: doubles as they are, Dual<3> through deflect_analytic().
template <class S>
ContactKinematics<S> deflect_for_solve(const Whisker& w, const V3<S>& force_L, const V3<S>& couple_L, const S& s) {
  if constexpr (std::is_same_v<S, Dual<3>>) return deflect_analytic(w, force_L, couple_L, s);
  else return deflect<S>(w, force_L, couple_L, s);
}

}  // namespace vibrissa
