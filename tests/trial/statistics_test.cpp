// Regression formulas against hand-computed values (Figs. 2e, 2f, 4b; §2.3 roll fit; §3.4 IQR rule).
#include <gtest/gtest.h>

#include "vibrissa/trial/roll_regression.hpp"
#include "vibrissa/trial/statistics.hpp"

using namespace vibrissa::trial;

TEST(Statistics, LineFitMatchesHandComputation) {
  // x = 0..3, y = 1, 3, 2, 5: mx = 1.5, my = 2.75, Sxx = 5, Sxy = 5.5, Syy = 8.75.
  // slope = 1.1, intercept = 1.1; SS_res = Syy - Sxy^2/Sxx = 2.7 -> r2 = 1 - 2.7/8.75.
  // Identity: residuals 1, 2, 0, 2 -> 9 -> r2_id = 1 - 9/8.75.
  const LineFit f = fit_line({0, 1, 2, 3}, {1, 3, 2, 5});
  EXPECT_NEAR(f.slope, 1.1, 1e-14);
  EXPECT_NEAR(f.intercept, 1.1, 1e-14);
  EXPECT_NEAR(f.r2, 1.0 - 2.7 / 8.75, 1e-14);
  EXPECT_NEAR(f.r2_identity, 1.0 - 9.0 / 8.75, 1e-14);
  EXPECT_EQ(f.count, 4u);
  EXPECT_THROW(fit_line({1, 1}, {0, 1}), std::invalid_argument);
}

TEST(Statistics, QuantilesMedianAndIqrOutliers) {
  const std::vector<double> v = {1, 2, 3, 4, 100};
  EXPECT_DOUBLE_EQ(median(v), 3.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.25), 2.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.75), 4.0);
  EXPECT_DOUBLE_EQ(median({4, 1, 2, 3}), 2.5);
  // Q1 = 2, Q3 = 4, IQR = 2: fences -1 and 7.
  const auto out = iqr_outliers(v);
  EXPECT_EQ(out, (std::vector<bool>{false, false, false, false, true}));
  EXPECT_DOUBLE_EQ(mean({1, 2, 3}), 2.0);
  EXPECT_DOUBLE_EQ(standard_deviation({1, 2, 3}), 1.0);
}

TEST(RollRegression, FitsNonContactFramesOnlyAndExtrapolatesContactFrames) {
  // Non-contact frames follow zeta = 0.25 theta - 0.1 exactly; contact frames carry distorted roll.
  const std::vector<double> theta = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5};
  const std::vector<double> zeta = {-0.1, -0.075, 9.0, 9.0, 0.0, 0.025};
  const std::vector<std::uint8_t> contact = {0, 0, 1, 1, 0, 0};
  const RollFit f = fit_roll(theta, zeta, contact, "t.csv");
  EXPECT_NEAR(f.slope, 0.25, 1e-14);
  EXPECT_NEAR(f.intercept, -0.1, 1e-14);
  EXPECT_NEAR(f.r2, 1.0, 1e-14);
  EXPECT_EQ(f.frames, 4u);
  const auto z = extrapolate_roll(f, theta, zeta, contact);
  EXPECT_NEAR(z[2], -0.05, 1e-14);
  EXPECT_NEAR(z[3], -0.025, 1e-14);
  EXPECT_DOUBLE_EQ(z[4], 0.0);
  try {
    fit_roll(theta, zeta, {1, 1, 1, 1, 1, 0}, "t.csv");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("t.csv: column 'zeta'"), std::string::npos) << e.what();
  }
}
