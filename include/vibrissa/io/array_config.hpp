#pragma once
// The JSON configuration of an array simulation (docs/array.md, "Config"). Every length in the file is in
// mm, every angle in degrees, as the key names say; inside, everything is SI. Unknown keys are errors.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "vibrissa/array/simulation.hpp"

namespace vibrissa::io {

/// The built-in default: right side of the Towal array, one protraction (half a cycle at 8 Hz) against a
/// vertical peg in front of the face.
nlohmann::json default_array_config_json();

/// Builds and validates a configuration; errors name the offending key, e.g. "objects[1].length_mm".
/// Relative file names (a morphology table) are resolved against `base_dir`.
array::SimulationConfig array_config_from_json(const nlohmann::json& config,
                                               const std::filesystem::path& base_dir = ".");
/// Reads a JSON file (comments allowed) and calls array_config_from_json.
array::SimulationConfig load_array_config(const std::filesystem::path& path);
/// A whisk from {"amplitude_deg", "frequency_Hz", "set_point_deg", "phase_deg", "series": {"time_s",
/// "dtheta_deg"}} (keys missing: `base`'s values), validated; errors name `where`. Other keys are the caller's.
array::Protraction protraction_from_json(const nlohmann::json& j, const std::string& where,
                                         const array::Protraction& base = {});
/// Reads a JSON file (comments allowed); errors name the file.
nlohmann::json read_array_config_json(const std::filesystem::path& path);

}  // namespace vibrissa::io
