// Whisking kinematics (spec §2.2, data sheet §3) and head pose conventions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vibrissa/array/head.hpp"
#include "vibrissa/array/kinematics.hpp"

using namespace vibrissa::array;

namespace {
double rad(double d) { return d * std::numbers::pi / 180.0; }
}  // namespace

TEST(Kinematics, RowSlopesOfTheNamedSets) {
  EXPECT_DOUBLE_EQ(row_slopes(SlopeSet::knutsen2008, 1).k_phi, 0.12);
  EXPECT_DOUBLE_EQ(row_slopes(SlopeSet::knutsen2008, 1).k_zeta, -0.76);
  EXPECT_DOUBLE_EQ(row_slopes(SlopeSet::knutsen2008, 3).k_zeta, 0.22);
  EXPECT_DOUBLE_EQ(row_slopes(SlopeSet::knutsen2008, 5).k_phi, -0.02);
  EXPECT_DOUBLE_EQ(row_slopes(SlopeSet::knutsen2008_pitch_adjusted, 2).k_phi, 0.591);
  EXPECT_DOUBLE_EQ(row_slopes(SlopeSet::knutsen2008_pitch_adjusted, 4).k_zeta, 0.449);
  EXPECT_DOUBLE_EQ(row_slopes(SlopeSet::rigid, 4).k_zeta, 0.0);
  EXPECT_THROW(row_slopes(SlopeSet::knutsen2008, 6), std::invalid_argument);
  EXPECT_EQ(slope_set_from_string("knutsen2008_pitch_adjusted"), SlopeSet::knutsen2008_pitch_adjusted);
  try {
    slope_set_from_string("knutsen");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("whisking.slopes"), std::string::npos);
  }
}

TEST(Kinematics, ElevationAndRollAreLinearInProtractionWithRowSlopes) {
  WhiskingKinematics k;
  k.protraction.amplitude = rad(25);
  k.protraction.set_point = rad(5);
  k.protraction.frequency = 8;
  for (int row = 1; row <= 5; ++row) {
    WhiskerSpec s;
    s.name = std::string(1, "ABCDE"[row - 1]) + "1";
    s.row = row;
    s.theta_rest = rad(60);
    s.phi_rest = rad(10);
    s.zeta_rest = rad(-20);
    const RowSlopes slopes = row_slopes(SlopeSet::knutsen2008, row);
    for (double t : {0.0, 0.013, 0.04, 0.0625}) {
      const WhiskerAngles a = angles_at(s, k, t);
      const double dtheta = a.theta - s.theta_rest;
      EXPECT_NEAR(dtheta, rad(5) - rad(25) * std::cos(2 * std::numbers::pi * 8 * t), 1e-14);
      EXPECT_NEAR(a.phi - s.phi_rest, slopes.k_phi * dtheta, 1e-14);
      EXPECT_NEAR(a.zeta - s.zeta_rest, slopes.k_zeta * dtheta, 1e-14);
    }
  }
}

TEST(Kinematics, SinusoidProtractsFromRetractedToProtractedInHalfACycle) {
  Protraction p;
  p.amplitude = rad(30);
  p.set_point = rad(10);
  p.frequency = 8;
  EXPECT_NEAR(p(0.0), rad(-20), 1e-14);
  EXPECT_NEAR(p(1.0 / 16), rad(40), 1e-14);
  const double t = 0.021, h = 1e-7;
  EXPECT_NEAR(p.rate(t), (p(t + h) - p(t - h)) / (2 * h), 1e-6);
}

TEST(Kinematics, UserTimeSeriesAndOverrides) {
  Protraction p;
  p.series_time = {0.0, 0.1, 0.2};
  p.series_dtheta = {0.0, 0.5, 0.1};
  EXPECT_NEAR(p(0.05), 0.25, 1e-15);
  EXPECT_NEAR(p(0.15), 0.3, 1e-15);
  EXPECT_NEAR(p(-1.0), 0.0, 1e-15);
  EXPECT_NEAR(p(9.0), 0.1, 1e-15);
  EXPECT_NEAR(p.rate(0.05), 5.0, 1e-12);
  WhiskingKinematics k;
  k.per_whisker["C2"] = p;
  WhiskerSpec c2;
  c2.name = "C2";
  WhiskerSpec c3 = c2;
  c3.name = "C3";
  EXPECT_EQ(&k.protraction_of(c2), &k.per_whisker["C2"]);
  EXPECT_EQ(&k.protraction_of(c3), &k.protraction);
}

