#include "vibrissa/io/trial_outputs.hpp"

namespace vibrissa::io {

TrialOutputs trial_outputs(const trial::TrialRun& run) {
  TrialOutputs out;
  out.table = result_table(run.result, run.analysis);
  out.summary = summary_json(run.result, run.analysis);
  out.summary["pipeline_seconds"] = run.pipeline_seconds;
  return out;
}

void write_trial_outputs(const TrialOutputs& outputs, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  write_result_table_csv(outputs.table, (dir / "frames.csv").string());
  write_result_table_h5(outputs.table, (dir / "frames.h5").string());
  write_json(outputs.summary, (dir / "summary.json").string());
}

}  // namespace vibrissa::io
