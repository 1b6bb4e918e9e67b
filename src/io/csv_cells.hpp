#pragma once
// Cells of the library's CSV readers (private to the library): trial files (src/io/trial_csv.cpp) and the
// text track files of src/recon (plain, DeepLabCut, Janelia whisker1). Each reader words its own errors.
// And the numeric cell of the CSV outputs (array.csv, pitch_summary.csv, frames.csv): exact, SI.
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
/// The cell of a number in a CSV output: the shortest text that reads back as exactly `value`; empty for NaN
/// (a value that does not exist).
std::string cell(double value);

}  // namespace vibrissa::io::csv