TEST(Kinematics, InvalidProtractionNamesTheField) {
  Protraction p;
  p.amplitude = std::nan("");
  try {
    validate(p, "whisking");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("whisking.amplitude_deg"), std::string::npos);
  }
  Protraction q;
  q.series_time = {0.0, 0.0};
  q.series_dtheta = {0.0, 1.0};
  EXPECT_THROW(validate(q), std::invalid_argument);
  // Finite but absurd values are refused naming the field (a whisking frequency of 1e308 Hz made the dynamics
  // take unbounded steps); the bounds themselves are accepted.
  const auto message = [](const Protraction& bad) {
    try {
      validate(bad, "whisking");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  Protraction f;
  f.frequency = 1e308;
  EXPECT_NE(message(f).find("whisking.frequency_Hz must lie in [0, 10000], got 1e+308"), std::string::npos) << message(f);
  f.frequency = 1e4;
  EXPECT_EQ(message(f), "accepted");
  Protraction a;
  a.amplitude = rad(180.5);
  EXPECT_NE(message(a).find("whisking.amplitude_deg must lie in [-180, 180]"), std::string::npos) << message(a);
  a.amplitude = -rad(180);
  EXPECT_EQ(message(a), "accepted");
  Protraction sp;
  sp.set_point = rad(1e30);
  EXPECT_NE(message(sp).find("whisking.set_point_deg"), std::string::npos) << message(sp);
  Protraction sd;
  sd.series_time = {0.0, 1.0};
  sd.series_dtheta = {0.0, rad(400)};
  EXPECT_NE(message(sd).find("whisking.series.dtheta_deg[1] must lie in [-360, 360]"), std::string::npos) << message(sd);
}

TEST(Head, PitchRaisesTheNoseYawTurnsItLeftRollLowersTheRightSide) {
  const HeadMotion none;
  HeadMotion h;
  h.pitch = rad(20);
  const Eigen::Vector3d nose = h.at(0.0).R_WH * Eigen::Vector3d::UnitY();
  EXPECT_NEAR(nose.z(), std::sin(rad(20)), 1e-15);
  EXPECT_NEAR(nose.y(), std::cos(rad(20)), 1e-15);
  const Eigen::Vector3d nose_swept = none.at(0.0, rad(20)).R_WH * Eigen::Vector3d::UnitY();
  EXPECT_NEAR((nose_swept - nose).norm(), 0.0, 1e-15);
  HeadMotion y;
  y.yaw = rad(10);
  EXPECT_LT((y.at(0.0).R_WH * Eigen::Vector3d::UnitY()).x(), 0.0);
  HeadMotion r;
  r.roll = rad(10);
  EXPECT_LT((r.at(0.0).R_WH * Eigen::Vector3d::UnitX()).z(), 0.0);
}

TEST(Head, MotionOverTime) {
  HeadMotion h;
  h.p_W_head = {0.001, 0.0, 0.0};
  h.v_W_head = {0.0, 0.02, 0.0};
  h.pitch_rate = rad(100);
  const HeadPose p = h.at(0.1);
  EXPECT_NEAR((p.p_W_head - Eigen::Vector3d(0.001, 0.002, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((p.R_WH * Eigen::Vector3d::UnitY()).z(), std::sin(rad(10)), 1e-14);
  HeadMotion s;
  s.series = {HeadSample{0.0, Eigen::Vector3d::Zero(), 0.0, 0.0, 0.0},
              HeadSample{1.0, Eigen::Vector3d(0.01, 0.0, 0.0), 0.0, rad(30), 0.0}};
  const HeadPose q = s.at(0.5);
  EXPECT_NEAR(q.p_W_head.x(), 0.005, 1e-15);
  EXPECT_NEAR((q.R_WH * Eigen::Vector3d::UnitY()).z(), std::sin(rad(15)), 1e-14);
  s.series[1].time = 0.0;
  EXPECT_THROW(validate(s), std::invalid_argument);
}
