// Modes about a deflected equilibrium (dynamics/deflected_modes.hpp): zero load gives the modes about rest, the
// tangent stiffness agrees with finite differences of the equilibrium equations, the equilibrium is the
// quasi-static solve's, and a pinned tip gives a propped cantilever's frequency.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "vibrissa/core/whisker.hpp"
#include "vibrissa/dynamics/deflected_modes.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa::dynamics {
namespace {

Whisker curved(int links) {
  WhiskerProperties p;
  p.links = links;
  p.base_stiffness = 2e-5;  // follicle spring in series at joint 0
  return Whisker::from_parabola(0.03, 15.0, p);
}

TEST(DynamicsDeflectedModes, ZeroLoadGivesTheModesAboutRest) {
  const Whisker w = curved(40);
  const DynamicsProperties props;
  const Modes rest = modes(w, props, 8);
  HeldLoad load;
  load.arc_length = 0.02;
  const DeflectedModes d = deflected_modes(w, props, load, {}, 8);
  EXPECT_EQ(d.equilibrium.iterations, 0);
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(d.modes.frequency_hz(i) / rest.frequency_hz(i), 1.0, 1e-8) << i;
    EXPECT_NEAR(d.modes.damping_ratio(i) / rest.damping_ratio(i), 1.0, 1e-8) << i;
    EXPECT_NEAR((d.modes.node_shapes.col(i) - rest.node_shapes.col(i)).norm(), 0.0, 1e-6) << i;
  }
}

/// Rotation of link k of a configuration (independent of the library: Eigen's angle-axis).
Eigen::Matrix3d link_rotation(const JointRotations& omega, std::size_t k) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  for (std::size_t j = 0; j <= k; ++j)
    if (omega[j].norm() > 0.0) R = R * Eigen::AngleAxisd(omega[j].norm(), omega[j].normalized()).toRotationMatrix();
  return R;
}

TEST(DynamicsDeflectedModes, TangentStiffnessAgreesWithFiniteDifferences) {
  const Whisker w = curved(12);
  const double s = 0.021;  // inside link 8
  int k = 0;
  double h = 0.0;
  w.locate(s, k, h);
  const Eigen::Vector3d F(-6e-6, 5e-5, 2.4e-5);  // bends in both planes and twists the curved whisker
  for (const bool follower : {false, true}) {
    HeldLoad load;
    load.arc_length = s;
    load.force_B = F;
    load.follower = follower;
    const HeldEquilibrium eq = held_equilibrium(w, load, {});
    ASSERT_LT(eq.residual, 1e-10);
    const double tip = (chain_nodes_B(w, eq.omega).back() - w.rest_nodes_B().back()).norm();
    EXPECT_GT(tip, 0.1 * w.length());  // a large deflection: the geometric stiffness matters
    const Eigen::MatrixXd K = tangent_stiffness(w, eq.omega, F, s, follower);
    const Eigen::Index n = K.rows();
    const Eigen::Matrix3d Rk = link_rotation(eq.omega, static_cast<std::size_t>(k));
    Eigen::MatrixXd fd(n, n);
    const double eps = 1e-6;
    for (Eigen::Index c = 0; c < n; ++c) {
      Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
      d(c) = eps;
      const JointRotations plus = apply_increments(eq.omega, d), minus = apply_increments(eq.omega, -d);
      auto force = [&](const JointRotations& o) -> Eigen::Vector3d {
        return follower ? Eigen::Vector3d(link_rotation(o, static_cast<std::size_t>(k)) * Rk.transpose() * F) : F;
      };
      fd.col(c) = (equilibrium_residual(w, plus, force(plus), s) - equilibrium_residual(w, minus, force(minus), s)) /
                  (2.0 * eps);
    }
    EXPECT_LT((K - fd).norm() / K.norm(), 1e-7) << "follower " << follower;
    std::printf("follower %d: tip moved %.3g mm, |K_T - FD| / |K_T| = %.2e, asymmetry %.2e\n", follower ? 1 : 0,
                tip * 1e3, (K - fd).norm() / K.norm(), (K - K.transpose()).norm() / K.norm());
    // The load's geometric stiffness is a sizeable part of K_T here (so the comparison tests it).
    const Eigen::MatrixXd Ks = tangent_stiffness(w, eq.omega, Eigen::Vector3d::Zero(), s, false);
    EXPECT_GT((K - Ks).norm() / K.norm(), 1e-3);
  }
}

TEST(DynamicsDeflectedModes, EquilibriumIsTheQuasiStaticSolves) {
  // A dead load at a node (the dynamic chain's links are rigid; the static walk weights the loaded joint by where
  // on its link the load acts, which coincides at a node): the tips agree to the Newton tolerance.
  const Whisker w = curved(50);
  const double s = w.node_arc_lengths()[40];
  const Eigen::Vector3d F(0.0, 2e-5, 5e-6);
  const Solution sol = solve_dead_load(w, F, s, SolveOptions{});
  ASSERT_EQ(sol.status, Status::converged);
  HeldLoad load;
  load.arc_length = s;
  load.force_B = F;
  const HeldEquilibrium eq = held_equilibrium(w, load, {});
  const Eigen::Vector3d tip = chain_nodes_B(w, eq.omega).back();
  const Eigen::Vector3d rest = w.rest_nodes_B().back();
  EXPECT_GT((tip - rest).norm(), 0.05 * w.length());
  EXPECT_LT((tip - sol.shape_W.back()).norm() / (tip - rest).norm(), 1e-9);
  std::printf("dead load at node 40 of 50: tip moved %.3g mm, |tip - quasi-static tip| / that = %.2e\n",
              (tip - rest).norm() * 1e3, (tip - sol.shape_W.back()).norm() / (tip - rest).norm());
}

