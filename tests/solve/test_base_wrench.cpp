// The base-wrench inverse (docs/inverse.md): force mode -> base wrench -> inverse recovers (s, f, zeta);
// the linearised covariance equals the one built from finite-difference Jacobians of force mode; reduced
// signal sets are flagged when they cannot determine the contact.
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

#include "../core/test_helpers.hpp"
#include "vibrissa/solve/base_wrench.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {
namespace {

using test::deg;

double angle_difference(double a, double b) { return std::remainder(a - b, 2.0 * std::numbers::pi); }

/// A 3D whisker from points: curved in y, curling slightly out of plane (z), 35 mm.
Whisker real_shaped(Scheme scheme, std::optional<double> base_stiffness = std::nullopt) {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i <= 60; ++i) {
    const double x = 0.033 * i / 60.0;
    pts.emplace_back(x, 14.0 * x * x - 60.0 * x * x * x, 120.0 * x * x * x);
  }
  WhiskerProperties p;
  p.links = 80;
  p.scheme = scheme;
  p.base_stiffness = base_stiffness;
  const Pose pose{{0.001, -0.002, 0.003}, 0.4, -0.2, 0.7};
  return Whisker::from_points(pts, p, pose);
}

// The round trips put the contact inside a link, not on a node: the forward map has a kink at each node (the
// loaded joint's weight and, in the paper scheme, the re-mesh change there), where the inverse and central
// differences are accurate to ~1e-7 relative rather than 1e-9.
void expect_round_trip(const Whisker& w, double f, double s, double zeta) {
  const Solution fwd = solve_force(w, f, s, zeta);
  const BaseWrenchResult inv = solve_base_wrench(w, fwd.force_W, fwd.moment_W);
  ASSERT_EQ(inv.solution.status, Status::converged) << "f=" << f << " s=" << s << " zeta=" << zeta;
  EXPECT_NEAR(inv.solution.arc_length, s, 1e-9 * s) << "f=" << f << " s=" << s << " zeta=" << zeta;
  EXPECT_NEAR(inv.solution.force_magnitude, f, 1e-9 * f) << "f=" << f << " s=" << s << " zeta=" << zeta;
  EXPECT_NEAR(angle_difference(inv.solution.angle, zeta), 0.0, 1e-9) << "f=" << f << " s=" << s;
  EXPECT_LT((inv.solution.contact_point_W - fwd.contact_point_W).norm(), 1e-9 * w.length());
  EXPECT_TRUE(inv.identifiability.identifiable);
  EXPECT_EQ(inv.roots.size(), 1U);
}

TEST(BaseWrench, RoundTripParabolic) {
  const Whisker w = test::rat_whisker(100, Pose{{0.01, 0.02, -0.01}, 0.3, 0.2, -0.5});
  // Contact anywhere but the distal tenth, forces from 20 uN to 0.2 mN (base moments up to ~0.6 E I_0 / L).
  for (double frac : {0.045, 0.305, 0.555, 0.725, 0.875})
    for (double zeta : {0.0, deg(50), deg(-120), deg(180), deg(265)})
      for (double f : {2e-5, 2e-4}) expect_round_trip(w, f, frac * w.length(), zeta);
}

TEST(BaseWrench, RoundTripRealShapedBothSchemesAndFollicleSpring) {
  for (Scheme scheme : {Scheme::second_order, Scheme::paper}) {
    const Whisker w = real_shaped(scheme, scheme == Scheme::paper ? std::optional<double>(5e-5) : std::nullopt);
    for (double frac : {0.156, 0.456, 0.82})
      for (double zeta : {deg(20), deg(-75), deg(140)}) expect_round_trip(w, 1.5e-4, frac * w.length(), zeta);
  }
}

TEST(BaseWrench, ReducedSquareSetRoundTrip) {
  // Fx, My, Mz: three equations, three unknowns. The true contact must be among the roots.
  const Whisker w = test::rat_whisker();
  BaseWrenchOptions o;
  o.signals = SignalSet::bending_axial();
  for (double frac : {0.3, 0.7}) {
    const double s = frac * w.length(), f = 5e-4, zeta = deg(35);
    const Solution fwd = solve_force(w, f, s, zeta);
    const BaseWrenchResult inv = solve_base_wrench(w, fwd.force_W, fwd.moment_W, o);
    ASSERT_EQ(inv.solution.status, Status::converged);
    bool found = false;
    for (const auto& r : inv.roots)
      found = found || (std::abs(r.arc_length - s) < 1e-9 * s && std::abs(r.force_magnitude - f) < 1e-9 * f &&
                        std::abs(angle_difference(r.angle, zeta)) < 1e-9);
    EXPECT_TRUE(found) << "frac " << frac;
    for (std::size_t i = 1; i < inv.roots.size(); ++i) EXPECT_GE(inv.roots[i].chi2, inv.roots[i - 1].chi2 - 1e-9);
  }
}

