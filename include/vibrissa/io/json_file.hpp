#pragma once
// Writing JSON files: two-space indent and a final newline, numbers as nlohmann-json prints them (doubles
// round-trip exactly). Atomic (io/atomic_file.hpp).
#include <filesystem>

#include <nlohmann/json.hpp>

#include "vibrissa/io/atomic_file.hpp"

namespace vibrissa::io {

void write_json_file(const std::filesystem::path& path, const nlohmann::json& json);
/// The same file, staged among other outputs of a run.
void stage_json_file(StagedFiles& files, const std::filesystem::path& path, const nlohmann::json& json);

}  // namespace vibrissa::io
