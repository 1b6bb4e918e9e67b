#pragma once
// Cells of the library's CSV readers (private to the library): trial files (src/io/trial_csv.cpp) and the
// text track files of src/recon (plain, DeepLabCut, Janelia whisker1). Each reader words its own errors.
#include <optional>
#include <string>
#include <vector>

namespace vibrissa::io::csv {

/// Without leading and trailing spaces, tabs, CR and LF.
std::string trim(const std::string& s);
/// The cells of one line, each trimmed; a trailing separator gives an empty last cell.
std::vector<std::string> split(const std::string& line, char sep = ',');
/// A numeric cell: empty, "nan", "NaN" and "NAN" are NaN; otherwise a decimal number (no hex, no trailing
/// text; "inf" parses and is left to the caller); nullopt if the cell is not a number.
std::optional<double> number(const std::string& cell);

}  // namespace vibrissa::io::csv
