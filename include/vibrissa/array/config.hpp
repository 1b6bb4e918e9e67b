#pragma once
// The JSON configuration of an array simulation (docs/array.md, "Config"). Every length in the file is in
// mm, every angle in degrees, as the key names say; inside, everything is SI. Unknown keys are errors.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "vibrissa/array/simulation.hpp"

namespace vibrissa::array {

/// The built-in default: right side of the Towal array, one protraction (half a cycle at 8 Hz) against a
/// vertical peg in front of the face.
nlohmann::json default_config_json();

/// Builds and validates a configuration; errors name the offending key, e.g. "objects[1].length_mm".
/// Relative file names (a morphology table) are resolved against `base_dir`.
SimulationConfig config_from_json(const nlohmann::json& config, const std::filesystem::path& base_dir = ".");
/// Reads a JSON file (comments allowed) and calls config_from_json.
SimulationConfig load_config(const std::filesystem::path& path);
nlohmann::json read_config_json(const std::filesystem::path& path);

}  // namespace vibrissa::array
