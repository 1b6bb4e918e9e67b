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
// version stays the reference. Its values are turned by the joint's matrix, which the tangents need anyway,
// where deflect() uses the split form (shorter on its critical path): they agree with deflect<double>'s to
// rounding, not bit for bit. deflect_for_solve() picks the fastest exact evaluation for a scalar.
#include <type_traits>
#include <vector>

#include "vibrissa/core/chain.hpp"

namespace vibrissa {

/// deflect() of the second-order scheme on Dual<3> inputs by analytic tangents (the derivatives of the
/// outputs along the three derivative directions of the inputs). Values equal deflect<double>'s to rounding.
/// Where the CPU has AVX2 the three directions run side by side in vector lanes (same numbers bit for bit).
/// The paper scheme falls back to deflect_published<Dual<3>>.
ContactKinematics<Dual<3>> deflect_analytic(const Whisker& w, const V3<Dual<3>>& force_L,
                                            const V3<Dual<3>>& couple_L, const Dual<3>& s);
/// The same carrying `followers` (deflect<S, true>): they come out in B with their derivatives.
ContactKinematics<Dual<3>> deflect_analytic(const Whisker& w, const V3<Dual<3>>& force_L,
                                            const V3<Dual<3>>& couple_L, const Dual<3>& s,
                                            FollowerVectors<Dual<3>>& followers);

namespace detail {
/// One build of deflect_analytic()'s second-order walk (no paper-scheme fallback).
struct AnalyticBuild {
  const char* name;
  ContactKinematics<Dual<3>> (*walk)(const Whisker&, const V3<Dual<3>>&, const V3<Dual<3>>&, const Dual<3>&);
  /// The same walk carrying follower vectors.
  ContactKinematics<Dual<3>> (*follow)(const Whisker&, const V3<Dual<3>>&, const V3<Dual<3>>&, const Dual<3>&,
                                       FollowerVectors<Dual<3>>&);
};
/// The builds this CPU runs: "portable" (one vector per derivative direction), then on x86 with AVX2 "avx2"
/// (the three directions in vector lanes) and with AVX-512 "avx512" (the same code compiled for it).
/// deflect_analytic() runs the last; all give the same numbers bit for bit (tested).
std::vector<AnalyticBuild> analytic_builds();
}  // namespace detail

/// deflect() for the solvers: doubles as they are, Dual<3> through deflect_analytic().
template <class S>
ContactKinematics<S> deflect_for_solve(const Whisker& w, const V3<S>& force_L, const V3<S>& couple_L, const S& s) {
  if constexpr (std::is_same_v<S, Dual<3>>) return deflect_analytic(w, force_L, couple_L, s);
  else return deflect<S>(w, force_L, couple_L, s);
}
/// deflect_for_solve() carrying follower vectors (the object solves' load frame).
template <class S>
ContactKinematics<S> deflect_for_solve(const Whisker& w, const V3<S>& force_L, const V3<S>& couple_L, const S& s,
                                       FollowerVectors<S>& followers) {
  if constexpr (std::is_same_v<S, Dual<3>>) return deflect_analytic(w, force_L, couple_L, s, followers);
  else return deflect<S, true>(w, force_L, couple_L, s, nullptr, &followers);
}

}  // namespace vibrissa
