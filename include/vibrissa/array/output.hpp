#pragma once
// Files written by an array simulation (docs/array.md, "Outputs"): HDF5 laid out [pitch][whisker][frame],
// an optional long-format CSV, a JSON summary and a per-pitch summary table.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "vibrissa/array/simulation.hpp"

namespace vibrissa::array {

void write_array_h5(const ArrayResult& result, const SimulationConfig& config, const std::filesystem::path& path);
/// One row per (pitch, whisker, frame); units in the column names.
void write_array_csv(const ArrayResult& result, const std::filesystem::path& path);
/// One row per pitch (the head-pitch sweep table).
void write_pitch_summary_csv(const ArrayResult& result, const std::filesystem::path& path);
/// Shape of dataset `name` in an HDF5 file (for checking outputs); throws std::runtime_error if absent.
std::vector<std::size_t> h5_dataset_shape(const std::filesystem::path& path, const std::string& name);
nlohmann::json summary_json(const ArrayResult& result, const SimulationConfig& config);

}  // namespace vibrissa::array
