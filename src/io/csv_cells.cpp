#include "csv_cells.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::io::csv {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream is(line);
  while (std::getline(is, cell, sep)) out.push_back(trim(cell));
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

std::optional<double> number(const std::string& cell) {
  if (cell.empty() || cell == "nan" || cell == "NaN" || cell == "NAN") return std::numeric_limits<double>::quiet_NaN();
  return parse_decimal(cell);
}

std::string cell(double value) { return std::isnan(value) ? std::string() : format_value(value); }

}  // namespace vibrissa::io::csv
