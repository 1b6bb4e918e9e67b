// Reading user whisker-array tables (CSV or JSON); see io/morphology_table.hpp.
#include "vibrissa/io/morphology_table.hpp"

#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "vibrissa/io/json_input.hpp"
#include "../array/array_util.hpp"  // the array layer's message, unit and CSV-cell helpers

namespace vibrissa::io {

using array::Morphology;
using array::WhiskerSpec;
using array::deg;
using array::fail;
using array::parse_number;
using array::split_csv_line;

namespace {

constexpr double mm = 1e-3;

WhiskerSpec spec_from_fields(const std::map<std::string, std::string>& f, const std::string& where) {
  auto get = [&](const std::string& key) -> const std::string& {
    const auto it = f.find(key);
    if (it == f.end() || it->second.empty()) fail(where + "." + key + " is missing");
    return it->second;
  };
  auto number = [&](const std::string& key) { return parse_number(get(key), where + "." + key); };
  auto optional_number = [&](const std::string& key, double fallback) {
    const auto it = f.find(key);
    return (it == f.end() || it->second.empty()) ? fallback : parse_number(it->second, where + "." + key);
  };
  WhiskerSpec s;
  s.name = get("name");
  array::parse_whisker_name(s.name, s.row, s.column, where + ".name");
  const array::Side side =
      f.count("side") ? array::side_from_string(get("side"), (where + ".side").c_str()) : array::Side::right;
  s.arc_length = number("S_mm") * mm;
  s.curvature = number("A_per_mm") / mm;
  s.theta_rest = deg(number("theta_deg"));
  s.phi_rest = deg(number("phi_deg"));
  s.zeta_rest = deg(number("zeta_deg"));
  s.p_H_base = Eigen::Vector3d(number("base_x_mm"), number("base_y_mm"), number("base_z_mm")) * mm;
  const double d_mm = array::belli_base_diameter_mm(s.arc_length / mm, s.row, std::max(s.column, 1));
  s.base_radius = optional_number("base_radius_um", 0.5 * d_mm * 1e3) * 1e-6;
  s.taper_ratio = optional_number("taper_ratio", 15.0);
  s.youngs_modulus = optional_number("youngs_modulus_GPa", 3.3) * 1e9;
  s.poisson_ratio = optional_number("poisson_ratio", 0.38);
  s = array::on_side(s, side);
  try {
    array::validate(s);
  } catch (const std::invalid_argument& e) {
    fail(where + ": " + e.what());
  }
  return s;
}

void check_unique(const Morphology& m) {
  for (std::size_t i = 0; i < m.whiskers.size(); ++i)
    for (std::size_t j = i + 1; j < m.whiskers.size(); ++j)
      if (m.whiskers[i].label() == m.whiskers[j].label())
        fail("morphology: whisker " + m.whiskers[i].label() + " appears twice in " + m.source);
}

}  // namespace

Morphology morphology_from_csv(std::istream& in, const std::string& source) {
  Morphology m;
  m.source = source;
  std::string line;
  std::vector<std::string> header;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    const auto cells = split_csv_line(line);
    if (header.empty()) {
      header = cells;
      continue;
    }
    if (cells.size() != header.size())
      fail(source + " line " + std::to_string(line_no) + ": expected " + std::to_string(header.size()) +
           " columns, got " + std::to_string(cells.size()));
    require_at_most(m.whiskers.size() + 1, limits::max_whiskers, source + ": number of whiskers");
    std::map<std::string, std::string> fields;
    for (std::size_t i = 0; i < cells.size(); ++i) fields[header[i]] = cells[i];
    m.whiskers.push_back(spec_from_fields(fields, source + " line " + std::to_string(line_no)));
  }
  if (m.whiskers.empty()) fail(source + ": no whiskers in the table");
  check_unique(m);
  return m;
}

Morphology morphology_from_json(const nlohmann::json& table, const std::string& source) {
  const nlohmann::json& rows = table.is_object() && table.contains("whiskers") ? table.at("whiskers") : table;
  if (!rows.is_array()) fail(source + ": expected an array of whisker rows");
  require_at_most(rows.size(), limits::max_whiskers, source + ": number of whiskers");
  Morphology m;
  m.source = source;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string where = source + "[" + std::to_string(i) + "]";
    if (!rows[i].is_object()) fail(where + " must be an object");
    std::map<std::string, std::string> fields;
    for (const auto& [key, value] : rows[i].items())
      fields[key] = value.is_string() ? value.get<std::string>() : describe(value);
    m.whiskers.push_back(spec_from_fields(fields, where));
  }
  if (m.whiskers.empty()) fail(source + ": no whiskers in the table");
  check_unique(m);
  return m;
}

Morphology read_morphology_table(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext != ".csv" && ext != ".json")
    fail("morphology.source: table '" + path.string() + "' must end in .csv or .json");
  if (ext == ".json") {
    try {
      return morphology_from_json(read_json_input(path), path.string());
    } catch (const std::invalid_argument& e) {
      fail(std::string("morphology.source: ") + e.what());
    }
  }
  std::ifstream in(path);
  if (!in) fail("morphology.source: cannot open '" + path.string() + "'");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) require_at_most(size, limits::max_csv_file_bytes, "morphology.source: '" + path.string() + "': file size in bytes");
  return morphology_from_csv(in, path.string());
}

}  // namespace vibrissa::io
