#include "vibrissa/io/json_file.hpp"

#include <ostream>

namespace vibrissa::io {

void print_json_file(const nlohmann::json& json, std::ostream& out) {
  out << json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

std::string compact_json(const nlohmann::json& json) {
  return json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void write_json_file(const std::filesystem::path& path, const nlohmann::json& json) {
  write_text_atomically(path, [&](std::ostream& out) { print_json_file(json, out); });
}

void stage_json_file(OutputFolder& folder, std::string_view name, const nlohmann::json& json) {
  folder.stage_text(name, [&](std::ostream& out) { print_json_file(json, out); });
}

}  // namespace vibrissa::io
