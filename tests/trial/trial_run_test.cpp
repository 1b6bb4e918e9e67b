// The shared front-end layer of `vibrissa synth` / `vibrissa trial` and their Python twins: the synth option
// table (units in the names) and the trial-run options.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "vibrissa/trial/synth_parameters.hpp"
#include "vibrissa/trial/trial_run.hpp"

using namespace vibrissa::trial;

TEST(SynthParameters, DefaultsAreSynthOptionsInTheNamedUnits) {
  const auto d = synth_parameter_defaults();
  EXPECT_EQ(d.size(), synth_parameters().size());
  EXPECT_EQ(d.at("duration"), SynthOptions{}.duration);
  EXPECT_EQ(d.at("whisk_hz"), 8.3);
  EXPECT_NEAR(d.at("theta_center_jitter_deg"), 2.0, 1e-12);
  EXPECT_EQ(d.at("theta_amplitude_jitter"), 0.1);
  EXPECT_NEAR(d.at("theta_center_deg"), 10.0, 1e-12);
  EXPECT_NEAR(d.at("peg_azimuth_deg"), 34.0, 1e-12);
  EXPECT_EQ(d.at("whisker_length_mm"), 35.0);
  EXPECT_EQ(d.at("peg_distance_mm"), 20.0);
  EXPECT_EQ(d.at("noise_position_um"), 0.0);
}

TEST(SynthParameters, ConvertsEachValueToSi) {
  const SynthOptions o = synth_options_from_parameters(
      {{"theta_amplitude_deg", 20.0}, {"whisker_length_mm", 30.0}, {"noise_position_um", 5.0}, {"mu", 0.3}});
  EXPECT_EQ(o.theta_amplitude, 20.0 * (std::numbers::pi / 180.0));
  EXPECT_EQ(o.whisker_length, 30.0 * 1e-3);
  EXPECT_EQ(o.noise_position, 5.0 * 1e-6);
  EXPECT_EQ(o.mu, 0.3);
  // Values not given keep their defaults (through the unit and back, as the CLI always did).
  EXPECT_NEAR(o.theta_center, SynthOptions{}.theta_center, 1e-15);
  EXPECT_EQ(o.duration, SynthOptions{}.duration);
}

TEST(SynthParameters, UnknownNameThrowsNamingIt) {
  try {
    (void)synth_options_from_parameters({{"peg_distance", 20.0}});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'peg_distance'"), std::string::npos) << e.what();
  }
}

TEST(TrialRunOptions, FlagsMapOntoPipelineAndAnalysisOptions) {
  TrialFlags f;
  f.mu = 0.4;
  f.mu_eq7 = 0.5;
  f.cutoff = 60.0;
  f.filter_order = 4;
  f.no_filter = true;
  f.no_roll_fit = true;
  f.rest_shape_per_contact = true;
  const TrialRunOptions o = run_options(f);
  EXPECT_EQ(o.pipeline.mu, 0.4);
  EXPECT_EQ(o.analysis.mu_eq7, 0.5);
  EXPECT_EQ(o.pipeline.preprocess.cutoff_hz, 60.0);
  EXPECT_EQ(o.pipeline.preprocess.filter_order, 4);
  EXPECT_FALSE(o.pipeline.preprocess.filter);
  EXPECT_FALSE(o.pipeline.preprocess.roll_from_theta);
  EXPECT_TRUE(o.pipeline.preprocess.rest_shape_per_contact);
  const TrialRunOptions d = run_options(TrialFlags{});
  EXPECT_FALSE(d.pipeline.mu.has_value());
  EXPECT_TRUE(d.pipeline.preprocess.filter);
  EXPECT_EQ(d.pipeline.preprocess.cutoff_hz, 85.0);
}

