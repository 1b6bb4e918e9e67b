#pragma once
// Output of `vibrissa trial` (docs/trials.md, "Outputs"): the per-frame table as CSV and HDF5 (same
// columns), and summary.json with every number of the analyses. All writes are atomic (io/atomic_file.hpp).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "vibrissa/trial/analysis.hpp"

namespace vibrissa::io {

/// One numeric column of the table and its units as frames.h5 states them ("m", "N m", "deg", "1", ...).
struct NumericColumn {
  std::string name;
  std::vector<double> values;
  std::string units;  ///< SI unless the name says otherwise (FD_deg: "deg")
};

struct ResultTable {
  std::vector<NumericColumn> numeric;
  /// Solver status columns by name: Status names or "not_in_contact" (text in CSV and Python, codes in frames.h5).
  std::vector<std::pair<std::string, std::vector<std::string>>> text;
};

/// Columns: time, contact, period, period_edge, theta, phi, zeta (filtered, used), then per mode
/// (prefix cp_, edge_, fric_): status, contact_x/y/z, height, s_applied, Fx/Fy/Fz_world, Mx/My/Mz_world,
/// Fx/Fy/Fz_B, Mx/My/Mz_B, FT, MB, FD_deg, MD_deg, normal_force, friction_force, shape_error, iterations;
/// then mu, mu_outlier, z_error, z_error_eq6, z_error_eq7, kinematic_height, tracked_height.
ResultTable result_table(const trial::PipelineResult& result, const trial::TrialAnalysis& analysis);

nlohmann::json summary_json(const trial::PipelineResult& result, const trial::TrialAnalysis& analysis);

/// Everything `vibrissa trial` writes into `dir` (created if missing): frames.csv and frames.h5 (the table)
/// and summary.json, renamed into place together once all are written (summary.json last: its presence marks
/// a finished run). The figures/ folder of an older run is removed: figures, if wanted, are drawn afterwards
/// from the new files, so outputs never mix runs.
void write_trial_outputs(const ResultTable& table, const nlohmann::json& summary, const std::filesystem::path& dir);

}  // namespace vibrissa::io
