// Inertia and modes of the chain (dynamics/linear_model.hpp, dynamics/modes.hpp) against closed forms and an
// independent Euler-Bernoulli solution (euler_bernoulli.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "euler_bernoulli.hpp"
#include "vibrissa/array/morphology.hpp"
#include "vibrissa/core/whisker.hpp"
#include "vibrissa/dynamics/modes.hpp"
#include "vibrissa/io/dynamics_case.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa::dynamics {
namespace {

WhiskerProperties straight_props(int links, double base_radius = 100e-6) {
  WhiskerProperties p;
  p.links = links;
  p.base_radius = base_radius;
  return p;
}

/// Distinct bending frequencies of a straight whisker (each comes twice: bending about y and about z).
std::vector<double> bending_frequencies(const Modes& m, std::size_t count) {
  std::vector<double> f;
  for (int i = 0; i < m.count() && f.size() < count; ++i) {
    if (m.torsion_fraction(i) > 0.5) continue;
    if (!f.empty() && std::abs(m.frequency_hz(i) / f.back() - 1.0) < 1e-6) continue;
    f.push_back(m.frequency_hz(i));
  }
  return f;
}

TEST(DynamicsInertia, FrustumMassCentroidAndInertiaOfAStraightConeAreExact) {
  const Whisker w = Whisker::from_parabola(0.03, 0.0, straight_props(40));
  const double rho = 1300.0, r0 = 100e-6, r1 = r0 / 15.0, L = 0.03;
  const auto links = link_inertias(w, rho);
  double mass = 0.0, first = 0.0, Iz_base = 0.0;
  for (const auto& l : links) {
    mass += l.mass;
    first += l.mass * l.centroid_B.x();
    Iz_base += l.inertia_B(2, 2) + l.mass * l.centroid_B.x() * l.centroid_B.x();
    EXPECT_NEAR(l.centroid_B.y(), 0.0, 1e-15);
  }
  // Whole frustum: m = rho pi L (r0^2 + r0 r1 + r1^2) / 3, first moment rho pi L^2 (r0^2 + 2 r0 r1 + 3 r1^2) / 12.
  const double m_exact = rho * std::numbers::pi * L * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
  const double first_exact = rho * std::numbers::pi * L * L * (r0 * r0 + 2 * r0 * r1 + 3 * r1 * r1) / 12.0;
  EXPECT_NEAR(mass / m_exact, 1.0, 1e-13);
  EXPECT_NEAR(first / first_exact, 1.0, 1e-13);
  // About the base, transverse: integral of rho pi r^2 x^2 (+ r^4 / 4, the section's own): r = r0 + (r1 - r0) x / L.
  double Iz_exact = 0.0;
  for (int i = 0; i < 20000; ++i) {  // midpoint rule, error ~1e-9 relative
    const double x = (i + 0.5) * L / 20000, r = r0 + (r1 - r0) * x / L;
    Iz_exact += rho * std::numbers::pi * (r * r * x * x + std::pow(r, 4) / 4.0) * L / 20000;
  }
  EXPECT_NEAR(Iz_base / Iz_exact, 1.0, 1e-8);
}

TEST(DynamicsModel, MassAndStiffnessAreSymmetricPositiveDefinite) {
  const Whisker w = Whisker::from_parabola(0.03, 20.0, straight_props(30));
  const LinearModel m = linear_model(w, DynamicsProperties{});
  EXPECT_LT((m.mass - m.mass.transpose()).norm(), 1e-14 * m.mass.norm());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m.mass).eigenvalues().minCoeff(), 0.0);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m.stiffness).eigenvalues().minCoeff(), 0.0);
  // The mass matrix is the kinetic energy: a rigid turn of the whole whisker about the base by theta_0 alone
  // (every link follows joint 0) has T = theta' . I_base theta' / 2 with I_base about the base point.
  Eigen::Matrix3d I_base = Eigen::Matrix3d::Zero();
  for (const auto& l : m.links) {
    const Eigen::Vector3d c = l.centroid_B;
    I_base += l.inertia_B + l.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  }
  EXPECT_LT((m.mass.topLeftCorner<3, 3>() - I_base).norm(), 1e-12 * I_base.norm());
}

