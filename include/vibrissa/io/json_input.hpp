#pragma once
// Reading JSON input (case files, array configs, JSON morphology tables, text from Python) safely:
// bounded size and nesting depth, no duplicate keys, nothing after the value, and typed access whose
// errors name the field path and the value (never a raw nlohmann message). docs/formats.md, "Limits".
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "vibrissa/core/limits.hpp"

namespace vibrissa::io {

/// Parses one JSON document. Throws std::invalid_argument naming `source` for invalid JSON, nesting deeper
/// than limits::max_json_depth (checked before any recursion), a key repeated in one object, or any byte
/// (a NUL included) after the value. `allow_comments`: accept // and /* */ comments.
nlohmann::json parse_json_text(std::string_view text, const std::string& source, bool allow_comments = false);
/// Reads a file of at most limits::max_json_file_bytes and parses it with parse_json_text.
nlohmann::json read_json_input(const std::filesystem::path& path, bool allow_comments = false);

/// A value as it appears in a message: compact JSON text, cut to limits::max_quoted_chars.
std::string describe(const nlohmann::json& j);

// Typed access. Every function throws std::invalid_argument "<field> must be ..., got <value>".
/// A finite number.
double json_number(const nlohmann::json& j, std::string_view field);
/// An integral number in [lo, hi] (1 and 1.0 are accepted, 2.7 and 1e300 are not).
int json_integer(const nlohmann::json& j, std::string_view field, int lo, int hi);
bool json_bool(const nlohmann::json& j, std::string_view field);
std::string json_string(const nlohmann::json& j, std::string_view field);
/// An array of exactly 3 finite numbers.
Eigen::Vector3d json_vec3(const nlohmann::json& j, std::string_view field);
/// An array of at most `max_size` finite numbers.
std::vector<double> json_numbers(const nlohmann::json& j, std::string_view field,
                                 std::size_t max_size = limits::max_list_length);

}  // namespace vibrissa::io
