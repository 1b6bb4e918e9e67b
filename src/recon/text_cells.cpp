#include "text_cells.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace vibrissa::recon {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream is(line);
  while (std::getline(is, cell, ',')) out.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

std::string cell_message(const std::string& path, std::size_t line, const std::string& field,
                         const std::string& message) {
  std::string s = path + ": ";
  if (line > 0) s += "line " + std::to_string(line) + ", ";
  if (!field.empty()) s += "field '" + field + "': ";
  return s + message;
}

double parse_cell(const std::string& cell, const std::string& path, std::size_t line, const std::string& field) {
  if (cell.empty() || cell == "nan" || cell == "NaN" || cell == "NAN") return std::numeric_limits<double>::quiet_NaN();
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(cell, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != cell.size() || std::isinf(v))
    throw std::invalid_argument(cell_message(path, line, field, "'" + cell + "' is not a finite number"));
  return v;
}

std::int64_t parse_index(const std::string& cell, const std::string& path, std::size_t line, const std::string& field) {
  std::size_t used = 0;
  long long v = -1;
  try {
    v = std::stoll(cell, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != cell.size() || cell.empty() || v < 0)
    throw std::invalid_argument(cell_message(path, line, field, "'" + cell + "' is not a non-negative integer"));
  return v;
}

}  // namespace vibrissa::recon