TEST(DynamicsModel, StiffnessIsTheQuasiStaticChainsForSmallLoads) {
  // The static deflection K^-1 Q under a small dead load at s (the initial state of a release) is the
  // quasi-static solve's (core/chain.hpp walk) to first order: their difference is O(F^2).
  WhiskerProperties p = straight_props(50);
  p.base_stiffness = 2e-5;  // the follicle spring in series too
  const Whisker w = Whisker::from_parabola(0.03, 18.0, p);
  const LinearModel model = linear_model(w, DynamicsProperties{});
  auto relative_gap = [&](double f) {
    const Eigen::Vector3d F(0.2 * f, f, -0.5 * f);
    nlohmann::json j = {{"initial", {{"force", {F.x(), F.y(), F.z()}}, {"arc_length", 0.021}}}};
    const io::DynamicsCase c = io::dynamics_case_from_json(j, w);
    const Eigen::VectorXd q = io::initial_state(c, model).q;
    const Solution s = solve_dead_load(w, F, 0.021);
    EXPECT_EQ(s.status, Status::converged);
    // The quasi-static tip against the linear model's tip.
    const Eigen::Vector3d tip_linear = w.rest_nodes_B().back() +
                                       model.node_displacement.bottomRows<3>() * q;
    const Eigen::Vector3d tip = w.placement().to_body(s.shape_W.back());
    return (tip - tip_linear).norm() / (tip - w.rest_nodes_B().back()).norm();
  };
  const double small = relative_gap(1e-7), smaller = relative_gap(1e-8);
  EXPECT_LT(small, 1e-2);
  EXPECT_NEAR(small / smaller, 10.0, 0.5);  // the gap is first order in F relative to a first-order deflection
}

TEST(DynamicsModes, FirstThreeBendingFrequenciesMatchEulerBernoulliAndConverge) {
  // Straight cone, r0 = 100 um, taper 15, L = 30 mm, E = 3.3 GPa, rho = 1300 kg/m^3.
  const double L = 0.03, r0 = 100e-6, E = 3.3e9, rho = 1300.0;
  const auto ref = test::euler_bernoulli_frequencies(L, r0, r0 / 15.0, E, rho, 400, 3);
  const auto ref_eb = test::euler_bernoulli_frequencies(L, r0, r0 / 15.0, E, rho, 400, 3, false);
  std::printf("Euler-Bernoulli f [Hz]: %.6f %.6f %.6f; with rotary inertia: %.6f %.6f %.6f\n", ref_eb[0],
              ref_eb[1], ref_eb[2], ref[0], ref[1], ref[2]);
  DynamicsProperties dp;
  dp.density = rho;
  std::vector<std::vector<double>> err;
  for (int N : {25, 50, 100, 200}) {
    const Whisker w = Whisker::from_parabola(L, 0.0, straight_props(N));
    const auto f = bending_frequencies(modes(w, dp, 12), 3);
    ASSERT_EQ(f.size(), 3u);
    std::vector<double> e;
    for (int i = 0; i < 3; ++i) e.push_back(f[static_cast<std::size_t>(i)] / ref[static_cast<std::size_t>(i)] - 1.0);
    if (N == 100) {
      for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_LT(std::abs(e[i]), 0.01);
        EXPECT_LT(std::abs(f[i] / ref_eb[i] - 1.0), 0.01);  // the classical beam without rotary inertia too
      }
    }
    std::printf("N = %d: f/f_EB - 1 = %.3e %.3e %.3e\n", N, e[0], e[1], e[2]);
    err.push_back(e);
  }
  // Second order in 1/N: doubling N divides the error by about four (measured 3.9-4.8, docs/dynamics.md).
  for (std::size_t k = 1; k < err.size(); ++k)
    for (std::size_t i = 0; i < 3; ++i) {
      const double ratio = err[k - 1][i] / err[k][i];
      EXPECT_GT(ratio, 3.3) << "N step " << k << " mode " << i;
      EXPECT_LT(ratio, 5.0) << "N step " << k << " mode " << i;
    }
}

TEST(DynamicsModes, FundamentalScalesWithBaseRadiusOverLengthSquared) {
  // Euler-Bernoulli cone: f1 = c r0 / L^2 sqrt(E / rho) (the section's rotary inertia, O((r/L)^2), aside).
  DynamicsProperties dp;
  auto f1 = [&](double L, double r0) {
    return bending_frequencies(modes(Whisker::from_parabola(L, 0.0, straight_props(60, r0)), dp, 4), 1)[0];
  };
  const double base = f1(0.03, 100e-6);
  EXPECT_NEAR(f1(0.03, 150e-6) / base, 1.5, 1e-4);
  EXPECT_NEAR(f1(0.045, 100e-6) / base, 1.0 / 2.25, 1e-4);
}