/// Base signals (Fx..Mz in B, SI) of force mode at (s, f, zeta).
Eigen::Matrix<double, 6, 1> signals(const Whisker& w, double s, double f, double zeta) {
  const Solution r = solve_force(w, f, s, zeta);
  Eigen::Matrix<double, 6, 1> out;
  out << r.whisker_frame.force, r.whisker_frame.moment;
  return out;
}

TEST(BaseWrench, CovarianceMatchesFiniteDifferenceJacobian) {
  const Whisker w = test::rat_whisker(100, Pose{{0, 0, 0}, 0.2, 0.1, 0.3});
  const double s = 0.0222, f = 3e-4, zeta = deg(40);  // mid-link (see expect_round_trip)
  BaseWrenchOptions o;
  Eigen::Matrix<double, 6, 1> sd;
  sd << 2e-6, 2e-6, 3e-6, 1e-8, 2e-8, 2e-8;
  o.noise_covariance = sd.array().square().matrix().asDiagonal();
  o.noise_covariance(4, 5) = o.noise_covariance(5, 4) = 0.5 * 2e-8 * 2e-8;
  const Solution fwd = solve_force(w, f, s, zeta);
  const BaseWrenchResult inv = solve_base_wrench(w, fwd.force_W, fwd.moment_W, o);
  ASSERT_TRUE(inv.identifiability.identifiable);

  // Central differences of force mode in (s, f, zeta), and of the contact point.
  const double h[3] = {1e-6 * w.length(), 1e-6 * f, 1e-6};
  Eigen::Matrix<double, 6, 3> J;
  Eigen::Matrix3d P;
  for (int k = 0; k < 3; ++k) {
    double a[3] = {s, f, zeta}, b[3] = {s, f, zeta};
    a[k] += h[k];
    b[k] -= h[k];
    J.col(k) = (signals(w, a[0], a[1], a[2]) - signals(w, b[0], b[1], b[2])) / (2 * h[k]);
    P.col(k) = (solve_force(w, a[1], a[0], a[2]).contact_point_W - solve_force(w, b[1], b[0], b[2]).contact_point_W) /
               (2 * h[k]);
  }
  const Eigen::Matrix3d C = (J.transpose() * o.noise_covariance.inverse() * J).inverse();
  const Eigen::Matrix3d Cp = P * C * P.transpose();
  EXPECT_LT((inv.identifiability.covariance - C).norm(), 1e-5 * C.norm());
  EXPECT_LT((inv.identifiability.contact_point_covariance_W - Cp).norm(), 1e-5 * Cp.norm());
  EXPECT_GT(inv.identifiability.condition_number, 1.0);
  EXPECT_TRUE(std::isfinite(inv.identifiability.condition_number));
}

TEST(BaseWrench, BendingMomentsAloneAreUnderdeterminedAlongTheNullDirection) {
  const Whisker w = test::rat_whisker();
  const double s = 0.02, f = 4e-4, zeta = deg(30);
  const Solution fwd = solve_force(w, f, s, zeta);
  BaseWrenchOptions o;
  o.signals = SignalSet::bending();
  const BaseWrenchResult inv = solve_base_wrench(w, fwd.force_W, fwd.moment_W, o);
  ASSERT_EQ(inv.solution.status, Status::underdetermined);
  EXPECT_FALSE(inv.identifiability.identifiable);
  EXPECT_TRUE(std::isinf(inv.identifiability.condition_number));
  // Every reported fit reproduces M_y and M_z.
  for (const auto& r : inv.roots) {
    const Solution g = solve_force(w, r.force_magnitude, r.arc_length, r.angle);
    EXPECT_NEAR(g.whisker_frame.moment.y(), fwd.whisker_frame.moment.y(), 1e-9 * fwd.whisker_frame.MB);
    EXPECT_NEAR(g.whisker_frame.moment.z(), fwd.whisker_frame.moment.z(), 1e-9 * fwd.whisker_frame.MB);
  }
  // Moving along the null direction (ds/L, df/F_unit, dzeta) leaves M_y, M_z unchanged to first order.
  const double L = w.length(), Fu = w.base_bending_stiffness() / (L * L);
  const Eigen::Vector3d v = inv.identifiability.null_direction;
  const double t = 1e-6;
  const auto& x = inv.solution;
  const Solution a = solve_force(w, x.force_magnitude + t * v[1] * Fu, x.arc_length + t * v[0] * L, x.angle + t * v[2]);
  const Solution b = solve_force(w, x.force_magnitude - t * v[1] * Fu, x.arc_length - t * v[0] * L, x.angle - t * v[2]);
  const Eigen::Vector2d dM(a.whisker_frame.moment.y() - b.whisker_frame.moment.y(),
                           a.whisker_frame.moment.z() - b.whisker_frame.moment.z());
  const double Mu = Fu * L;
  EXPECT_LT(dM.norm() / (2 * t * Mu), 1e-5);
  // ...while a step across it does not.
  const Solution c = solve_force(w, x.force_magnitude * (1 + 1e-3), x.arc_length, x.angle);
  EXPECT_GT(std::abs(c.whisker_frame.MB - x.whisker_frame.MB), 1e-4 * x.whisker_frame.MB);
}

