#include "vibrissa/io/json_file.hpp"

#include <ostream>

namespace vibrissa::io {

void stage_json_file(StagedFiles& files, const std::filesystem::path& path, const nlohmann::json& json) {
  files.stage_text(path, [&](std::ostream& out) { out << json.dump(2) << "\n"; });
}

void write_json_file(const std::filesystem::path& path, const nlohmann::json& json) {
  StagedFiles files;
  stage_json_file(files, path, json);
  files.commit();
}

}  // namespace vibrissa::io