TEST(TrialRunOptions, InvalidFlagsNameTheFlagAndValue) {
  auto message = [](TrialFlags f) {
    try {
      (void)run_options(f);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  TrialFlags f;
  f.filter_order = 3;
  EXPECT_EQ(message(f), "filter_order must be 2 or 4, got 3");
  f = {};
  f.cutoff = 0.0;
  EXPECT_EQ(message(f), "cutoff must be finite and > 0 [Hz], got 0");
  f = {};
  f.mu = -0.5;
  EXPECT_EQ(message(f), "mu must be finite and >= 0, got -0.5");
  f = {};
  f.mu_eq7 = std::nan("");
  EXPECT_EQ(message(f), "mu_eq7 must be finite and >= 0, got nan");
}

TEST(TrialRun, CountsContactFramesAndMatchesThePipelineBitForBit) {
  SynthOptions so;
  so.duration = 0.3;
  const Trial t = synthesize_trial(so);
  EXPECT_EQ(contact_frame_count(t), static_cast<std::size_t>(std::count(t.contact.begin(), t.contact.end(), 1)));
  const TrialRun run = run_trial(t, run_options(TrialFlags{}));
  const PipelineResult direct = run_pipeline(t, run_options(TrialFlags{}).pipeline);
  ASSERT_EQ(run.result.frames.size(), direct.frames.size());
  for (std::size_t i = 0; i < direct.frames.size(); ++i) {
    const auto& a = run.result.frames[i].contact_point;
    const auto& b = direct.frames[i].contact_point;
    ASSERT_EQ(a.solved, b.solved);
    if (a.ok()) {
      EXPECT_EQ(a.force_W, b.force_W) << "frame " << i;
    }
  }
  EXPECT_GT(run.pipeline_seconds, 0.0);
}

TEST(TrialRun, UntaperedWhiskerHasNoZErrorFitsRatherThanNaN) {
  // Once: taper_ratio 1 (no cone for eq. 5) printed "slope -nan" and wrote null fits.
  SynthOptions so;
  so.duration = 0.3;
  Trial t = synthesize_trial(so);
  t.meta.material.taper_ratio = 1.0;
  const TrialRun run = run_trial(t, run_options(TrialFlags{}));
  ASSERT_TRUE(run.analysis.z_error.has_value());
  const ZErrorAnalysis& z = *run.analysis.z_error;
  EXPECT_FALSE(z.fit_eq6.all.has_value());
  EXPECT_FALSE(z.fit_eq7.all.has_value());
  EXPECT_TRUE(std::none_of(z.used.begin(), z.used.end(), [](bool u) { return u; }));
}

// Issue 23: one finite outlier (base_y = 1e308 in one frame) was spread by the low-pass filter and turned every
// contact frame into no_contact. Now it is dropped before filtering, and named with its reason.
TEST(TrialRun, ImpossibleSampleIsDroppedBeforeFilteringNotSpread) {
  SynthOptions so;
  so.duration = 0.3;
  const Trial clean = synthesize_trial(so);
  const auto first_contact = static_cast<std::size_t>(std::find(clean.contact.begin(), clean.contact.end(), 1) -
                                                      clean.contact.begin());
  ASSERT_LT(first_contact + 5, clean.frames());
  const std::size_t bad = first_contact + 5;
  auto ok_frames = [](const TrialRun& r) {
    return std::count_if(r.result.frames.begin(), r.result.frames.end(),
                         [](const auto& f) { return f.contact_point.ok(); });
  };
  const TrialRun reference = run_trial(clean, run_options(TrialFlags{}));
  EXPECT_TRUE(reference.dropped_frames.empty());
  for (int kind = 0; kind < 3; ++kind) {
    Trial t = clean;
    if (kind == 0) t.base_W[bad].y() = 1e308;
    if (kind == 1) t.theta[bad] = -1e300;
    if (kind == 2) t.contact_W[bad].x() = 50.0;
    const TrialRun run = run_trial(t, run_options(TrialFlags{}));
    ASSERT_EQ(run.dropped_frames.size(), 1u) << kind;
    EXPECT_EQ(run.dropped_frames[0].frame, bad);
    EXPECT_EQ(run.dropped_frames[0].time, clean.time[bad]);
    const char* column[] = {"base = ", "theta = -1e+300 rad", "contact point = "};
    EXPECT_EQ(run.dropped_frames[0].reason.rfind(column[kind], 0), 0u) << run.dropped_frames[0].reason;
    EXPECT_EQ(run.result.frames.size(), reference.result.frames.size() - 1);
    EXPECT_GE(ok_frames(run), ok_frames(reference) - 3) << kind;  // one frame fewer, the rest as before
  }
}
