// End-to-end: synthetic trials simulated with the frictional edge mode, analysed by the pipeline.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "vibrissa/io/trial_io.hpp"
#include "vibrissa/trial/analysis.hpp"
#include "vibrissa/trial/synth.hpp"

using namespace vibrissa::trial;

namespace {
SynthOptions short_trial(double mu) {
  SynthOptions o;
  o.duration = 1.0;  // 8 whisks at 1 kHz
  o.mu = mu;
  return o;
}
}  // namespace

TEST(TrialPipeline, RecoversMuFromANoiseFreeSyntheticTrial) {
  SynthStats st;
  const Trial t = synthesize_trial(short_trial(0.48), &st);
  ASSERT_GE(st.periods, 7u);
  ASSERT_EQ(st.failures, 0u);
  ASSERT_GT(st.slip_frames, st.contact_frames / 2) << "the test needs mostly slipping contact";
  PipelineOptions po;
  po.mu = 0.48;
  const PipelineResult r = run_pipeline(t, po);
  const TrialAnalysis a = analyse_trial(r);
  ASSERT_TRUE(a.friction);
  EXPECT_GT(a.friction->frames_used, 150u);
  EXPECT_NEAR(a.friction->median, 0.48, 0.02);
  // Eq. (6) (linear tapered beam) predicts the measured z_error with a slope near 1.
  ASSERT_TRUE(a.z_error && a.z_error->fit_eq6.all);
  EXPECT_NEAR(a.z_error->fit_eq6.all->slope, 1.0, 0.2);
  EXPECT_GT(a.z_error->fit_eq6.all->r2, 0.95);
  // Friction makes the edge-mode (frictionless) contact slip further up the peg than the tracked one.
  EXPECT_GT(a.z_error->measured_max, 1e-3);
}

TEST(TrialPipeline, MuIsALowerBoundWhenTheContactSticks) {
  // mu = 0.48: the contact slides up the peg in most used frames, so the median estimates mu; mu = 1.0: it
  // sticks, |F_edge| / F_N stays below mu, and the analysis says the median is only a lower bound.
  const TrialAnalysis slides = analyse_trial(run_pipeline(synthesize_trial(short_trial(0.48))));
  ASSERT_TRUE(slides.friction);
  EXPECT_EQ(slides.friction->kind, "estimate");
  EXPECT_GT(slides.friction->slip_fraction, 0.75);
  EXPECT_NEAR(slides.friction->median_slipping, 0.48, 0.02);
  const TrialAnalysis sticks = analyse_trial(run_pipeline(synthesize_trial(short_trial(1.0))));
  ASSERT_TRUE(sticks.friction);
  EXPECT_EQ(sticks.friction->kind, "lower_bound");
  EXPECT_LT(sticks.friction->slip_fraction, 0.5);
  EXPECT_LT(sticks.friction->median, 1.0);
  ASSERT_FALSE(sticks.friction->warnings.empty());
  EXPECT_NE(sticks.friction->warnings.back().find("lower bound"), std::string::npos);
}

TEST(TrialPipeline, FrictionConeHoldsInEveryFrame) {
  const Trial t = synthesize_trial(short_trial(0.3));
  PipelineOptions po;
  po.mu = 0.3;
  const PipelineResult r = run_pipeline(t, po);
  std::size_t checked = 0, on_cone = 0;
  for (const FrameResult& f : r.frames) {
    if (!f.frictional.ok()) continue;
    ++checked;
    const double ratio = std::abs(f.frictional.friction_force) / f.frictional.normal_force;
    EXPECT_LE(ratio, 0.3 * (1.0 + 1e-6)) << "t = " << f.time;
    on_cone += ratio > 0.3 * (1.0 - 1e-6);
    // Edge mode is frictionless: no force along the peg.
    ASSERT_TRUE(f.edge.ok());
    EXPECT_NEAR(f.edge.friction_force, 0.0, 1e-9 * f.edge.normal_force + 1e-15);
  }
  EXPECT_GT(checked, 300u);
  EXPECT_GT(on_cone, checked / 3) << "slipping frames must sit on the cone";
}

