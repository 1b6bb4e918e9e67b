#pragma once
// The files of one trial analysis (docs/trials.md, "Outputs"): frames.csv, frames.h5 and summary.json, as
// `vibrissa trial` and `vibrissa.TrialResult.write` write them. Built once from a TrialRun, so the per-frame
// table and the summary a Python caller sees are exactly what the files hold.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "vibrissa/io/trial_results.hpp"
#include "vibrissa/trial/trial_run.hpp"

namespace vibrissa::io {

struct TrialOutputs {
  ResultTable table;     ///< the columns of frames.csv / frames.h5
  nlohmann::json summary;  ///< summary.json, including the wall-clock "pipeline_seconds"
};

TrialOutputs trial_outputs(const trial::TrialRun& run);

/// Creates `dir` and writes frames.csv, frames.h5 and summary.json, staged and renamed together
/// (trial_results.hpp, write_trial_outputs).
void write_trial_outputs(const TrialOutputs& outputs, const std::filesystem::path& dir);

}  // namespace vibrissa::io
