#include "vibrissa/trial/trial_run.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::trial {

std::size_t contact_frame_count(const Trial& trial) {
  std::size_t contact = 0;
  for (auto c : trial.contact) contact += c;
  return contact;
}

namespace {
void require(bool ok, const char* name, double value, const char* expected) {
  if (ok) return;
  throw std::invalid_argument(std::string(name) + " must be " + expected + ", got " + format_value(value));
}
}  // namespace

TrialRunOptions run_options(const TrialFlags& flags) {
  if (flags.mu) require(std::isfinite(*flags.mu) && *flags.mu >= 0.0, "mu", *flags.mu, "finite and >= 0");
  if (flags.mu_eq7)
    require(std::isfinite(*flags.mu_eq7) && *flags.mu_eq7 >= 0.0, "mu_eq7", *flags.mu_eq7, "finite and >= 0");
  require(std::isfinite(flags.cutoff) && flags.cutoff > 0.0, "cutoff", flags.cutoff, "finite and > 0 [Hz]");
  require(flags.filter_order == 2 || flags.filter_order == 4, "filter_order", flags.filter_order, "2 or 4");
  TrialRunOptions o;
  o.pipeline.preprocess.filter = !flags.no_filter;
  o.pipeline.preprocess.cutoff_hz = flags.cutoff;
  o.pipeline.preprocess.filter_order = flags.filter_order;
  o.pipeline.preprocess.roll_from_theta = !flags.no_roll_fit;
  o.pipeline.preprocess.rest_shape_per_contact = flags.rest_shape_per_contact;
  o.pipeline.mu = flags.mu;
  o.analysis.mu_eq7 = flags.mu_eq7;
  return o;
}

TrialRun run_trial(const Trial& trial, const TrialRunOptions& options, const RunControl& control) {
  const auto t0 = std::chrono::steady_clock::now();
  TrialRun run;
  // Frames that could not be reconstructed (docs/reconstruction.md) are skipped, never filled in.
  // Impossible samples are dropped before the filter could spread them (docs/trials.md, "Impossible samples").
  run.dropped_frames = impossible_frames(trial);
  run.result = run_pipeline(reconstructed_frames_only(without_frames(trial, run.dropped_frames)), options.pipeline,
                            control);
  run.analysis = analyse_trial(run.result, options.analysis);
  run.pipeline_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

}  // namespace vibrissa::trial