TEST(BaseWrench, BendingMomentsAloneAreNeverReportedConverged) {
  // The case of issue 22: from My, Mz alone a fit far from the truth (s = 21.6 mm) explains the signals
  // exactly; it must be flagged underdetermined, with a warning naming the signals, and never converged.
  const Whisker w = test::rat_whisker();
  BaseWrenchOptions o;
  o.signals = SignalSet::bending();
  for (double s : {0.0054, 0.0216, 0.032})
    for (double zeta : {deg(40), deg(-110)}) {
      const Solution fwd = solve_force(w, 1e-4, s, zeta);
      const BaseWrenchResult inv = solve_base_wrench(w, fwd.force_W, fwd.moment_W, o);
      EXPECT_EQ(inv.solution.status, Status::underdetermined) << "s=" << s << " zeta=" << zeta;
      EXPECT_EQ(inv.solution.contact_state, ContactState::contact);
      EXPECT_LT(inv.chi2, 1e-6);  // the signals are explained...
      const auto warnings = base_wrench_warnings(inv);  // ...and the user is told they do not locate the contact
      ASSERT_EQ(warnings.size(), 1U);
      EXPECT_EQ(warnings[0].rfind("underdetermined: the signals bending (2 equations)", 0), 0U) << warnings[0];
    }
  // Adding the axial force makes the same contact identifiable: converged, no warning.
  const Solution fwd = solve_force(w, 1e-4, 0.0218, deg(40));
  o.signals = SignalSet::bending_axial();
  const BaseWrenchResult inv = solve_base_wrench(w, fwd.force_W, fwd.moment_W, o);
  EXPECT_EQ(inv.solution.status, Status::converged);
  EXPECT_NEAR(inv.solution.arc_length, 0.0218, 1e-9);
  EXPECT_TRUE(base_wrench_warnings(inv).empty());
}

TEST(BaseWrench, NoisySignalsGiveAStationaryFitNearTheTruth) {
  const Whisker w = test::rat_whisker();
  const double s = 0.025, f = 5e-4, zeta = deg(-20);
  const Solution fwd = solve_force(w, f, s, zeta);
  BaseWrenchOptions o;
  const double sf = 1e-6, sm = 1e-8;
  o.noise_covariance = Eigen::Matrix<double, 6, 1>(sf * sf, sf * sf, sf * sf, sm * sm, sm * sm, sm * sm).asDiagonal();
  // A fixed perturbation of about one standard deviation (inconsistent with any contact: M·F != 0).
  const Eigen::Vector3d dF(0.8 * sf, -1.1 * sf, 0.5 * sf), dM(-0.7 * sm, 1.2 * sm, 0.9 * sm);
  const BaseWrenchResult inv =
      solve_base_wrench(w, fwd.force_W + w.placement().R_WB * dF, fwd.moment_W + w.placement().R_WB * dM, o);
  ASSERT_EQ(inv.solution.status, Status::converged);
  EXPECT_GT(inv.chi2, 0.0);
  EXPECT_LT(inv.chi2, 6.0);
  EXPECT_NEAR(inv.solution.residual, std::sqrt(inv.chi2), 1e-15);
  const double sd_s = std::sqrt(inv.identifiability.covariance(0, 0));
  EXPECT_LT(std::abs(inv.solution.arc_length - s), 5 * sd_s);
}

