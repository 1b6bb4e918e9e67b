#include "vibrissa/io/json_input.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::io {

using nlohmann::json;

nlohmann::json parse_json_text(std::string_view text, const std::string& source, bool allow_comments) {
  // nlohmann stops at a NUL byte as if the input ended there; JSON text never holds a raw NUL.
  if (const auto nul = text.find('\0'); nul != std::string_view::npos)
    invalid_input(source + ": not valid JSON: NUL byte at offset " + std::to_string(nul));
  // The parser itself is iterative; depth and duplicate keys are checked as it goes, before any recursive
  // operation (dump, copy, comparison) could see a deep document.
  std::vector<std::set<std::string>> keys;  // one entry per open container (empty for arrays)
  const json::parser_callback_t check = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        keys.emplace_back();
        if (keys.size() > static_cast<std::size_t>(limits::max_json_depth))
          invalid_input(source + ": JSON nested deeper than " + std::to_string(limits::max_json_depth) + " levels");
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end: keys.pop_back(); break;
      case json::parse_event_t::key:
        if (!keys.back().insert(parsed.get<std::string>()).second)
          invalid_input(source + ": duplicate key \"" + quote_text(parsed.get<std::string>()) +
                        "\" in one JSON object (the earlier value would be ignored)");
        break;
      case json::parse_event_t::value: break;
    }
    return true;
  };
  try {
    return json::parse(text.begin(), text.end(), check, true, allow_comments);
  } catch (const json::exception& e) {
    if (e.id != 406) invalid_input(source + ": not valid JSON: " + quote_text(e.what()));
    // "number overflow parsing '1e400'" (id 406) carries no position: locate the number in the text.
    const std::string what = e.what();
    const auto quote_start = what.find("parsing '");
    const auto quote_end = quote_start == std::string::npos ? quote_start : what.find('\'', quote_start + 9);
    std::string where;
    if (quote_end != std::string::npos) {
      const std::string token = what.substr(quote_start + 9, quote_end - quote_start - 9);
      if (const auto at = text.find(token); !token.empty() && at != std::string_view::npos) {
        const auto line_start = text.rfind('\n', at);
        const std::size_t line = 1 + std::size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n'));
        const std::size_t column = at - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
        where = "line " + std::to_string(line) + ", column " + std::to_string(column) + ": ";
      }
      invalid_input(source + ": not valid JSON: " + where + "the number " + quote_text(token) +
                    " is beyond the range of a double (about 1.8e308)");
    }
    invalid_input(source + ": not valid JSON: " + quote_text(what));
  }
}

nlohmann::json read_json_input(const std::filesystem::path& path, bool allow_comments) {
  std::ifstream in(path, std::ios::binary);
  if (!in) invalid_input("cannot open '" + path.string() + "'");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) require_at_most(size, limits::max_json_file_bytes, "'" + path.string() + "': file size in bytes");
  std::string text;
  text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  require_at_most(text.size(), limits::max_json_file_bytes, "'" + path.string() + "': file size in bytes");
  return parse_json_text(text, "'" + path.string() + "'", allow_comments);
}

std::string describe(const nlohmann::json& j) {
  return quote_text(j.dump(-1, ' ', false, json::error_handler_t::replace));
}

double json_number(const nlohmann::json& j, std::string_view field) {
  if (!j.is_number()) invalid_input(std::string(field) + " must be a number, got " + describe(j));
  const double v = j.get<double>();
  require_finite(v, field);
  return v;
}

int json_integer(const nlohmann::json& j, std::string_view field, int lo, int hi) {
  if (!j.is_number()) invalid_input(std::string(field) + " must be an integer, got " + describe(j));
  return require_integer(j.get<double>(), lo, hi, field);
}

bool json_bool(const nlohmann::json& j, std::string_view field) {
  if (!j.is_boolean()) invalid_input(std::string(field) + " must be true or false, got " + describe(j));
  return j.get<bool>();
}

std::string json_string(const nlohmann::json& j, std::string_view field) {
  if (!j.is_string()) invalid_input(std::string(field) + " must be a string, got " + describe(j));
  return j.get<std::string>();
}

Eigen::Vector3d json_vec3(const nlohmann::json& j, std::string_view field) {
  if (!j.is_array() || j.size() != 3) invalid_input(std::string(field) + " must be an array of 3 numbers, got " + describe(j));
  Eigen::Vector3d v;
  for (std::size_t i = 0; i < 3; ++i) v[static_cast<Eigen::Index>(i)] = json_number(j[i], std::string(field) + "[" + std::to_string(i) + "]");
  return v;
}

std::vector<double> json_numbers(const nlohmann::json& j, std::string_view field, std::size_t max_size) {
  if (!j.is_array()) invalid_input(std::string(field) + " must be an array of numbers, got " + describe(j));
  require_at_most(j.size(), max_size, std::string(field) + ": number of values");
  std::vector<double> out;
  out.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i) out.push_back(json_number(j[i], std::string(field) + "[" + std::to_string(i) + "]"));
  return out;
}

std::filesystem::path resolve_input_path(const std::filesystem::path& name, const std::filesystem::path& base_dir) {
  if (name.empty() || name.is_absolute()) return name;
  return std::filesystem::absolute(base_dir.empty() ? name : base_dir / name).lexically_normal();
}

nlohmann::json resolve_input_paths(nlohmann::json input, const std::filesystem::path& base_dir) {
  if (!input.is_object()) return input;
  auto resolve = [&](nlohmann::json& holder, const char* key) {
    if (holder.is_object() && holder.contains(key) && holder[key].is_string())
      holder[key] = resolve_input_path(holder[key].get<std::string>(), base_dir).string();
  };
  auto is_mesh = [](const nlohmann::json& o) {
    return o.is_object() && o.contains("type") && o["type"].is_string() && o["type"].get<std::string>() == "mesh";
  };
  if (input.contains("morphology") && input["morphology"].is_object()) {
    nlohmann::json& m = input["morphology"];
    if (m.contains("source") && m["source"].is_string()) {
      const std::string source = m["source"].get<std::string>();
      if (source.size() > 4 && (source.ends_with(".csv") || source.ends_with(".json"))) resolve(m, "source");
    }
  }
  if (input.contains("objects") && input["objects"].is_array())
    for (nlohmann::json& o : input["objects"])
      if (is_mesh(o)) resolve(o, "file");
  if (input.contains("load") && input["load"].is_object() && input["load"].contains("object") &&
      is_mesh(input["load"]["object"]))
    resolve(input["load"]["object"], "file");
  return input;
}

}  // namespace vibrissa::io