TEST(DynamicsDeflectedModes, PinnedTipGivesAProppedCantilever) {
  // A uniform straight beam clamped at the base: free tip f1 = (1.8751^2 / 2 pi) sqrt(EI / (rho A L^4)); pinned tip
  // (propped cantilever) (3.9266 / 1.8751)^2 = 4.3852 times higher (roots of cos cosh = -1 and tan = tanh).
  WhiskerProperties p;
  p.links = 100;
  p.taper_ratio = 1.0;
  const Whisker w = Whisker::from_parabola(0.03, 0.0, p);
  DynamicsProperties props;
  props.damping_ratio = 0.0;
  const Modes free = modes(w, props, 2);
  const double b1 = 1.8751040687119611, p1 = 3.9266023120479220;
  HeldLoad load;
  load.arc_length = w.length();
  load.contact = ContactModel::stick;
  const DeflectedModes stuck = deflected_modes(w, props, load, {}, 4);
  EXPECT_EQ(stuck.constraints, 2);  // the tip of a straight beam cannot move axially to first order
  const double ratio = (p1 * p1) / (b1 * b1);
  EXPECT_NEAR(stuck.modes.frequency_hz(0) / free.frequency_hz(0), ratio, 5e-4 * ratio);
  EXPECT_NEAR(stuck.modes.frequency_hz(1) / free.frequency_hz(0), ratio, 5e-4 * ratio);
  // Slip along y only: the tip can still move in z (free cantilever), the y bending is propped.
  load.contact = ContactModel::slip;
  load.normal_B = Eigen::Vector3d::UnitY();
  std::printf("pinned tip: f1 ratio %.6f vs %.6f (%.2e)\n", stuck.modes.frequency_hz(0) / free.frequency_hz(0), ratio,
              stuck.modes.frequency_hz(0) / free.frequency_hz(0) / ratio - 1.0);
  const DeflectedModes slip = deflected_modes(w, props, load, {}, 4);
  EXPECT_EQ(slip.constraints, 1);
  EXPECT_NEAR(slip.modes.frequency_hz(0) / free.frequency_hz(0), 1.0, 1e-6);
  EXPECT_GT(std::abs(slip.modes.node_shapes(3 * 100 + 2, 0)), 0.99);  // tip moves in z
  EXPECT_NEAR(slip.modes.frequency_hz(1) / free.frequency_hz(0), ratio, 5e-4 * ratio);
}

TEST(DynamicsDeflectedModes, APegContactStiffensTheWhisker) {
  // A point contact from the quasi-static solve, held stuck: the equilibrium keeps the contact point, its reaction
  // is the quasi-static force to within the loaded joint's weighting, and the lowest frequency rises above rest.
  const Whisker w = curved(60);
  const Solution sol = solve_point(w, Eigen::Vector3d(0.02, 0.003, 0.0));
  ASSERT_EQ(sol.status, Status::converged);
  HeldLoad load;
  load.arc_length = sol.arc_length;
  load.force_B = sol.force_W;
  load.contact = ContactModel::stick;
  load.contact_point_B = sol.contact_point_W;  // the whisker's placement is the world frame here
  const DeflectedModes d = deflected_modes(w, DynamicsProperties{}, load, {}, 3);  // Newton from the rest shape
  EXPECT_LT((d.equilibrium.contact_B - sol.contact_point_W).norm(), 1e-12);
  EXPECT_LT((d.equilibrium.force_B - sol.force_W).norm() / sol.force_W.norm(), 0.05);
  const Modes rest = modes(w, DynamicsProperties{}, 3);
  EXPECT_GT(d.modes.frequency_hz(0), 1.5 * rest.frequency_hz(0));
  std::printf("peg at s = %.2f mm: reaction %.3g uN (quasi-static %.3g), f1 %.1f Hz (rest %.1f), asymmetry %.1e\n",
              sol.arc_length * 1e3, d.equilibrium.force_B.norm() * 1e6, sol.force_W.norm() * 1e6,
              d.modes.frequency_hz(0), rest.frequency_hz(0), d.asymmetry);
}

TEST(DynamicsDeflectedModes, RejectsAnArcLengthOffTheWhisker) {
  const Whisker w = curved(10);
  HeldLoad load;
  load.arc_length = 0.05;
  EXPECT_THROW(deflected_modes(w, DynamicsProperties{}, load), std::invalid_argument);
}

}  // namespace
}  // namespace vibrissa::dynamics
