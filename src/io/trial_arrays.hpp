#pragma once
// The array layout shared by the HDF5 and MATLAB trial files (docs/trials.md): named numeric arrays
// (row-major here, whatever the file's own order), unit strings and metadata numbers. Private to io/.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vibrissa/trial/format.hpp"

namespace vibrissa::io {

struct NamedArray {
  std::vector<std::size_t> dims;  ///< row-major dimensions
  std::vector<double> data;
  std::string units;  ///< what a writer states ("m", "rad", "s", "1", "px"); readers leave it empty
};

/// Lookup functions of one open file; each returns nullopt when the name is absent.
struct ArrayReader {
  std::string source;
  std::function<std::optional<NamedArray>(const std::string&)> array;
  std::function<std::optional<std::string>(const std::string&)> text;
  std::function<std::optional<double>(const std::string&)> number;
};

/// Names of the arrays a trial file may hold (others are errors: typos must not pass silently).
inline constexpr const char* trial_array_names[] = {
    "time",  "base",       "theta", "phi",           "zeta",           "contact",   "contact_point",
    "shape", "rest_shape", "edges", "reconstructed", "reprojection_px", "likelihood"};

/// Builds and validates a trial from named arrays; errors name the file, row and array.
trial::Trial assemble_trial(const ArrayReader& reader);

/// Everything a writer must store, in SI units (units strings "m", "rad", "s").
struct TrialArrays {
  std::vector<std::pair<std::string, NamedArray>> arrays;
  std::vector<std::pair<std::string, std::string>> texts;
  std::vector<std::pair<std::string, double>> numbers;
};
TrialArrays disassemble_trial(const trial::Trial& trial);

}  // namespace vibrissa::io
