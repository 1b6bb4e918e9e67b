#pragma once
// Output of `vibrissa trial` (docs/trials.md, "Outputs"): the per-frame table as CSV and HDF5 (same
// columns), and summary.json with every number of the analyses. All writes are atomic (io/atomic_file.hpp).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "vibrissa/io/labelled_data.hpp"
#include "vibrissa/trial/analysis.hpp"

namespace vibrissa::io {

/// One numeric column of the table, its units as frames.h5 states them ("m", "N m", "rad", "1", ...; SI, as
/// every output: docs/formats.md, "Units") and what it is (frames.h5's long_name).
struct NumericColumn {
  std::string name;
  std::vector<double> values;
  std::string units;
  std::string long_name;
};

/// A solver status column: Status names or "not_in_contact" (text in CSV and Python, codes in frames.h5).
struct TextColumn {
  std::string name;
  std::vector<std::string> values;
  std::string long_name;
};

struct ResultTable {
  std::vector<NumericColumn> numeric;
  std::vector<TextColumn> text;
};

/// Columns: time, contact, period, period_edge, theta, phi, zeta (filtered, used), then per mode
/// (prefix cp_, edge_, fric_): status, contact_x/y/z, height, s_applied, Fx/Fy/Fz_world, Mx/My/Mz_world,
/// Fx/Fy/Fz_B, Mx/My/Mz_B, FT, MB, FD, MD, normal_force, friction_force, shape_error, iterations;
/// then mu, mu_outlier, z_error, z_error_eq6, z_error_eq7, kinematic_height, tracked_height.
ResultTable result_table(const trial::PipelineResult& result, const trial::TrialAnalysis& analysis);

nlohmann::json summary_json(const trial::PipelineResult& result, const trial::TrialAnalysis& analysis);

/// The variables of frames.h5 (docs/trials.md, "Outputs"): every column over dimension time (its coordinate the
/// time column), status columns as int8 codes with their code table. Borrows `table`.
LabelledData trial_results_data(const ResultTable& table);

/// Everything `vibrissa trial` writes into `dir` (created if missing): frames.csv and frames.h5 (the table)
/// and summary.json, renamed into place together once all are written (summary.json last: its presence marks
/// a finished run). The figures/ folder of an older run is removed: figures, if wanted, are drawn afterwards
/// from the new files, so outputs never mix runs.
void write_trial_outputs(const ResultTable& table, const nlohmann::json& summary, const std::filesystem::path& dir);

}  // namespace vibrissa::io
