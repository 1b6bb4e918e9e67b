#pragma once
// One analysis run of a tracked trial, as `vibrissa trial` and `vibrissa.analyze_trial` perform it: the
// frame-by-frame pipeline (spec §2.3-§3.3) followed by every analysis of the paper (spec §3.3-§3.4). Both
// front ends call this, so the same trial and options give bit-identical numbers from either.
#include <cstddef>
#include <optional>

#include "vibrissa/core/run_control.hpp"
#include "vibrissa/trial/outliers.hpp"
#include "vibrissa/trial/analysis.hpp"
#include "vibrissa/trial/pipeline.hpp"

namespace vibrissa::trial {

struct TrialRunOptions {
  PipelineOptions pipeline;
  AnalysisOptions analysis;
};

/// The options of `vibrissa trial` (flags) and `vibrissa.analyze_trial` (keywords), named as there.
struct TrialFlags {
  std::optional<double> mu;      ///< --mu: also run frictional edge mode with this coefficient
  std::optional<double> mu_eq7;  ///< --mu-eq7: mu of eq. (7) (default: median mu of contact-point mode)
  double cutoff = 85.0;          ///< --cutoff: low-pass cutoff [Hz] (spec §2.3)
  int filter_order = 2;          ///< --filter-order: Butterworth order per pass (2 or 4)
  bool no_filter = false;        ///< --no-filter
  bool no_roll_fit = false;      ///< --no-roll-fit: keep the tracked zeta in contact frames
  bool rest_shape_per_contact = false;  ///< --rest-shape-per-contact (spec §2.3)
};
/// Throws std::invalid_argument naming the option (mu, mu_eq7, cutoff, filter_order) and its value.
TrialRunOptions run_options(const TrialFlags& flags);

struct TrialRun {
  PipelineResult result;
  TrialAnalysis analysis;
  /// Frames dropped before filtering as impossible (trial/outliers.hpp): not solved, not in the results.
  std::vector<DroppedFrame> dropped_frames;
  double pipeline_seconds = 0.0;  ///< wall-clock time of pipeline + analyses [s] (not reproducible)
};

/// Contact frames of a trial: the progress total of run_trial.
std::size_t contact_frame_count(const Trial& trial);

/// Runs the pipeline and the analyses. Progress counts contact frames solved; cancel is polled per frame
/// (throws Cancelled). Throws std::invalid_argument for invalid options, naming the option.
TrialRun run_trial(const Trial& trial, const TrialRunOptions& options = {}, const RunControl& control = {});

}  // namespace vibrissa::trial
