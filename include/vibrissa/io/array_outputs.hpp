#pragma once
// Files written by an array simulation (docs/array.md, "Outputs"): HDF5 laid out [pitch][whisker][frame],
// an optional long-format CSV, a JSON summary, a per-pitch summary table and the configuration as run.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "vibrissa/array/simulation.hpp"
#include "vibrissa/io/labelled_data.hpp"

namespace vibrissa::io {

struct ArrayOutputOptions {
  bool csv = false;  ///< also write array.csv (one row per pitch, whisker and frame; units in the column names)
};

/// Everything `vibrissa array` writes into `dir` (created if missing): array.h5, array.csv (if asked),
/// pitch_summary.csv (one row per pitch), config.json (`config_json`, the configuration as run) and
/// summary.json. All are written to temporaries first and renamed into place together, so a failed or
/// killed run leaves the older outputs untouched. Figures of an older run (io/figure_files.hpp) are removed
/// with them: figures, if wanted, are drawn afterwards from the new array.h5.
void write_array_outputs(const array::ArrayResult& result, const array::SimulationConfig& config,
                         const nlohmann::json& config_json, const std::filesystem::path& dir,
                         const ArrayOutputOptions& options = {});

/// The variables of array.h5 (docs/array.md, "Outputs"): dimensions pitch, whisker, time, component (group
/// render: frame, node, edge, end), coordinates, units, descriptions. Borrows `result`.
LabelledData array_data(const array::ArrayResult& result, const array::SimulationConfig& config);

nlohmann::json array_summary_json(const array::ArrayResult& result, const array::SimulationConfig& config);
/// Shape of dataset `name` in an HDF5 file (for checking outputs); throws std::runtime_error if absent.
std::vector<std::size_t> h5_dataset_shape(const std::filesystem::path& path, const std::string& name);

}  // namespace vibrissa::io
