// Butterworth zero-phase filter (spec §2.3, 85 Hz): gain exactly 1/2 at the cutoff for filtfilt, zero phase.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vibrissa/trial/filter.hpp"

using namespace vibrissa::trial;

namespace {
std::vector<double> sine(double f, double fs, std::size_t n, double phase = 0.0) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = std::sin(2.0 * std::numbers::pi * f * static_cast<double>(i) / fs + phase);
  return x;
}
/// Amplitude and phase of the component at f (least squares on the middle half, away from the edges).
std::pair<double, double> tone(const std::vector<double>& x, double f, double fs) {
  double c = 0.0, s = 0.0;
  const std::size_t a = x.size() / 4, b = 3 * x.size() / 4;
  for (std::size_t i = a; i < b; ++i) {
    const double w = 2.0 * std::numbers::pi * f * static_cast<double>(i) / fs;
    c += x[i] * std::cos(w);
    s += x[i] * std::sin(w);
  }
  const double n = static_cast<double>(b - a);
  return {2.0 * std::hypot(c, s) / n, std::atan2(c, s)};
}
}  // namespace

TEST(Butterworth, SecondOrderCoefficientsMatchHandComputedBilinearDesign) {
  // fc = fs/4: K = tan(pi/4) = 1, norm = 2 + sqrt(2); b0 = 1 / (2 + sqrt 2), a1 = 0, a2 = (2 - sqrt 2)/(2 + sqrt 2).
  const Butterworth f = design_butterworth_lowpass(250.0, 1000.0, 2);
  ASSERT_EQ(f.sections.size(), 1u);
  const double r2 = std::sqrt(2.0);
  EXPECT_NEAR(f.sections[0].b0, 1.0 / (2.0 + r2), 1e-15);
  EXPECT_NEAR(f.sections[0].b1, 2.0 / (2.0 + r2), 1e-15);
  EXPECT_NEAR(f.sections[0].a1, 0.0, 1e-15);
  EXPECT_NEAR(f.sections[0].a2, (2.0 - r2) / (2.0 + r2), 1e-15);
}

TEST(Butterworth, SinglePassGainAtCutoffIsOneOverRootTwoAndDcIsOne) {
  for (int order : {2, 4}) {
    const Butterworth f = design_butterworth_lowpass(85.0, 1000.0, order);
    EXPECT_NEAR(magnitude(f, 85.0), 1.0 / std::sqrt(2.0), 1e-12) << order;
    EXPECT_NEAR(magnitude(f, 0.0), 1.0, 1e-12) << order;
    // Maximally flat: order n falls as (fc/f)^n well above the cutoff (bilinear: faster near Nyquist).
    EXPECT_LT(magnitude(f, 300.0), std::pow(85.0 / 300.0, order)) << order;
  }
}

TEST(Butterworth, FiltfiltHasGainOneHalfAtCutoffAndZeroPhase) {
  const double fs = 1000.0;
  const Butterworth f = design_butterworth_lowpass(85.0, fs, 2);
  const auto x = sine(85.0, fs, 4000, 0.3);
  const auto y = filtfilt(f, x);
  const auto [ax, px] = tone(x, 85.0, fs);
  const auto [ay, py] = tone(y, 85.0, fs);
  EXPECT_NEAR(ay / ax, 0.5, 2e-3);  // |H|^2 at fc: -6.02 dB
  EXPECT_NEAR(py - px, 0.0, 1e-3);  // zero phase
  // A slow whisking signal (8 Hz) passes unchanged and unshifted.
  const auto w = sine(8.0, fs, 4000, 1.0);
  const auto v = filtfilt(f, w);
  for (std::size_t i = 0; i < w.size(); ++i) EXPECT_NEAR(v[i], w[i], 3e-3) << i;
}

TEST(Butterworth, FiltfiltPreservesLinesAtTheEdges) {
  // Odd reflection + steady-state start: a ramp is reproduced exactly, including the first and last samples.
  const Butterworth f = design_butterworth_lowpass(85.0, 1000.0, 4);
  std::vector<double> x(50);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 2.0 + 0.1 * static_cast<double>(i);
  const auto y = filtfilt(f, x);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(y[i], x[i], 1e-5) << i;  // 1e-4 of one step
}

TEST(Butterworth, RejectsBadDesigns) {
  EXPECT_THROW(design_butterworth_lowpass(85.0, 1000.0, 3), std::invalid_argument);
  EXPECT_THROW(design_butterworth_lowpass(600.0, 1000.0, 2), std::invalid_argument);
  EXPECT_THROW(design_butterworth_lowpass(0.0, 1000.0, 2), std::invalid_argument);
}