TEST(DynamicsModes, FundamentalsOfTheRatArrayAgainstTheMeasuredRange) {
  // Hartmann et al. 2003 (J. Neurosci. 23:6510): isolated rat whiskers clamped at the base resonate at 27-260 Hz
  // (first mode), mostly depending on length. The Towal 2011 array's whiskers (lengths, base radii; E = 3.3 GPa,
  // taper 15, default density), clamped: every whisker of 14 mm or longer falls in that range, the longest
  // (~50 mm) near its low end. The five short anterior whiskers (3-13 mm) lie above it (the abstract does not
  // give the lengths measured; docs/dynamics.md lists all 31).
  double lo = 1e9, hi_long = 0.0;
  for (const auto& spec : array::towal2011().whiskers) {
    const Whisker w = array::make_rest_whisker(spec, 40);
    const double f1 = modes(w, DynamicsProperties{}, 1).frequency_hz(0);
    std::printf("  %-3s L = %5.1f mm, r0 = %5.1f um: f1 = %7.1f Hz\n", spec.name.c_str(), spec.arc_length * 1e3,
                spec.base_radius * 1e6, f1);
    lo = std::min(lo, f1);
    if (spec.arc_length >= 0.014) hi_long = std::max(hi_long, f1);
  }
  EXPECT_GE(lo, 27.0);
  EXPECT_LE(lo, 27.0 * 1.3);
  EXPECT_LE(hi_long, 260.0);
}

TEST(DynamicsModes, DampingRatiosFollowTheJointDampers) {
  DynamicsProperties dp;
  dp.damping_ratio = 0.14;
  const Modes m = modes(Whisker::from_parabola(0.03, 15.0, straight_props(50)), dp, 6);
  EXPECT_NEAR(m.damping_ratio(0), 0.14, 1e-12);
  for (int i = 1; i < 6; ++i) EXPECT_NEAR(m.damping_ratio(i) / m.damping_ratio(0), m.omega(i) / m.omega(0), 1e-12);
}

TEST(DynamicsModes, PaperSchemeIsRejectedWithItsName) {
  WhiskerProperties p = straight_props(20);
  p.scheme = Scheme::paper;
  const Whisker w = Whisker::from_parabola(0.03, 10.0, p);
  try {
    (void)linear_model(w, DynamicsProperties{});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("whisker.scheme"), std::string::npos);
  }
  DynamicsProperties bad;
  bad.density = -1.0;
  EXPECT_THROW((void)linear_model(Whisker::from_parabola(0.03, 10.0, straight_props(20)), bad), std::invalid_argument);
  // Finite but absurd values are refused naming the field (a damping ratio of 1e308 made the integrator run
  // without end; a density of 1e308 failed inside the eigensolver).
  const auto message = [](const DynamicsProperties& props) {
    try {
      validate(props);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  DynamicsProperties dense;
  dense.density = 1e308;
  EXPECT_NE(message(dense).find("dynamics.density must lie in (0, 1e5]"), std::string::npos) << message(dense);
  DynamicsProperties damped;
  damped.damping_ratio = 1e308;
  EXPECT_NE(message(damped).find("dynamics.damping_ratio must lie in [0, 1e6], got 1e+308"), std::string::npos)
      << message(damped);
  damped.damping_ratio = 1e6;
  EXPECT_EQ(message(damped), "accepted");
  DynamicsProperties slow;
  slow.joint_damping_time = 1e308;
  EXPECT_NE(message(slow).find("dynamics.joint_damping_time"), std::string::npos) << message(slow);
}

// A surface in a dynamics case with an invalid field: the message names the object and the field and value.
TEST(DynamicsCase, AnInvalidSurfaceNamesTheObjectAndTheField) {
  const Whisker w = Whisker::from_parabola(0.03, 10.0, straight_props(20));
  auto message = [&](const nlohmann::json& object) {
    const nlohmann::json j = {{"objects", nlohmann::json::array({{{"type", "peg"}, {"point", {0.02, 0.0, 0.0}},
                                                                   {"radius", 0.001}},
                                                                  object})}};
    try {
      (void)io::dynamics_case_from_json(j, w);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string radius = message({{"type", "sphere"}, {"centre", {0.02, 0.01, 0.0}}, {"radius", -1.0}});
  EXPECT_NE(radius.find("objects[1]"), std::string::npos) << radius;
  EXPECT_NE(radius.find("radius"), std::string::npos) << radius;
  EXPECT_NE(radius.find("-1"), std::string::npos) << radius;
  const std::string centre = message({{"type", "sphere"}, {"centre", "x"}, {"radius", 0.002}});
  EXPECT_EQ(centre.rfind("objects[1].centre", 0), 0u) << centre;
}

}  // namespace
}  // namespace vibrissa::dynamics
