#pragma once
// Cells of the text track files (private to src/recon): numbers and indices with errors naming file, line
// and field. Splitting and trimming are the library's CSV cells (src/io/csv_cells.hpp).
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "../io/csv_cells.hpp"

namespace vibrissa::recon {

using io::csv::trim;
/// Comma-separated cells, each trimmed.
inline std::vector<std::string> split_cells(const std::string& line) { return io::csv::split(line); }
/// "file: line L, field 'F': message" (L = 0 omits the line).
std::string cell_message(const std::string& path, std::size_t line, const std::string& field,
                         const std::string& message);
/// A number; empty and "nan" give NaN; anything else that is not a number throws naming file, line, field.
double parse_cell(const std::string& cell, const std::string& path, std::size_t line, const std::string& field);
/// The input file at `path`, open for reading; throws "path: is a directory, not a WHAT" or "path: cannot open
/// WHAT" (a directory opens as an empty stream on Linux, which the readers took for an empty file).
std::ifstream open_input(const std::string& path, const std::string& what,
                         std::ios::openmode mode = std::ios::in);
/// A non-negative integer (e.g. a frame index).
std::int64_t parse_index(const std::string& cell, const std::string& path, std::size_t line, const std::string& field);

}  // namespace vibrissa::recon
