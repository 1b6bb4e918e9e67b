#include "text_cells.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>

namespace vibrissa::recon {

std::ifstream open_input(const std::string& path, const std::string& what, std::ios::openmode mode) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw std::invalid_argument(path + ": is a directory, not a " + what);
  std::ifstream in(path, mode);
  if (!in) throw std::invalid_argument(path + ": cannot open " + what);
  return in;
}

std::string cell_message(const std::string& path, std::size_t line, const std::string& field,
                         const std::string& message) {
  std::string s = path + ": ";
  if (line > 0) s += "line " + std::to_string(line) + ", ";
  if (!field.empty()) s += "field '" + field + "': ";
  return s + message;
}

double parse_cell(const std::string& cell, const std::string& path, std::size_t line, const std::string& field) {
  const std::optional<double> v = io::csv::number(cell);
  if (!v || std::isinf(*v))
    throw std::invalid_argument(cell_message(path, line, field, "'" + cell + "' is not a finite number"));
  return *v;
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
