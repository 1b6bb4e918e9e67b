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

/// The one rule for files an input names (docs/formats.md, "Paths"): a relative name is relative to the
/// folder of the file that names it (`base_dir`), never to the current directory. Returns `input` with these
/// names made absolute (lexically normal): `morphology.source` when it is a table (.csv, .json), the `file` of
/// every mesh in `objects` (array configs) and of `load.object` (cases). Other values are left as they are.
/// Readers call it on the JSON of a file before building from it, and outputs that copy an input (an
/// array's config.json) keep the absolute names, so the copy means the same from any folder.
nlohmann::json resolve_input_paths(nlohmann::json input, const std::filesystem::path& base_dir);
/// One name under that rule: `name` itself when absolute, else absolute(base_dir / name), lexically normal.
std::filesystem::path resolve_input_path(const std::filesystem::path& name, const std::filesystem::path& base_dir);

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
