#pragma once
// Writing JSON files: two-space indent and a final newline, numbers as nlohmann-json prints them (doubles
// round-trip exactly), bytes of a string that are not UTF-8 written as U+FFFD (a text never fails to print).
// Atomic (io/atomic_file.hpp).
#include <filesystem>
#include <iosfwd>
#include <string_view>

#include <nlohmann/json.hpp>

#include "vibrissa/io/output_folder.hpp"

namespace vibrissa::io {

/// The file's text: `json` as described above.
void print_json_file(const nlohmann::json& json, std::ostream& out);
/// Compact one-line text (JSON Lines), non-UTF-8 bytes as U+FFFD.
std::string compact_json(const nlohmann::json& json);
void write_json_file(const std::filesystem::path& path, const nlohmann::json& json);
/// The same file, staged among the other outputs of a run in one folder.
void stage_json_file(OutputFolder& folder, std::string_view name, const nlohmann::json& json);

}  // namespace vibrissa::io