TEST(BaseWrench, SeriesWarmStartsMatchColdSolves) {
  const Whisker w = test::rat_whisker();
  std::vector<Eigen::Vector3d> F, M;
  for (int k = 0; k < 8; ++k) {
    const Solution r = solve_force(w, 1e-4 * (1 + k), 0.0122 + 0.002 * k, deg(10.0 * k));
    F.push_back(r.force_W);
    M.push_back(r.moment_W);
  }
  const auto series = solve_base_wrench_series(w, w.placement(), F, M);
  ASSERT_EQ(series.size(), F.size());
  for (std::size_t k = 0; k < F.size(); ++k) {
    const BaseWrenchResult cold = solve_base_wrench(w, F[k], M[k]);
    EXPECT_EQ(series[k].solution.status, Status::converged);
    EXPECT_NEAR(series[k].solution.arc_length, cold.solution.arc_length, 1e-9 * cold.solution.arc_length);
    EXPECT_NEAR(series[k].solution.force_magnitude, cold.solution.force_magnitude,
                1e-9 * cold.solution.force_magnitude);
  }
}

TEST(BaseWrench, ZeroSignalsAreNoContactAndBadInputThrows) {
  const Whisker w = test::rat_whisker();
  const BaseWrenchResult none = solve_base_wrench(w, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_EQ(none.solution.status, Status::no_contact);
  EXPECT_EQ(none.solution.force_magnitude, 0.0);
  const Eigen::Vector3d F(0, 1e-4, 0), M(0, 0, 1e-6);
  EXPECT_THROW(solve_base_wrench(w, Eigen::Vector3d(NAN, 0, 0), M), std::invalid_argument);
  BaseWrenchOptions o;
  o.noise_covariance = Eigen::MatrixXd::Identity(3, 3);
  EXPECT_THROW(solve_base_wrench(w, F, M, o), std::invalid_argument);  // 6 signals need 6 x 6
  o.noise_covariance = -Eigen::MatrixXd::Identity(6, 6);
  EXPECT_THROW(solve_base_wrench(w, F, M, o), std::invalid_argument);
  EXPECT_THROW(SignalSet::parse("Fx,Mq"), std::invalid_argument);
  EXPECT_THROW(SignalSet::parse("My,My"), std::invalid_argument);
  EXPECT_EQ(SignalSet::parse("My, Mz"), SignalSet::bending());
  EXPECT_EQ(SignalSet::parse("Fx,My,Mz").name(), "bending_axial");
  EXPECT_EQ(SignalSet::parse("Fy,Mx").name(), "Fy,Mx");
}

}  // namespace
}  // namespace vibrissa

namespace vibrissa {
namespace {

// Contacts drawn over the whole whisker, distal tip included, forces over three decades: a fit that does not
// explain the signals is never reported as converged, and all but a few large deflections near the tip (a
// documented limit, docs/inverse.md) come back exactly.
TEST(BaseWrench, RandomContactsIncludingTheTipRoundTrip) {
  const Whisker w = test::rat_whisker(100, Pose{{0.0, 0.0, 0.0}, 0.2, 0.1, 0.3});
  std::uint64_t state = 12345;
  auto uniform = [&state] {  // SplitMix64: the same cases on every platform
    state += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  int recovered = 0, cases = 0;
  for (int k = 0; k < 100; ++k) {
    const double s = (0.03 + 0.95 * uniform()) * w.length();
    const double f = 1e-6 * std::pow(2000.0, uniform());
    const double zeta = 2.0 * std::numbers::pi * uniform();
    const Solution fwd = solve_force(w, f, s, zeta);
    const BaseWrenchResult inv = solve_base_wrench(w, fwd.force_W, fwd.moment_W);
    ++cases;
    if (inv.solution.status != Status::converged) continue;
    const bool same = std::abs(inv.solution.arc_length - s) <= 1e-9 * s &&
                      std::abs(inv.solution.force_magnitude - f) <= 1e-9 * f;
    EXPECT_TRUE(same) << "converged to another contact: s=" << s << " f=" << f << " zeta=" << zeta
                      << " -> s=" << inv.solution.arc_length << " chi2=" << inv.chi2;
    recovered += same;
  }
  EXPECT_GE(recovered, cases - 6) << recovered << " of " << cases;
}

}  // namespace
}  // namespace vibrissa
