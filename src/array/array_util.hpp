#pragma once
// Small helpers private to the array layer: error messages, unit conversion, CSV cells.
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::array {

/// A value that does not exist (the contact point of a free frame): NaN in HDF5, an empty CSV cell.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

[[noreturn]] inline void fail(const std::string& what) { throw std::invalid_argument(what); }

inline std::string fmt(double v) { return format_value(v); }

/// Degrees to radians.
constexpr double deg(double degrees) { return degrees * std::numbers::pi / 180.0; }
/// Radians to degrees.
constexpr double to_deg(double radians) { return radians * 180.0 / std::numbers::pi; }

/// A number from text; throws naming `field` (NaN and inf are refused).
inline double parse_number(const std::string& text, const std::string& field) {
  std::size_t end = text.size();
  while (end > 0 && std::isspace(static_cast<unsigned char>(text[end - 1]))) --end;
  const std::optional<double> v = parse_decimal(std::string_view(text).substr(0, end));
  if (!v) fail(field + " must be a number, got '" + quote_text(text) + "'");
  if (!std::isfinite(*v)) fail(field + " must be finite, got " + quote_text(text));
  return *v;
}

/// Cells of one CSV line (no quoting; surrounding blanks trimmed).
inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t");
    const auto e = cell.find_last_not_of(" \t");
    cells.push_back(b == std::string::npos ? std::string() : cell.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

}  // namespace vibrissa::array
