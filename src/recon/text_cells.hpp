#pragma once
// Cells of the text track files (private to src/recon): splitting, trimming, numbers with located errors.
#include <cstdint>
#include <string>
#include <vector>

namespace vibrissa::recon {

std::string trim(const std::string& s);
/// Comma-separated cells, each trimmed.
std::vector<std::string> split_cells(const std::string& line);
/// "file: line L, field 'F': message" (L = 0 omits the line).
std::string cell_message(const std::string& path, std::size_t line, const std::string& field,
                         const std::string& message);
/// A number; empty and "nan" give NaN; anything else that is not a number throws naming file, line, field.
double parse_cell(const std::string& cell, const std::string& path, std::size_t line, const std::string& field);
/// A non-negative integer (e.g. a frame index).
std::int64_t parse_index(const std::string& cell, const std::string& path, std::size_t line, const std::string& field);

}  // namespace vibrissa::recon