TEST(TrialPipeline, FrictionalLimitsReproduceEdgeAndContactPointModes) {
  // mu = 0: the frictional mode is the edge mode, frame by frame.
  const Trial t = synthesize_trial(short_trial(0.48));
  PipelineOptions zero;
  zero.mu = 0.0;
  const PipelineResult r0 = run_pipeline(t, zero);
  std::size_t n0 = 0;
  for (const FrameResult& f : r0.frames)
    if (f.frictional.ok() && f.edge.ok()) {
      ++n0;
      EXPECT_LT((f.frictional.contact_W - f.edge.contact_W).norm(), 1e-9) << f.time;
    }
  EXPECT_GT(n0, 300u);
  // mu -> infinity: the contact never leaves its onset point; the height stays at the touch height.
  PipelineOptions big;
  big.mu = 1e6;
  const PipelineResult rb = run_pipeline(t, big);
  for (std::size_t p = 0; p < rb.pre.periods.size(); ++p) {
    const auto& per = rb.pre.periods[p];
    const double z0 = rb.frames[per.first].frictional.height;
    for (std::size_t i = per.first; i <= per.last; ++i)
      if (rb.frames[i].frictional.ok()) {
        EXPECT_NEAR(rb.frames[i].frictional.height, z0, 1e-9) << i;
      }
  }
}

TEST(TrialPipeline, NoisyTrialStillGivesMuNearTheTruth) {
  SynthOptions o = short_trial(0.48);
  o.noise_position = 5e-6;                // 5 um
  o.noise_angle = 0.05 * 3.14159265 / 180;  // 0.05 deg
  const Trial t = synthesize_trial(o);
  const TrialAnalysis a = analyse_trial(run_pipeline(t));
  ASSERT_TRUE(a.friction);
  EXPECT_NEAR(a.friction->median, 0.48, 0.1);
}

TEST(TrialPipeline, SyntheticTrialSurvivesTheFileRoundTrip) {
  const Trial t = synthesize_trial(short_trial(0.48));
  const auto path = (std::filesystem::temp_directory_path() / "vibrissa_synth_roundtrip.h5").string();
  vibrissa::io::write_trial(t, path);
  const Trial back = vibrissa::io::read_trial(path);
  ASSERT_EQ(back.frames(), t.frames());
  const TrialAnalysis a = analyse_trial(run_pipeline(back));
  EXPECT_NEAR(a.friction->median, 0.48, 0.02);
}

TEST(SyntheticTrial, WhisksVaryFromWhiskToWhiskAndThetaStaysContinuous) {
  SynthOptions o = short_trial(0.48);
  o.duration = 2.0;
  const Trial varied = synthesize_trial(o);
  // Peaks of theta per whisk (local maxima): different from whisk to whisk, by about the set-point and
  // amplitude jitter (2 deg, 10 % of 30 deg).
  std::vector<double> peaks;
  for (std::size_t i = 1; i + 1 < varied.frames(); ++i)
    if (varied.theta[i] > varied.theta[i - 1] && varied.theta[i] >= varied.theta[i + 1]) peaks.push_back(varied.theta[i]);
  ASSERT_GE(peaks.size(), 15u);
  double spread = 0.0, step_at_joins = 0.0;
  for (double p : peaks) spread = std::max(spread, std::abs(p - peaks.front()));
  // Where one whisk ends and the next begins theta sits at a trough (zero slope): a join without a jump moves
  // it by second-order amounts only, while a jump would be of the order of the jitter (~0.05 rad).
  for (std::size_t i = 1; i < varied.frames(); ++i)
    if (std::floor(o.whisk_frequency * varied.time[i]) != std::floor(o.whisk_frequency * varied.time[i - 1]))
      step_at_joins = std::max(step_at_joins, std::abs(varied.theta[i] - varied.theta[i - 1]));
  EXPECT_GT(spread, 0.02);          // rad: the whisks are not copies of one whisk
  EXPECT_LT(step_at_joins, 2e-3);   // rad: no jump where whisks join
  // 1000 Hz / 8.3 Hz is not a whole number of frames: successive whisk onsets fall on different phases.
  EXPECT_NE(std::fmod(o.frame_rate / o.whisk_frequency, 1.0), 0.0);
  // Without jitter at 8 Hz every whisk is the same 125 frames.
  o.theta_center_jitter = 0.0;
  o.theta_amplitude_jitter = 0.0;
  o.whisk_frequency = 8.0;
  const Trial same = synthesize_trial(o);
  for (std::size_t i = 125; i < same.frames(); ++i) ASSERT_NEAR(same.theta[i], same.theta[i - 125], 1e-12) << i;
}
