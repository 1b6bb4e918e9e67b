#include "vibrissa/io/trial_outputs.hpp"

namespace vibrissa::io {

TrialOutputs trial_outputs(const trial::TrialRun& run) {
  TrialOutputs out;
  out.table = result_table(run.result, run.analysis);
  out.summary = summary_json(run.result, run.analysis);
  out.summary["pipeline_seconds"] = run.pipeline_seconds;
  nlohmann::json dropped = nlohmann::json::array();
  for (const trial::DroppedFrame& d : run.dropped_frames)
    dropped.push_back({{"frame", d.frame}, {"time", d.time}, {"reason", d.reason}});
  out.summary["dropped_frames"] = dropped;  // impossible samples, dropped before filtering (docs/trials.md)
  return out;
}

void write_trial_outputs(const TrialOutputs& outputs, const std::filesystem::path& dir) {
  write_trial_outputs(outputs.table, outputs.summary, dir);
}

}  // namespace vibrissa::io
