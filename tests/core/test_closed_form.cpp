// Closed-form beam solutions and large-deflection elastica tables (issue 2, item 10).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "test_helpers.hpp"
#include "vibrissa/core/chain.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {
namespace {

using test::uniform_rod;

TEST(ClosedForm, UniformCantileverSmallTipLoad) {
  // y(s) = F s^3 / (3 E I) for a small normal tip load on a clamped uniform rod.
  const Whisker w = uniform_rod(100);
  const double L = w.length(), EI = w.base_bending_stiffness();
  const double F = 1e-6 * EI / (L * L);  // alpha = 1e-6: linear regime
  for (double s : {0.3 * L, 0.62 * L, L}) {
    const Solution sol = solve_force(w, F, s, 0.0);
    const double exact = F * s * s * s / (3.0 * EI);
    const double ds = L / 100;  // second order: relative error below (ds / s)^2
    EXPECT_NEAR(sol.contact_point_W.y() / exact, 1.0, (ds / s) * (ds / s)) << "s = " << s;
  }
}

TEST(ClosedForm, TaperedConeEquation4AndSlope) {
  // Spec eq. (4)-(5): a truncated cone loaded at a, deflection 4 F L a^3 / (3 E pi R^4 (L - a)), and slope
  // P Lc a^2 (3 Lc - 2 a) / (6 E I0 (Lc - a)^2).
  WhiskerProperties p;
  p.base = BaseJoint::rigid;
  p.links = 200;
  const double S = 0.05;
  const Whisker w = Whisker::from_parabola(S, 0.0, p);
  const double R = p.base_radius, Rt = R / p.taper_ratio, E = p.youngs_modulus;
  const double Lc = R / (R - Rt) * S;  // eq. (5)
  const double I0 = std::numbers::pi * std::pow(R, 4) / 4.0;
  for (double a : {0.2 * S, 0.5 * S, 0.8 * S}) {
    const double F = 1e-9;  // linear regime
    const Solution sol = solve_force(w, F, a, 0.0);
    const double y = 4.0 * F / (3.0 * E * std::numbers::pi * std::pow(R, 4)) * Lc * a * a * a / (Lc - a);
    EXPECT_NEAR(sol.contact_point_W.y() / y, 1.0, 3e-4) << "a/S = " << a / S;
    // Slope at the load: the follower force is normal to the whisker there, so the tangent is (F_y, -F_x).
    const auto c = deflect<double>(w, V3<double>(0, F, 0), V3<double>(0, 0, 0), a);
    const double slope = -c.force_B.x / c.force_B.y;
    const double exact_slope = F * Lc * a * a * (3 * Lc - 2 * a) / (6 * E * I0 * (Lc - a) * (Lc - a));
    EXPECT_NEAR(slope / exact_slope, 1.0, 3e-4) << "a/S = " << a / S;
  }
}

struct ElasticaCase {
  double alpha, v_over_L, foreshortening, angle;
};

TEST(ClosedForm, DeadTipLoadMattiasson) {
  // Mattiasson 1981 / Bisshopp-Drucker: uniform cantilever, vertical dead load at the tip, alpha = P L^2 / EI.
  for (const ElasticaCase& c : {ElasticaCase{1.0, 0.30172, 0.05643, 0.46135}, ElasticaCase{10.0, 0.81061, 0.55500, 1.430286}}) {
    const Whisker w = uniform_rod(100);
    const double L = w.length(), P = c.alpha * w.base_bending_stiffness() / (L * L);
    const Solution sol = solve_dead_load(w, Eigen::Vector3d(0, P, 0), L);
    ASSERT_EQ(sol.status, Status::converged) << sol.message;
    EXPECT_NEAR(sol.contact_point_W.y() / L, c.v_over_L, 2e-4) << "alpha " << c.alpha;
    EXPECT_NEAR((L - sol.contact_point_W.x()) / L, c.foreshortening, 2e-4) << "alpha " << c.alpha;
    const Eigen::Vector3d tip = sol.shape_W.back() - sol.shape_W[sol.shape_W.size() - 2];
    EXPECT_NEAR(std::atan2(tip.y(), tip.x()), c.angle, 5e-4) << "alpha " << c.alpha;
    EXPECT_NEAR((sol.force_W - Eigen::Vector3d(0, P, 0)).norm() / P, 0.0, 1e-10);
  }
}

TEST(ClosedForm, FollowerLoadElastica) {
  // The model's own load: force kept normal to the bent rod at s = a; alpha = P a^2 / EI = 1.
  const Whisker w = uniform_rod(100);
  const double a = w.length(), P = w.base_bending_stiffness() / (a * a);
  const Solution sol = solve_force(w, P, a, 0.0);
  EXPECT_NEAR(sol.contact_point_W.y() / a, 0.32064199, 3e-5);
  EXPECT_NEAR((a - sol.contact_point_W.x()) / a, 0.06435433, 1e-5);
  const Eigen::Vector3d tip = sol.shape_W.back() - sol.shape_W[sol.shape_W.size() - 2];
  EXPECT_NEAR(std::atan2(tip.y(), tip.x()), 0.49588464, 1e-7);
}

TEST(ClosedForm, PaperSchemeReproducesPublishedChainError) {
  // Issue 2: the published chain at N = 100 overshoots v/a by about 0.46 / N.
  const Whisker w = [] {
    WhiskerProperties p;
    p.taper_ratio = 1.0;
    p.scheme = Scheme::paper;
    return Whisker::from_parabola(0.05, 0.0, p);
  }();
  const double a = w.length(), P = w.base_bending_stiffness() / (a * a);
  const Solution sol = solve_force(w, P, a, std::numbers::pi);  // Elastica3D's ζ = π pushes toward +y here
  EXPECT_NEAR(sol.contact_point_W.y() / a - 0.32064199, 0.46 / 100, 2e-4);
}

TEST(ClosedForm, PureEndMomentBendsIntoCircularArc) {
  const Whisker w = uniform_rod(100);
  const double L = w.length(), EI = w.base_bending_stiffness();
  const double M = 0.5 * EI / L;  // curvature 0.5 / L: a 28.6 degree arc
  const double R = EI / M;
  std::vector<Eigen::Vector3d> omega(100), nodes;
  deflect<double>(w, V3<double>(0, 0, 0), V3<double>(0, 0, M), L, omega.data());
  deflected_nodes_B(w, omega.data(), nodes);
  const Eigen::Vector3d centre(0, R, 0);
  for (const auto& p : nodes) EXPECT_NEAR((p - centre).norm() / R, 1.0, 2e-5);
  const Eigen::Vector3d tip = nodes.back() - nodes[nodes.size() - 2];
  EXPECT_NEAR(std::atan2(tip.y(), tip.x()), L / R, 1e-12);  // the loaded link carries the tangent at s = L
  const Eigen::Vector3d mid = nodes[50] - nodes[49];      // interior links: chords of the arc
  EXPECT_NEAR(std::atan2(mid.y(), mid.x()), 49.5 * (L / 100) / R, 1e-12);
}

double follower_error(int links, Scheme scheme) {
  WhiskerProperties p;
  p.links = links;
  p.taper_ratio = 1.0;
  p.scheme = scheme;
  const Whisker w = Whisker::from_parabola(0.05, 0.0, p);
  const double a = w.length(), P = w.base_bending_stiffness() / (a * a);
  const double angle = scheme == Scheme::paper ? std::numbers::pi : 0.0;  // both push toward +y
  return solve_force(w, P, a, angle).contact_point_W.y() / a - 0.32064199;
}

TEST(Convergence, ObservedOrderMatchesEachScheme) {
  const double paper_order = std::log2(follower_error(50, Scheme::paper) / follower_error(100, Scheme::paper));
  const double second_order =
      std::log2(follower_error(50, Scheme::second_order) / follower_error(100, Scheme::second_order));
  EXPECT_NEAR(paper_order, 1.0, 0.05);
  EXPECT_NEAR(second_order, 2.0, 0.05);
  EXPECT_LT(std::abs(follower_error(100, Scheme::second_order)), 2e-5);
}

TEST(Convergence, TaperedCurvedWhiskerSecondOrder) {
  // No closed form: successive differences must fall by ~4 per halving of ds, also for a 3D load on a
  // curved, tapered rod (bend-twist coupling).
  auto tip = [](int n) {
    WhiskerProperties p;
    p.links = n;
    const Whisker w = Whisker::from_parabola(0.04, 12.0, p);
    return solve_force(w, 2e-4, 0.028, 0.7).contact_point_W;  // a node for every N
  };
  const Eigen::Vector3d a = tip(50), b = tip(100), c = tip(200);
  const double ratio = (a - b).norm() / (b - c).norm();
  EXPECT_GT(ratio, 3.5);
  EXPECT_LT(ratio, 4.5);
}

}  // namespace
}  // namespace vibrissa
