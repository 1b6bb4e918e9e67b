// Air drag (dynamics/air_drag.hpp): the cylinder correlation, and a whisker turning steadily in air carries the
// closed-form drag force and moment at its base.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "vibrissa/core/whisker.hpp"
#include "vibrissa/dynamics/air_drag.hpp"

namespace vibrissa::dynamics {
namespace {

TEST(DynamicsAirDrag, CylinderDragCoefficientIsWhitesCorrelation) {
  EXPECT_DOUBLE_EQ(cylinder_drag_coefficient(1.0), 11.0);
  EXPECT_NEAR(cylinder_drag_coefficient(1000.0), 1.1, 1e-12);
  EXPECT_THROW(cylinder_drag_coefficient(0.0), std::invalid_argument);
}

TEST(DynamicsAirDrag, SteadyRotationCarriesTheClosedFormDrag) {
  // A straight uniform whisker (diameter d, length L) turning at constant Omega about B's z axis through its base:
  // the air meets it at v = Omega x, so per length f = rho C_d(Omega x d / nu) d (Omega x)^2 / 2 against +y. Once
  // the start-up transient has died out (damped joints), the follicle carries the whole drag:
  //   F_y = -rho d Omega^2 / 2 [L^3 / 3 + 10 (nu / (Omega d))^(2/3) (3/7) L^(7/3)],
  //   M_z = -rho d Omega^2 / 2 [L^4 / 4 + 10 (nu / (Omega d))^(2/3) (3/10) L^(10/3)]
  // (the centrifugal load of a straight whisker is axial and has no moment).
  WhiskerProperties p;
  p.links = 40;
  p.taper_ratio = 1.0;
  const double L = 0.03, d = 2.0 * p.base_radius, Omega = 20.0;
  const Whisker w = Whisker::from_parabola(L, 0.0, p);
  DynamicsProperties props;
  props.air_drag = true;
  const BaseTrajectory base = trajectory_from_placements(
      [&](double t) { return Placement(Eigen::AngleAxisd(Omega * t, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                                       Eigen::Vector3d::Zero()); });
  SimulationOptions o;
  o.duration = 0.15;
  o.output_rate = 200.0;
  o.record_nodes = false;
  o.relative_tolerance = 1e-8;
  const TimeSeries ts = simulate(w, props, base, o);
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  const double rho = props.air.density, nu = props.air.kinematic_viscosity;
  const double c = 10.0 * std::cbrt(std::pow(nu / (Omega * d), 2));
  const double Fy = -0.5 * rho * d * Omega * Omega * (L * L * L / 3.0 + c * (3.0 / 7.0) * std::pow(L, 7.0 / 3.0));
  const double Mz = -0.5 * rho * d * Omega * Omega * (std::pow(L, 4) / 4.0 + c * 0.3 * std::pow(L, 10.0 / 3.0));
  const Eigen::Vector3d F = ts.force_B.back(), M = ts.moment_B.back();
  std::printf("steady rotation: F_y %.6e N (%.1e off), M_z %.6e N m (%.1e off)\n", F.y(), F.y() / Fy - 1.0, M.z(),
              M.z() / Mz - 1.0);
  EXPECT_NEAR(F.y() / Fy, 1.0, 1e-5);
  EXPECT_NEAR(M.z() / Mz, 1.0, 1e-5);
  EXPECT_NEAR(M.y(), 0.0, 1e-9 * std::abs(Mz));
  // Without drag the same motion loads the follicle only axially (centripetal).
  props.air_drag = false;
  const TimeSeries dry = simulate(w, props, base, o);
  EXPECT_NEAR(dry.moment_B.back().z(), 0.0, 1e-6 * std::abs(Mz));
}

TEST(DynamicsAirDrag, RejectsNonPositiveAir) {
  DynamicsProperties props;
  props.air.kinematic_viscosity = 0.0;
  EXPECT_THROW(validate(props), std::invalid_argument);
}

}  // namespace
}  // namespace vibrissa::dynamics
