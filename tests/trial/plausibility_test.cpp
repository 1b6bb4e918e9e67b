// Unit guardrails of a trial (trial/plausibility.hpp): a trial read in the wrong units is flagged, naming
// the quantity, the value and the likely mistake; a plausible trial is not.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "vibrissa/trial/plausibility.hpp"

namespace vibrissa::trial {
namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// A 30 mm whisker y = 10 x^2 whisking theta = 0.2..1.0 rad for 50 frames, its base moving 2 mm along x, a
/// vertical peg 20 mm out; SI units, as a reader leaves them when the declared units are right.
Trial plausible_trial() {
  Trial t;
  t.source = "test";
  for (int i = 0; i <= 30; ++i) {
    const double x = 0.029 * i / 30.0;
    t.meta.rest_shape.emplace_back(x, 10.0 * x * x, 0.0);
  }
  for (int i = 0; i < 50; ++i) {
    t.time.push_back(i * 1e-3);
    t.base_W.emplace_back(0.002 * i / 49.0, 0.0, 0.0);
    t.theta.push_back(0.2 + 0.8 * std::sin(i * 0.1) * std::sin(i * 0.1));
    t.phi.push_back(0.1);
    t.contact.push_back(0);
  }
  t.meta.edges.push_back({Eigen::Vector3d(0.02, 0.01, 0.0), Eigen::Vector3d::UnitZ()});
  return t;
}

TEST(TrialPlausibility, APlausibleTrialHasNoWarning) { EXPECT_TRUE(trial_warnings(plausible_trial()).empty()); }

TEST(TrialPlausibility, MetresDeclaredMillimetresIsA30MicrometreWhisker) {
  Trial t = plausible_trial();
  for (auto& p : t.meta.rest_shape) p *= 1e-3;  // every length read 1000 times too small
  for (auto& p : t.base_W) p *= 1e-3;
  for (auto& e : t.meta.edges) e.point *= 1e-3;
  t.meta.declared_units.length = "mm";
  const auto w = trial_warnings(t);
  ASSERT_EQ(w.size(), 1U);
  EXPECT_TRUE(has(w[0], "um) lies outside the plausible 1-200 mm of a rodent whisker: did you mean 30")) << w[0];
  EXPECT_TRUE(has(w[0], "(metres given or declared as mm)?")) << w[0];
}

TEST(TrialPlausibility, RadiansDeclaredDegreesAndDegreesDeclaredRadians) {
  Trial t = plausible_trial();
  t.meta.declared_units.angle = "deg";
  for (double& v : t.theta) v *= std::numbers::pi / 180.0;  // radians read as degrees
  for (double& v : t.phi) v *= std::numbers::pi / 180.0;
  auto w = trial_warnings(t);
  ASSERT_EQ(w.size(), 2U);
  EXPECT_TRUE(has(w[0], "theta stays within +-")) << w[0];
  EXPECT_TRUE(has(w[1], "phi stays within +-0.1 deg although the file declares angle=deg")) << w[1];
  t = plausible_trial();
  for (double& v : t.theta) v *= 180.0 / std::numbers::pi;  // degrees declared as radians
  w = trial_warnings(t);
  ASSERT_EQ(w.size(), 1U);
  EXPECT_TRUE(has(w[0], "theta reaches 57.")) << w[0];
  EXPECT_TRUE(has(w[0], "deg), beyond a full turn: degrees declared as radians (angle=rad)?")) << w[0];
}

TEST(TrialPlausibility, APegOutOfReachInEveryFrameNamesTheNearestFrame) {
  Trial t = plausible_trial();
  t.meta.edges.push_back({Eigen::Vector3d(16.6, 11.2, 0.0), Eigen::Vector3d::UnitZ()});  // mm given as metres
  t.meta.edges.push_back({Eigen::Vector3d(0.047, 0.0, 0.0), Eigen::Vector3d::UnitZ()});  // in reach late only
  const auto w = trial_warnings(t);
  ASSERT_EQ(w.size(), 1U);
  EXPECT_TRUE(has(w[0], "edge 2 (peg) passes 20.02 m from the whisker base")) << w[0];
  EXPECT_TRUE(has(w[0], "positions in mm given as metres? (at its nearest over all frames)")) << w[0];
}

}  // namespace
}  // namespace vibrissa::trial
